// Budget sources of `type: measured`: a spectrum file read at load.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "deb/budget/engine.h"
#include "deb/load/budget_yaml.h"

namespace deb {
namespace {

const char* kBudget = R"(name: measured
sources:
  - name: floor
    spectrum: {type: measured, file: spec.csv}
paths:
  - {name: g, type: gain, gain: 1, input_unit: um/s, output_unit: um/s, outputs: [v]}
contributors:
  - {name: floor, source: floor, path: g}
outputs:
  - {name: velocity, signal: v, unit: um/s}
)";

// A budget file beside a spectrum file whose first lines are `header`.
class BudgetDir {
 public:
  explicit BudgetDir(const std::string& header)
      : dir_(std::filesystem::temp_directory_path() / ("deb_measured_source_" + std::to_string(::getpid()))) {
    std::filesystem::create_directories(dir_);
    std::ofstream(dir_ / "spec.csv") << header << "f_hz, z\n0.1, 4e-2\n1000, 4e-2\n";
    std::ofstream(dir_ / "b.yaml") << kBudget;
  }
  ~BudgetDir() { std::filesystem::remove_all(dir_); }
  std::string budget() const { return (dir_ / "b.yaml").string(); }

 private:
  std::filesystem::path dir_;
};

bool Mentions(const std::vector<std::string>& lines, const std::string& text) {
  for (const auto& line : lines)
    if (line.find(text) != std::string::npos) return true;
  return false;
}

TEST_CASE("a spectrum file that does not say PSD or ASD is read as a PSD, and check and run say so") {
  const BudgetDir dir("# unit: um/s\n");
  const Budget b = LoadBudgetFile(dir.budget());
  REQUIRE(b.sources.size() == 1);
  REQUIRE(b.sources[0].notes.size() == 1);
  CHECK(b.sources[0].notes[0].find("no '# quantity:' line") != std::string::npos);
  CHECK(b.sources[0].notes[0].find("(um/s)^2/Hz") != std::string::npos);
  CHECK(b.sources[0].notes[0].find("'# quantity: asd'") != std::string::npos);
  // The values were taken as a PSD: 4e-2 (um/s)^2/Hz.
  CHECK(b.sources[0].spectrum->Psd(10.0)(0) == doctest::Approx(4e-2).epsilon(1e-12));
  const EvaluationPlan plan = PlanEvaluation(b);
  CHECK(Mentions(plan.warnings, "source 'floor': "));
  CHECK(Mentions(plan.warnings, "has no '# quantity:' line"));
}

TEST_CASE("a spectrum file that declares its quantity gets no such note") {
  const BudgetDir psd("# unit: um/s\n# quantity: psd\n");
  const Budget b = LoadBudgetFile(psd.budget());
  CHECK(b.sources[0].notes.empty());
  CHECK_FALSE(Mentions(PlanEvaluation(b).warnings, "quantity"));
}

TEST_CASE("a declared ASD is squared and gets no note") {
  const BudgetDir asd("# unit: um/s\n# quantity: asd\n");
  const Budget b = LoadBudgetFile(asd.budget());
  CHECK(b.sources[0].notes.empty());
  CHECK(b.sources[0].spectrum->Psd(10.0)(0) == doctest::Approx(16e-4).epsilon(1e-12));
}

}  // namespace
}  // namespace deb

namespace deb {

TEST_CASE("a measured source reads a spectrum with confidence bounds as one channel, and may pick a bound") {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("deb_measured_bounds_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "spec.csv") << "# unit: um/s\n# quantity: psd\nf_hz, z, z_lo, z_hi\n0.1, 4e-2, 3e-2, 6e-2\n"
                                     "1000, 4e-2, 3e-2, 6e-2\n";
  std::ofstream(dir / "b.yaml") << kBudget;
  const Budget b = LoadBudgetFile((dir / "b.yaml").string());
  CHECK(b.sources[0].channels() == 1);  // z_lo, z_hi are bounds, not channels
  CHECK(b.sources[0].spectrum->Psd(10.0)(0) == doctest::Approx(4e-2));
  // The upper bound as a conservative source.
  std::string text = kBudget;
  const std::string file = "file: spec.csv}";
  text.replace(text.find(file), file.size(), "file: spec.csv, columns: [z_hi]}");
  std::ofstream(dir / "hi.yaml") << text;
  const Budget hi = LoadBudgetFile((dir / "hi.yaml").string());
  CHECK(hi.sources[0].spectrum->Psd(10.0)(0) == doctest::Approx(6e-2));
  std::filesystem::remove_all(dir);
}

}  // namespace deb
