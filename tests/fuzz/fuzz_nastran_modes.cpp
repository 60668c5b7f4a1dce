// Fuzzes the Nastran mode readers (OP2 and punch): opening the file (the scan
// of its records, the eigenvalue table), then the eigenvectors of every mode
// at DOFs of the beam fixture's grids, a scalar point's component and a grid
// that is in no file.
#include "deb/formats/nastran_modes.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > deb_fuzz::kMaxInput) return 0;
  const std::string path = deb_fuzz::WriteTempFile("x.op2", data, size);
  deb_fuzz::ExpectOnlyInputError("NastranModeFile", [&] {
    const deb::formats::NastranModeFile f(path);
    const int n = static_cast<int>(f.modes().size());
    deb_fuzz::ExpectOnlyInputError("Shapes", [&] { f.Shapes({{11, 3}, {2, 4}, {1, 1}}, n); });
    deb_fuzz::ExpectOnlyInputError("Shapes", [&] { f.Shapes({{5, 2}}, n > 0 ? 1 : 0); });
    deb_fuzz::ExpectOnlyInputError("Shapes", [&] { f.Shapes({{123456789, 6}}, n); });
  });
  return 0;
}
