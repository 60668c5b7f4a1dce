// Fuzzes the measured frequency response (FRF) reader.
#include <sstream>

#include "deb/systems/frf_csv.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > deb_fuzz::kMaxInput) return 0;
  const std::string text(reinterpret_cast<const char*>(data), size);
  deb_fuzz::ExpectOnlyInputError("ParseFrfCsv", [&] {
    std::istringstream in(text);
    deb::ParseFrfCsv(in, "fuzz.csv");
  });
  return 0;
}
