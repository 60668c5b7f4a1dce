#include "tools/sweep_command.h"

#include <unistd.h>

#include <cstdio>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "deb/budget/sweep.h"
#include "deb/budget/sweep_ranking.h"
#include "deb/core/error.h"
#include "deb/core/output_dir.h"
#ifdef DEB_MPI
#include "deb/distributed/mpi_queue.h"
#endif
#include "deb/load/sweep_yaml.h"
#include "deb/report/compare/sweep_directory.h"
#include "deb/report/compare/sweep_documents.h"
#include "deb/report/compare/sweep_plots.h"
#include "deb/report/figure/plot.h"
#include "deb/report/budget/file_digest.h"
#include "deb/results/study_part.h"
#include "deb/version.h"
#include "tools/budget_overrides_option.h"
#include "tools/mpi_timeout_option.h"
#include "tools/shard_option.h"

namespace deb::tools {

struct SweepCommand::Options {
  std::string budget_file;
  std::vector<BudgetOverride> overrides;  // --set
  std::string out_dir;
  int threads = 0;
  bool quiet = false;
  bool force = false;  // --force: replace an output directory deb did not write
  bool plots = true;
  std::string shard;  // --shard K/N
  double timeout_s = 0.0;  // --timeout, under mpirun
};

namespace {

// The best three variants (RankVariants), each with its settings and every
// output's RMS and status.
void PrintTopThree(const SweepSpec& spec, const std::vector<BudgetResult>& results) {
  const auto rows = spec.Variants();
  const auto ranked = RankVariants(results);
  std::printf("best variants (fewest failing outputs, then lowest worst RMS / requirement):\n");
  for (std::size_t i = 0; i < ranked.size() && i < 3; ++i) {
    const VariantScore& s = ranked[i];
    std::printf("  %zu. %s: %d output(s) fail", i + 1, report::VariantSettings(spec, rows[s.variant]).c_str(),
                s.failing);
    if (s.worst_utilisation > 0.0) std::printf(", worst RMS / requirement %.3g", s.worst_utilisation);
    std::printf("\n    ");
    const std::vector<OutputResult>& outputs = results[s.variant].outputs;
    for (std::size_t o = 0; o < outputs.size(); ++o)
      std::printf("%s %s; ", outputs[o].name.c_str(),
                  report::VariantCell(outputs[o], report::LargestVariance(results, o)).c_str());
    std::printf("\n");
  }
}

}  // namespace

std::string SweepDigest(const std::string& budget_text) {
  return report::Sha256(budget_text + "\n--- deb " + DEB_VERSION + " sweep\n");
}

void WriteSweepStudy(const std::string& name, const SweepSpec& spec, const std::vector<BudgetResult>& results,
                     const std::string& budget_file, const std::string& out_dir, bool force, bool plots, bool quiet,
                     int threads) {
  const std::string dir = out_dir.empty() ? report::DefaultSweepDirectory(name) : out_dir;
  ReplaceOptions replace;
  replace.force = force;
  const std::vector<report::Plot> drawn = plots ? report::SweepPlots(spec, results) : std::vector<report::Plot>{};
  report::WriteSweepDirectory(name, spec, results, drawn, dir, replace, threads, {{"budget", budget_file, report::FileSha256(budget_file)}});
  if (!quiet) {
    std::printf("sweep of %s: %zu variants\n", name.c_str(), results.size());
    PrintTopThree(spec, results);
    std::printf("report: %s/sweep.html\n", dir.c_str());
  }
}

SweepCommand::SweepCommand() : options_(std::make_unique<Options>()) {}
SweepCommand::~SweepCommand() = default;

CLI::App* SweepCommand::Register(CLI::App& app) {
  Options& s = *options_;
  CLI::App* c = app.add_subcommand("sweep", "Evaluate every variant of a budget's sweep section; write sweep.csv");
  c->add_option("budget", s.budget_file, "Budget YAML file with a sweep section")->required()->check(CLI::ExistingFile);
  AddOverridesOption(c, &s.overrides, "--set", "the budget (not its sweep section)");
  c->add_option("--out,-o", s.out_dir, "Directory (default: reports/<budget-name>_sweep)");
  c->add_option("--threads,-j", s.threads, "Variants loaded and evaluated at once, plots drawn at once (default: all cores)")
      ->check(CLI::NonNegativeNumber);
  c->add_flag("--quiet,-q", s.quiet, "Print nothing but errors");
  c->add_flag("--force", s.force, "Replace --out even if it is not a directory deb wrote");
  c->add_flag_callback("--no-plots", [&s] { s.plots = false; }, "Write sweep.csv only; gnuplot is not needed");
  AddShardOption(c, &s.shard);
  AddMpiTimeoutOption(c, &s.timeout_s, "a block of variants");
  return c;
}

int SweepCommand::Run() const {
  const Options& s = *options_;
  const SweepBudget sweep = LoadSweepFile(s.budget_file, s.overrides);
  const bool progress = !s.quiet && ::isatty(STDERR_FILENO);
  const auto report_progress = [&](std::size_t done, std::size_t total) {
    if (progress) std::fprintf(stderr, "\rdeb: sweep %zu/%zu variants", done, total);
  };
#ifdef DEB_MPI
  if (MpiSession::Size() > 1) {
    // Under mpirun: the ranks evaluate blocks of variants, rank 0 alone writes.
    if (!s.shard.empty()) throw InputError("--shard under mpirun: the ranks share the sweep already; give one or the other");
    const std::vector<std::string> texts = DistributeBlocks(
        sweep.variant_count,
        [&](std::size_t begin, std::size_t end) {
          std::vector<std::string> out;
          for (const BudgetResult& r : EvaluateSweepRange(sweep.spec, sweep.variant, begin, end, s.threads))
            out.push_back(SweepResultText(r));
          return out;
        },
        s.timeout_s);
    if (MpiSession::Rank() != 0) return 0;
    std::vector<BudgetResult> results;
    for (const std::string& t : texts) results.push_back(SweepResultFromText(t));
    WriteSweepStudy(sweep.name, sweep.spec, results, s.budget_file, s.out_dir, s.force, s.plots, s.quiet, s.threads);
    return 0;
  }
#endif
  if (const std::optional<StudyShard> shard = ShardOf(s.shard)) {
    SweepPartFile part;
    part.total = sweep.variant_count;
    std::tie(part.begin, part.end) = shard->Range(part.total);
    part.results = EvaluateSweepPart(sweep.spec, sweep.variant, *shard, s.threads, report_progress);
    if (progress) std::fprintf(stderr, "\n");
    part.header = ShardPartHeader(s.budget_file, s.overrides, *shard);
    part.header.digest = SweepDigest(sweep.text);
    part.header.method = "sweep";
    part.header.samples = part.total;
    const std::string dir =
        WriteShardPart(report::DefaultSweepDirectory(sweep.name), s.out_dir, *shard, SweepPartJson(part), s.force);
    if (!s.quiet)
      std::printf("sweep of %s, shard %zu/%zu: variants %zu to %zu of %zu in %s/part.json; join the parts with deb "
                  "merge\n",
                  sweep.name.c_str(), shard->index, shard->count, part.begin + 1, part.end, part.total, dir.c_str());
    return 0;
  }
  const auto results = EvaluateSweep(sweep.spec, sweep.variant, s.threads, report_progress);
  if (progress) std::fprintf(stderr, "\n");
  WriteSweepStudy(sweep.name, sweep.spec, results, s.budget_file, s.out_dir, s.force, s.plots, s.quiet, s.threads);
  return 0;
}

}  // namespace deb::tools
