// The --shard K/N option of the studies that can be split (deb uncertainty,
// deb sweep), the shard a Slurm job array gives instead, and the part a
// shard writes.
#pragma once

#include <CLI/CLI.hpp>

#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "deb/core/error.h"
#include "deb/core/input_file.h"
#include "deb/core/output_dir.h"
#include "deb/core/study_shard.h"
#include "deb/load/budget_yaml.h"
#include "deb/results/study_part.h"

namespace deb::tools {

// What is wrong with `text` as K/N (1 <= K <= N <= kMaxShards), or ""; the
// shard into *shard when it is one.
inline std::string ShardProblem(const std::string& text, StudyShard* shard) {
  const std::size_t slash = text.find('/');
  const auto number = [](const std::string& t, std::size_t* out) {
    if (t.empty() || t.size() > 6 || t.find_first_not_of("0123456789") != std::string::npos) return false;
    *out = std::stoul(t);
    return true;
  };
  StudyShard s;
  if (slash == std::string::npos || !number(text.substr(0, slash), &s.index) || !number(text.substr(slash + 1), &s.count))
    return "--shard '" + Excerpt(text) + "': give K/N, this process's shard K of N (e.g. 2/8)";
  if (!s.Valid())
    return "--shard " + text + ": K/N needs 1 <= K <= N <= " + std::to_string(kMaxShards);
  if (shard) *shard = s;
  return "";
}

// The shard from --shard (`option`), else from a Slurm job array
// (SLURM_ARRAY_TASK_ID counted from SLURM_ARRAY_TASK_MIN, of
// SLURM_ARRAY_TASK_COUNT), else none: the whole study.
// @throws InputError for Slurm variables that are no shard.
inline std::optional<StudyShard> ShardOf(const std::string& option) {
  StudyShard s;
  if (!option.empty()) {
    if (const std::string why = ShardProblem(option, &s); !why.empty()) throw InputError(why);
    return s;
  }
  const char* id = std::getenv("SLURM_ARRAY_TASK_ID");
  const char* count = std::getenv("SLURM_ARRAY_TASK_COUNT");
  if (!id || !count) return std::nullopt;
  const char* min = std::getenv("SLURM_ARRAY_TASK_MIN");
  const auto number = [](const char* name, const char* t) {
    const std::string text = t;
    if (text.empty() || text.size() > 9 || text.find_first_not_of("0123456789") != std::string::npos)
      throw InputError(std::string(name) + "='" + Excerpt(text) + "' is not a whole number (a Slurm array job sets it)");
    return std::stoul(text);
  };
  const unsigned long k = number("SLURM_ARRAY_TASK_ID", id), n = number("SLURM_ARRAY_TASK_COUNT", count);
  const unsigned long first = min ? number("SLURM_ARRAY_TASK_MIN", min) : 0;
  if (k < first || !ShardProblem(std::to_string(k - first + 1) + "/" + std::to_string(n), &s).empty())
    throw InputError("the Slurm array task " + std::to_string(k) + " (from " + std::to_string(first) + ", " +
                     std::to_string(n) + " tasks) is no shard K/N with 1 <= K <= N <= " + std::to_string(kMaxShards) +
                     "; give --shard K/N, or run an array of consecutive indices");
  return s;
}

// The --shard option on a study's command.
inline CLI::Option* AddShardOption(CLI::App* app, std::string* shard) {
  return app
      ->add_option("--shard", *shard,
                   "Evaluate only shard K of N and write it as a part for deb merge (default: from "
                   "SLURM_ARRAY_TASK_ID/_COUNT in a Slurm array job, else the whole study)")
      ->check(CLI::Validator([](std::string& t) { return ShardProblem(t, nullptr); }, "K/N"));
}

// The part of `shard` a study writes: its header's budget (absolute path),
// --set changes and shard filled, the rest the study's own.
inline StudyPartHeader ShardPartHeader(const std::string& budget_file, const std::vector<BudgetOverride>& overrides,
                                       const StudyShard& shard) {
  StudyPartHeader h;
  h.budget = std::filesystem::absolute(budget_file).lexically_normal().string();
  for (const BudgetOverride& o : overrides) h.overrides.push_back(o.key_path + "=" + o.value);
  h.shard = shard;
  return h;
}

// Writes part.json (`json`) atomically into out_dir, or when it is empty into
// <study_dir>_part<K>of<N>; returns the directory.
inline std::string WriteShardPart(const std::string& study_dir, const std::string& out_dir, const StudyShard& shard,
                                  const std::string& json, bool force) {
  const std::string dir = out_dir.empty() ? study_dir + "_part" + std::to_string(shard.index) + "of" +
                                                std::to_string(shard.count)
                                          : out_dir;
  ReplaceOptions replace;
  replace.force = force;
  ReplaceDirectory(
      dir, [&](const std::string& tmp) { WriteTextFile((std::filesystem::path(tmp) / "part.json").string(), json); },
      replace);
  return dir;
}

}  // namespace deb::tools
