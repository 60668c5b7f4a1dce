// The part of a study that one shard evaluated (deb uncertainty --shard
// K/N), and what deb merge checks before it joins the parts: part.json in
// the shard's directory holds which study it belongs to (the digest of the
// budget document and the study's settings, the budget file and its --set
// changes, the method, seed and samples), which shard it is, the block of
// evaluation indices it holds, and each evaluation's metric values, written
// so that they read back bit for bit.
#pragma once

#include <cstdint>
#include <string>
#include <variant>
#include <vector>

#include "deb/budget/result.h"
#include "deb/core/study_shard.h"
#include "deb/uncertainty/uncertainty_study.h"

namespace deb {

struct StudyPartHeader {
  std::string digest;                  // of the study: equal in every part of one
  std::string budget;                  // the budget file, as an absolute path
  std::vector<std::string> overrides;  // its --set changes, KEY.PATH=VALUE
  std::string method;                  // mc, lhs, sobol
  std::uint64_t seed = 1;
  std::size_t samples = 0;
  StudyShard shard;
};

// The most bytes deb merge reads of one part.json.
inline constexpr std::uintmax_t kMaxPartBytes = std::uintmax_t{4} << 30;

std::string UncertaintyPartJson(const StudyPartHeader& header, const UncertaintyPart& part);

struct UncertaintyPartFile {
  StudyPartHeader header;
  UncertaintyPart part;
};

// A shard of a sweep (deb sweep --shard K/N): its variants [begin, end) of
// `total`, of whose results the part keeps the fields the sweep's report
// and CSV read (SweepResultText), nothing of their spectra.
struct SweepPartFile {
  StudyPartHeader header;  // method "sweep"; seed and samples unused
  std::size_t total = 0, begin = 0, end = 0;
  std::vector<BudgetResult> results;  // read back: only those fields filled
};
std::string SweepPartJson(const SweepPartFile& part);

// DIR/part.json, read once, as the part of an uncertainty study or of a
// sweep. @throws InputError naming the file for one that is missing, not
// deb's part of either, or breaks a rule (a shard outside 1..N, a block
// that is not the shard's, figures not finite numbers or of unequal counts).
std::variant<UncertaintyPartFile, SweepPartFile> ReadStudyPart(const std::string& dir);

// One variant's result as text and back (a distributed sweep's messages):
// the fields a sweep's report and CSV read, per output its name, signal,
// unit, variance and rms_max; per contributor its name, source, path, group
// and variance; per band requirement its band, limit and variance. Read
// back, the rest is empty. @throws InputError for text that is not one.
std::string SweepResultText(const BudgetResult& r);
BudgetResult SweepResultFromText(const std::string& text);

}  // namespace deb
