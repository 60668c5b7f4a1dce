#include "deb/report/compare/sweep_directory.h"

#include <doctest/doctest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "deb/report/compare/sweep_documents.h"
#include "tests/support/cli_harness.h"

namespace deb::report {
namespace {

namespace fs = std::filesystem;
using test::ReadAll;

BudgetResult Variant(double rms) {
  BudgetResult r;
  OutputResult x;
  x.name = "x";
  x.unit = "nm";
  x.variance = rms * rms;
  r.outputs = {x};
  return r;
}

}  // namespace

TEST_CASE("the sweep directory holds sweep.csv, sweep.md, sweep.html and sweep.pdf, and no plots/ without plots") {
  SweepSpec spec;
  spec.parameters = {SweepParameter{"paths[0].h", {0, -100}, {}, {}, {}, {}}};
  const std::vector<BudgetResult> results = {Variant(3.0), Variant(2.0)};
  const fs::path dir = test::TempDir("sweep_directory") / "out";
  WriteSweepDirectory("s", spec, results, {}, dir.string(), {}, 1);
  CHECK(ReadAll(dir / "sweep.csv") == SweepCsv(spec, results));
  CHECK(ReadAll(dir / "sweep.md") == StudyMarkdown(SweepDocument("s", spec, results, {})));
  CHECK(ReadAll(dir / "sweep.html") == StudyHtml(SweepDocument("s", spec, results, {})));
  CHECK(ReadAll(dir / "sweep.pdf").rfind("%PDF-", 0) == 0);
  CHECK_FALSE(fs::exists(dir / "plots"));
}

TEST_CASE("a sweep's default directory is reports/<budget-name>_sweep") {
  CHECK(DefaultSweepDirectory("stage") == "reports/stage_sweep");
}

}  // namespace deb::report
