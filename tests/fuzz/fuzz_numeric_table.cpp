// Fuzzes the shared numeric table reader with the options the spectrum
// reader gives it, then the spectrum reader itself on the same text.
#include <sstream>

#include "deb/core/numeric_table.h"
#include "deb/spectra/spectrum_csv.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > deb_fuzz::kMaxInput) return 0;
  const std::string text(reinterpret_cast<const char*>(data), size);
  deb_fuzz::ExpectOnlyInputError("ParseNumericTable", [&] {
    // As deb/spectra/spectrum_csv.cpp asks for them.
    deb::NumericTableOptions options;
    options.metadata_keys = {"unit", "quantity", "sides", "interpolation"};
    options.first_column = "frequency";
    options.unnamed_prefix = "ch";
    std::istringstream in(text);
    deb::ParseNumericTable(in, "fuzz.csv", options);
  });
  deb_fuzz::ExpectOnlyInputError("ParseSpectrumCsv", [&] {
    std::istringstream in(text);
    deb::ParseSpectrumCsv(in, "fuzz.csv");
  });
  return 0;
}
