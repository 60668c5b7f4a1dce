// Fuzzes the reader of a shard's part.json (what `deb merge` reads): the
// file as a part directory's, and its text as one sweep variant's result.
#include <filesystem>

#include "deb/results/study_part.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > deb_fuzz::kMaxInput) return 0;
  const std::string path = deb_fuzz::WriteTempFile("part.json", data, size);
  const std::string dir = std::filesystem::path(path).parent_path().string();
  deb_fuzz::ExpectOnlyInputError("ReadStudyPart", [&] { deb::ReadStudyPart(dir); });
  const std::string text(reinterpret_cast<const char*>(data), size);
  deb_fuzz::ExpectOnlyInputError("SweepResultFromText", [&] { deb::SweepResultFromText(text); });
  return 0;
}
