// Fuzzes the reader of a run's summary.json (what `deb compare` reads).
#include "deb/results/comparison_files.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > deb_fuzz::kMaxInput) return 0;
  const std::string path = deb_fuzz::WriteTempFile("summary.json", data, size);
  deb_fuzz::ExpectOnlyInputError("ReadSummaryFigures", [&] { deb::ReadSummaryFigures(path, "fuzz"); });
  return 0;
}
