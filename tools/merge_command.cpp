#include "tools/merge_command.h"

#include <map>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "deb/core/error.h"
#include "deb/core/input_file.h"
#include "deb/load/sweep_yaml.h"
#include "deb/load/uncertainty_yaml.h"
#include "deb/results/study_part.h"
#include "deb/uncertainty/sample_design.h"
#include "tools/sweep_command.h"
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
      "merge", "Join the parts of a sharded study (deb uncertainty|sweep --shard K/N) into its report");
  c->add_option("parts", s.parts, "The parts' directories, every shard 1..N once")->required()->check(CLI::ExistingDirectory);
  c->add_option("--out,-o", s.out_dir, "Directory (default: the unsharded study's, reports/<budget-name>_uncertainty or _sweep)");
  c->add_option("--threads,-j", s.threads, "Threads for the report (default: all cores)")->check(CLI::NonNegativeNumber);
  c->add_flag("--quiet,-q", s.quiet, "Print nothing but errors");
  c->add_flag("--force", s.force, "Replace --out even if it is not a directory deb wrote");
  c->add_flag_callback("--no-plots", [&s] { s.plots = false; }, "As deb uncertainty|sweep --no-plots");
  return c;
}

namespace {

// The parts' headers make one study: the same digest, budget, --set and
// shard count, every shard 1..N once. Returns the index of shard k's part
// at [k - 1]. @throws InputError naming the parts that do not.
std::vector<std::size_t> CheckOneStudy(const std::vector<StudyPartHeader>& headers, const std::vector<std::string>& dirs) {
  const StudyPartHeader& first = headers.front();
  for (std::size_t i = 1; i < headers.size(); ++i) {
    const StudyPartHeader& h = headers[i];
    if (h.digest != first.digest || h.shard.count != first.shard.count || h.budget != first.budget ||
        h.overrides != first.overrides)
      throw InputError(dirs[i] + " is a part of another study than " + dirs[0] + " (" +
                       (h.budget != first.budget         ? "budget " + h.budget + ", not " + first.budget
                        : h.shard.count != first.shard.count ? "of " + std::to_string(h.shard.count) + " shards, not " +
                                                                 std::to_string(first.shard.count)
                                                             : "another budget document, --set, method, seed or samples") +
                       ")");
  }
  const std::size_t n = first.shard.count;
  std::map<std::size_t, std::size_t> by_shard;  // K -> index in headers
  for (std::size_t i = 0; i < headers.size(); ++i) {
    const std::size_t k = headers[i].shard.index;
    if (const auto at = by_shard.find(k); at != by_shard.end())
      throw InputError(dirs[at->second] + " and " + dirs[i] + " are both shard " + std::to_string(k) + "/" +
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
  std::vector<std::size_t> order;
  for (std::size_t k = 1; k <= n; ++k) order.push_back(by_shard[k]);
  return order;
}

std::vector<BudgetOverride> Overrides(const StudyPartHeader& h) {
  std::vector<BudgetOverride> overrides;
  for (const std::string& o : h.overrides) overrides.push_back(ParseBudgetOverride(o));
  return overrides;
}

// Why result b has not a's outputs, contributors and band requirements
// (names and counts), or "": a sweep's report reads every variant's by the
// first one's layout, and a part is a file deb does not trust.
std::string OtherShape(const BudgetResult& a, const BudgetResult& b) {
  if (a.outputs.size() != b.outputs.size())
    return std::to_string(b.outputs.size()) + " outputs, not " + std::to_string(a.outputs.size());
  for (std::size_t o = 0; o < a.outputs.size(); ++o) {
    const OutputResult &x = a.outputs[o], &y = b.outputs[o];
    if (x.name != y.name || x.unit != y.unit) return "output " + Excerpt(y.name) + " where " + x.name + " stands";
    if (x.band_requirements.size() != y.band_requirements.size())
      return "output " + x.name + " with other band requirements";
    if (x.contributors.size() != y.contributors.size()) return "output " + x.name + " with other contributors";
    for (std::size_t c = 0; c < x.contributors.size(); ++c)
      if (x.contributors[c].name != y.contributors[c].name)
        return "contributor " + Excerpt(y.contributors[c].name) + " of " + x.name + " where " + x.contributors[c].name +
               " stands";
  }
  return "";
}

[[noreturn]] void Stale(const StudyPartHeader& h) {
  throw InputError(h.budget + " (with the parts' --set) is not the budget the parts were made from: it changed "
                   "since; run the shards again");
}

}  // namespace

int MergeCommand::Run() const {
  const Options& s = *options_;
  // Every part read once; all of one kind.
  std::vector<std::variant<UncertaintyPartFile, SweepPartFile>> read;
  for (const std::string& dir : s.parts) read.push_back(ReadStudyPart(dir));
  const auto kind = [](const auto& part) {
    return std::holds_alternative<SweepPartFile>(part) ? "a sweep" : "an uncertainty study";
  };
  for (std::size_t i = 1; i < read.size(); ++i)
    if (read[i].index() != read[0].index())
      throw InputError(s.parts[i] + " is a part of " + kind(read[i]) + ", " + s.parts[0] + " of " + kind(read[0]) +
                       ": give the parts of one study");

  if (std::holds_alternative<SweepPartFile>(read[0])) {
    std::vector<SweepPartFile> parts;
    std::vector<StudyPartHeader> headers;
    for (auto& r : read) {
      parts.push_back(std::move(std::get<SweepPartFile>(r)));
      headers.push_back(parts.back().header);
    }
    const std::vector<std::size_t> order = CheckOneStudy(headers, s.parts);
    const SweepBudget sweep = LoadSweepFile(headers[0].budget, Overrides(headers[0]));
    if (SweepDigest(sweep.text) != headers[0].digest) Stale(headers[0]);
    std::vector<BudgetResult> results;
    for (std::size_t i : order) {
      if (parts[i].total != sweep.variant_count)
        throw InputError(s.parts[i] + ": " + std::to_string(parts[i].total) + " variants where the sweep has " +
                         std::to_string(sweep.variant_count));
      for (BudgetResult& r : parts[i].results) {
        if (!results.empty())
          if (const std::string why = OtherShape(results.front(), r); !why.empty())
            throw InputError(s.parts[i] + ": variant " + std::to_string(results.size() + 1) + " has " + why +
                             " (variant 1's): not what deb wrote");
        results.push_back(std::move(r));
      }
    }
    WriteSweepStudy(sweep.name, sweep.spec, results, headers[0].budget, s.out_dir, s.force, s.plots, s.quiet,
                    s.threads);
    return 0;
  }

  std::vector<UncertaintyPartFile> parts;
  std::vector<StudyPartHeader> headers;
  for (auto& r : read) {
    parts.push_back(std::move(std::get<UncertaintyPartFile>(r)));
    headers.push_back(parts.back().header);
  }
  const std::vector<std::size_t> order = CheckOneStudy(headers, s.parts);
  const StudyPartHeader& first = headers[0];
  // The budget as the parts read it: the same document, else the parts are stale.
  const UncertaintyBudget budget = LoadUncertaintyFile(first.budget, Overrides(first));
  UncertaintyOptions options;
  options.method = ParseSamplingMethod(first.method);
  options.seed = first.seed;
  options.samples = first.samples;
  options.threads = s.threads;
  if (UncertaintyDigest(budget.text, options) != first.digest) Stale(first);
  const std::size_t total = UncertaintyEvaluationCount(budget.spec, options);
  std::vector<std::vector<double>> values(total);
  for (std::size_t i : order) {
    const UncertaintyPart& part = parts[i].part;
    if (part.total != total)
      throw InputError(s.parts[i] + ": " + std::to_string(part.total) + " evaluations where the study has " +
                       std::to_string(total));
    for (std::size_t e = part.begin; e < part.end; ++e) values[e] = part.values[e - part.begin];
  }
  const UncertaintyResult result = SummariseUncertainty(budget.spec, options, budget.variant, values);
  WriteUncertaintyStudy(budget.name, result, first.budget, s.out_dir, s.force, s.plots, s.quiet, s.threads);
  return 0;
}

}  // namespace deb::tools
