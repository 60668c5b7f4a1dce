// Fuzzes the Nastran OP4 reader (text and binary, every layout): opening
// the file, then every matrix of the first few, read as complex and as real.
#include <algorithm>

#include "deb/formats/op4_file.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > deb_fuzz::kMaxInput) return 0;
  const std::string path = deb_fuzz::WriteTempFile("x.op4", data, size);
  (void)deb::formats::LooksLikeOp4File(path);
  deb_fuzz::ExpectOnlyInputError("Op4File", [&] {
    const deb::formats::Op4File f(path);
    for (std::size_t i = 0; i < std::min<std::size_t>(f.matrices().size(), 8); ++i) {
      const std::string& name = f.matrices()[i].name;
      deb_fuzz::ExpectOnlyInputError("Op4File::ComplexMatrix", [&] { f.ComplexMatrix(name); });
      deb_fuzz::ExpectOnlyInputError("Op4File::Matrix", [&] { f.Matrix(name); });
    }
    deb_fuzz::ExpectOnlyInputError("Op4File::Matrix", [&] { f.Matrix("KAA"); });
  });
  return 0;
}
