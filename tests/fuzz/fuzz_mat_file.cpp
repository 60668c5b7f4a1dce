// Fuzzes the MAT-file reader (versions 5, 7 and 7.3): opening the file,
// then every way deb reads a variable (a matrix, a vector, a list of names)
// for the variables of a state-space or modal model and the file's first
// few others.
#include <algorithm>
#include <set>

#include "deb/formats/mat_file.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > deb_fuzz::kMaxInput) return 0;
  const std::string path = deb_fuzz::WriteTempFile("x.mat", data, size);
  deb_fuzz::ExpectOnlyInputError("MatFile", [&] {
    const deb::formats::MatFile f(path);
    std::set<std::string> names = {"A", "B", "C", "D", "input_names", "output_names", "f_hz", "zeta", "phi_in",
                                   "phi_out"};
    for (std::size_t i = 0; i < std::min<std::size_t>(f.variables().size(), 8); ++i) names.insert(f.variables()[i]);
    for (const std::string& name : names) {
      deb_fuzz::ExpectOnlyInputError("MatFile::Matrix", [&] { f.Matrix(name); });
      deb_fuzz::ExpectOnlyInputError("MatFile::Vector", [&] { f.Vector(name); });
      deb_fuzz::ExpectOnlyInputError("MatFile::Names", [&] { f.Names(name); });
    }
  });
  return 0;
}
