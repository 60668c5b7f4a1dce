// Fuzzes the budget loader and the sweep loader with the same YAML text.
// Relative data-file paths resolve in a private, empty directory.
#include "deb/load/budget_yaml.h"
#include "deb/load/sweep_yaml.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > deb_fuzz::kMaxInput) return 0;
  const std::string text(reinterpret_cast<const char*>(data), size);
  const std::string base_dir = deb_fuzz::PrivateDir();
  deb_fuzz::ExpectOnlyInputError("LoadBudgetText", [&] { deb::LoadBudgetText(text, "fuzz.yaml", base_dir); });
  deb_fuzz::ExpectOnlyInputError(
      "LoadSweepText", [&] { deb::LoadSweepVariants(deb::LoadSweepText(text, "fuzz.yaml", base_dir), 1); });
  return 0;
}
