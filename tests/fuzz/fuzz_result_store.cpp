// Fuzzes the reader of a result store (result.h5, what `deb report` and
// `deb compare` read), starting from stores `deb run` wrote for shipped
// budgets (tools/fuzz). A crash inside libhdf5 is a finding like any other.
#include "deb/results/result_store.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > deb_fuzz::kMaxInput) return 0;
  const std::string path = deb_fuzz::WriteTempFile("result.h5", data, size);
  deb_fuzz::ExpectOnlyInputError("ReadResultStore", [&] { deb::ReadResultStore(path); });
  return 0;
}
