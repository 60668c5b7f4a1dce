#include "tools/merge_command.h"

#include <map>
#include <string>
#include <vector>

#include "deb/core/error.h"
#include "deb/load/uncertainty_yaml.h"
#include "deb/results/study_part.h"
#include "deb/uncertainty/sample_design.h"
#include "tools/uncertainty_command.h"

namespace deb::tools {

struct MergeCommand::Options {
  std::vector<std::string> parts;
  std::string out_dir;
  int threads = 0;
  bool quiet = false;
  bool force = false;
  bool plots = true;
};

MergeCommand::MergeCommand() : options_(std::make_unique<Options>()) {}
MergeCommand::~MergeCommand() = default;

CLI::App* MergeCommand::Register(CLI::App& app) {
  Options& s = *options_;
  CLI::App* c = app.add_subcommand(
      "merge", "Join the parts of a sharded uncertainty study (deb uncertainty --shard K/N) into its report");
  c->add_option("parts", s.parts, "The parts' directories, every shard 1..N once")->required()->check(CLI::ExistingDirectory);
  c->add_option("--out,-o", s.out_dir, "Directory (default: reports/<budget-name>_uncertainty, as the unsharded study)");
  c->add_option("--threads,-j", s.threads, "Threads for the report (default: all cores)")->check(CLI::NonNegativeNumber);
  c->add_flag("--quiet,-q", s.quiet, "Print nothing but errors");
  c->add_flag("--force", s.force, "Replace --out even if it is not a directory deb wrote");
  c->add_flag_callback("--no-plots", [&s] { s.plots = false; }, "As deb uncertainty --no-plots");
  return c;
}

int MergeCommand::Run() const {
  const Options& s = *options_;
  std::vector<UncertaintyPartFile> parts;
  for (const std::string& dir : s.parts) parts.push_back(ReadUncertaintyPart(dir));
  const StudyPartHeader& first = parts.front().header;
  // One study: the same digest (budget document and settings) and shard count.
  for (std::size_t i = 1; i < parts.size(); ++i) {
    const StudyPartHeader& h = parts[i].header;
    if (h.digest != first.digest || h.shard.count != first.shard.count || h.budget != first.budget ||
        h.overrides != first.overrides)
      throw InputError(s.parts[i] + " is a part of another study than " + s.parts[0] + " (" +
                       (h.budget != first.budget         ? "budget " + h.budget + ", not " + first.budget
                        : h.shard.count != first.shard.count ? "of " + std::to_string(h.shard.count) + " shards, not " +
                                                                 std::to_string(first.shard.count)
                                                             : "another budget document, --set, method, seed or samples") +
                       ")");
  }
  const std::size_t n = first.shard.count;
  std::map<std::size_t, std::size_t> by_shard;  // K -> index in parts
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const std::size_t k = parts[i].header.shard.index;
    if (const auto at = by_shard.find(k); at != by_shard.end())
      throw InputError(s.parts[at->second] + " and " + s.parts[i] + " are both shard " + std::to_string(k) + "/" +
                       std::to_string(n) + ": give each shard once");
    by_shard[k] = i;
  }
  if (by_shard.size() != n) {
    std::string missing;
    std::size_t count = 0;
    for (std::size_t k = 1; k <= n; ++k)
      if (!by_shard.count(k) && ++count <= 20) missing += (missing.empty() ? "" : ", ") + std::to_string(k);
    throw InputError("shard" + std::string(count > 1 ? "s " : " ") + missing + (count > 20 ? ", ..." : "") + " of " +
                     std::to_string(n) + (count > 1 ? " are" : " is") + " missing: every shard 1.." + std::to_string(n) +
                     " must be given once");
  }

  // The budget as the parts read it: the same document, else the parts are stale.
  std::vector<BudgetOverride> overrides;
  for (const std::string& o : first.overrides) overrides.push_back(ParseBudgetOverride(o));
  const UncertaintyBudget budget = LoadUncertaintyFile(first.budget, overrides);
  UncertaintyOptions options;
  options.method = ParseSamplingMethod(first.method);
  options.seed = first.seed;
  options.samples = first.samples;
  options.threads = s.threads;
  if (UncertaintyDigest(budget.text, options) != first.digest)
    throw InputError(first.budget + " (with the parts' --set) is not the budget the parts were made from: it changed "
                     "since; run the shards again");
  const std::size_t total = UncertaintyEvaluationCount(budget.spec, options);
  std::vector<std::vector<double>> values(total);
  for (std::size_t k = 1; k <= n; ++k) {
    const std::size_t i = by_shard[k];
    const UncertaintyPart& part = parts[i].part;
    if (part.total != total)
      throw InputError(s.parts[i] + ": " + std::to_string(part.total) + " evaluations where the study has " +
                       std::to_string(total));
    for (std::size_t e = part.begin; e < part.end; ++e) values[e] = part.values[e - part.begin];
  }
  const UncertaintyResult result = SummariseUncertainty(budget.spec, options, budget.variant, values);
  StudyOutput output;
  output.out_dir = s.out_dir;
  output.force = s.force;
  output.plots = s.plots;
  output.quiet = s.quiet;
  output.threads = s.threads;
  WriteUncertaintyStudy(budget.name, result, output);
  return 0;
}

}  // namespace deb::tools
