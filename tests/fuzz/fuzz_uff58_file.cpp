// Fuzzes the universal file reader (datasets 58 and 58b), and the reading
// of each dataset's units labels as units and densities.
#include "deb/formats/uff58_file.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > deb_fuzz::kMaxInput) return 0;
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  deb_fuzz::ExpectOnlyInputError("ParseUff58", [&] {
    deb::formats::LooksLikeUff(bytes);
    for (const deb::formats::Uff58Record& r : deb::formats::ParseUff58(bytes, "fuzz.uff")) {
      deb::formats::UffOrdinateUnit(r);
      deb::formats::UffDensity(r);
      deb::formats::UffUnitText(r.abscissa.units);
      r.Describe();
    }
  });
  return 0;
}
