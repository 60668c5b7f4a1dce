#include "tools/uncertainty_command.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

#include "deb/core/error.h"
#include "deb/core/number_text.h"
#include "deb/core/output_dir.h"
#ifdef DEB_MPI
#include "deb/distributed/mpi_queue.h"
#endif
#include "deb/load/uncertainty_yaml.h"
#include "deb/report/compare/uncertainty_directory.h"
#include "deb/report/budget/file_digest.h"
#include "deb/report/compare/uncertainty_plots.h"
#include "deb/results/study_part.h"
#include "deb/version.h"
#include "tools/budget_overrides_option.h"
#include "tools/mpi_timeout_option.h"
#include "tools/shard_option.h"

namespace deb::tools {

struct UncertaintyCommand::Options {
  std::string budget_file;
  std::vector<BudgetOverride> overrides;  // --set
  std::string out_dir;
  std::string method = "mc";
  long long samples = 1000;
  unsigned long long seed = 1;
  int threads = 0;
  bool quiet = false;
  bool force = false;
  bool plots = true;
  std::string shard;  // --shard K/N
  double timeout_s = 0.0;  // --timeout, under mpirun
};

namespace {

std::string Percent(double p) { return SignificantText(100.0 * p, 4) + " %"; }

void Print(const std::string& name, const UncertaintyResult& r) {
  std::printf("uncertainty of %s: %zu samples (%s, seed %llu), %zu budgets evaluated\n", name.c_str(), r.samples,
              ToString(r.options.method).c_str(), static_cast<unsigned long long>(r.options.seed), r.evaluations);
  for (const UncertainParameter& p : r.spec.parameters)
    std::printf("  %s = %s%s: mean %s, sd %s\n", p.name.c_str(), SignificantText(p.nominal / p.unit_si, 6).c_str(),
                p.unit.empty() ? "" : (" " + p.unit).c_str(),
                SignificantText(p.distribution.Mean() / p.unit_si, 4).c_str(),
                SignificantText(p.distribution.StandardDeviation() / p.unit_si, 4).c_str());
  for (const StudyMetric& m : r.metrics) {
    if (!m.contributor.empty()) continue;
    std::printf("%s [%s]: nominal %s, mean %s, sd %s (first-order %s), P5 %s, P50 %s, P95 %s, P99 %s\n",
                m.Name().c_str(), m.unit.c_str(), SignificantText(m.nominal, 4).c_str(),
                SignificantText(m.moments.mean, 4).c_str(), SignificantText(m.moments.sd, 3).c_str(),
                SignificantText(m.fosm_sd, 3).c_str(), SignificantText(m.p5, 4).c_str(),
                SignificantText(m.p50, 4).c_str(), SignificantText(m.p95, 4).c_str(), SignificantText(m.p99, 4).c_str());
    if (m.limit)
      std::printf("  P(RMS <= %s) = %s (95 %%: %s to %s)\n", SignificantText(*m.limit, 4).c_str(),
                  Percent(static_cast<double>(m.met) / static_cast<double>(r.samples)).c_str(),
                  Percent(m.p_meet.low).c_str(), Percent(m.p_meet.high).c_str());
    std::string drivers;
    for (std::size_t i = 0; i < r.spec.parameters.size(); ++i) {
      drivers += (i ? ", " : "") + r.spec.parameters[i].name + " " + SignificantText(m.spearman[i], 2);
      if (!m.sobol.empty())
        drivers += " (S " + SignificantText(m.sobol[i].first, 2) + ", ST " + SignificantText(m.sobol[i].total, 2) + ")";
    }
    std::printf("  drivers (rank correlation): %s\n", drivers.c_str());
    std::printf("  worst corner: %s\n", SignificantText(m.worst_corner_value, 4).c_str());
  }
  std::printf("all requirements met: %s (95 %%: %s to %s)\n",
              Percent(static_cast<double>(r.all_met) / static_cast<double>(r.samples)).c_str(),
              Percent(r.p_all_met.low).c_str(), Percent(r.p_all_met.high).c_str());
  std::printf("worst corners: %s\n", r.corner_method.c_str());
  for (const std::string& note : r.notes) std::printf("note: %s\n", note.c_str());
}

}  // namespace

std::string UncertaintyDigest(const std::string& budget_text, const UncertaintyOptions& options) {
  return report::Sha256(budget_text + "\n--- deb " + DEB_VERSION + " uncertainty: method " + ToString(options.method) +
                        ", seed " + std::to_string(options.seed) + ", samples " + std::to_string(options.samples) + "\n");
}

void WriteUncertaintyStudy(const std::string& budget_name, const UncertaintyResult& result,
                           const std::string& budget_file, const std::string& out_dir, bool force, bool plots, bool quiet,
                           int threads) {
  const std::string dir = out_dir.empty() ? report::DefaultUncertaintyDirectory(budget_name) : out_dir;
  ReplaceOptions replace;
  replace.force = force;
  const std::vector<report::Plot> drawn = plots ? report::UncertaintyPlots(result) : std::vector<report::Plot>{};
  report::WriteUncertaintyDirectory(budget_name, result, drawn, dir, replace, threads, {{"budget", budget_file, report::FileSha256(budget_file)}});
  if (!quiet) {
    Print(budget_name, result);
    std::printf("report: %s/uncertainty.html\n", dir.c_str());
  }
}

UncertaintyCommand::UncertaintyCommand() : options_(std::make_unique<Options>()) {}
UncertaintyCommand::~UncertaintyCommand() = default;

CLI::App* UncertaintyCommand::Register(CLI::App& app) {
  Options& s = *options_;
  CLI::App* c = app.add_subcommand(
      "uncertainty", "Sample the budget's uncertain parameters; the RMS's distribution and P(meet) per requirement");
  c->add_option("budget", s.budget_file, "Budget YAML file with parameters that have a distribution")
      ->required()
      ->check(CLI::ExistingFile);
  AddOverridesOption(c, &s.overrides, "--set", "the budget");
  c->add_option("--samples,-n", s.samples,
                "Samples (with sobol: base samples, each costing parameters + 2 budgets) (default 1000)")
      ->check(CLI::Range(1LL, static_cast<long long>(kMaxUncertaintySamples)));
  c->add_option("--method", s.method, "mc (Monte Carlo), lhs (Latin hypercube) or sobol (Sobol sequence, with Sobol indices)")
      ->check(CLI::IsMember({"mc", "lhs", "sobol"}));
  c->add_option("--seed", s.seed, "Seed of the random numbers (default 1)");
  c->add_option("--out,-o", s.out_dir, "Directory (default: reports/<budget-name>_uncertainty)");
  c->add_option("--threads,-j", s.threads, "Budgets evaluated at once (default: all cores)")->check(CLI::NonNegativeNumber);
  c->add_flag("--quiet,-q", s.quiet, "Print nothing but errors");
  c->add_flag("--force", s.force, "Replace --out even if it is not a directory deb wrote");
  c->add_flag_callback("--no-plots", [&s] { s.plots = false; }, "Write summary.json, samples.csv and the documents without figures; gnuplot is not needed");
  AddShardOption(c, &s.shard);
  AddMpiTimeoutOption(c, &s.timeout_s, "a block of budgets");
  return c;
}

int UncertaintyCommand::Run() const {
  const Options& s = *options_;
  const UncertaintyBudget budget = LoadUncertaintyFile(s.budget_file, s.overrides);
  UncertaintyOptions options;
  options.samples = static_cast<std::size_t>(s.samples);
  options.method = ParseSamplingMethod(s.method);
  options.seed = s.seed;
  options.threads = s.threads;
  const bool progress = !s.quiet && ::isatty(STDERR_FILENO);
  const auto report_progress = [&](std::size_t done, std::size_t total) {
    if (progress) std::fprintf(stderr, "\rdeb: uncertainty %zu/%zu budgets", done, total);
  };
#ifdef DEB_MPI
  if (MpiSession::Size() > 1) {
    // Under mpirun: the ranks evaluate blocks, rank 0 alone summarises and writes.
    if (!s.shard.empty()) throw InputError("--shard under mpirun: the ranks share the study already; give one or the other");
    const std::vector<std::string> bytes = DistributeBlocks(
        UncertaintyEvaluationCount(budget.spec, options),
        [&](std::size_t begin, std::size_t end) {
          std::vector<std::string> out;
          for (const std::vector<double>& v : EvaluateUncertaintyRange(budget.spec, options, budget.variant, begin, end))
            out.push_back(DoublesToBytes(v));
          return out;
        },
        s.timeout_s);
    if (MpiSession::Rank() != 0) return 0;
    std::vector<std::vector<double>> values;
    for (const std::string& b : bytes) values.push_back(DoublesFromBytes(b));
    const UncertaintyResult result = SummariseUncertainty(budget.spec, options, budget.variant, values);
    WriteUncertaintyStudy(budget.name, result, s.budget_file, s.out_dir, s.force, s.plots, s.quiet, s.threads);
    return 0;
  }
#endif
  if (const std::optional<StudyShard> shard = ShardOf(s.shard)) {
    const UncertaintyPart part = EvaluateUncertaintyPart(budget.spec, options, budget.variant, *shard, report_progress);
    if (progress) std::fprintf(stderr, "\n");
    StudyPartHeader header = ShardPartHeader(s.budget_file, s.overrides, *shard);
    header.digest = UncertaintyDigest(budget.text, options);
    header.method = s.method;
    header.seed = options.seed;
    header.samples = options.samples;
    const std::string dir = WriteShardPart(report::DefaultUncertaintyDirectory(budget.name), s.out_dir, *shard,
                                           UncertaintyPartJson(header, part), s.force);
    if (!s.quiet)
      std::printf("uncertainty of %s, shard %zu/%zu: evaluations %zu to %zu of %zu in %s/part.json; join the parts "
                  "with deb merge\n",
                  budget.name.c_str(), shard->index, shard->count, part.begin + 1, part.end, part.total, dir.c_str());
    return 0;
  }
  const UncertaintyResult result = RunUncertainty(budget.spec, options, budget.variant, report_progress);
  if (progress) std::fprintf(stderr, "\n");
  WriteUncertaintyStudy(budget.name, result, s.budget_file, s.out_dir, s.force, s.plots, s.quiet, s.threads);
  return 0;
}

}  // namespace deb::tools
