#include "deb/report/compare/sensitivity_directory.h"

#include <doctest/doctest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "tests/support/cli_harness.h"

namespace deb::report {
namespace {

namespace fs = std::filesystem;
using test::ReadAll;

// Output y (variance 4, nm) with contributors a and b; parameter k.
SensitivityStudy Study() {
  SensitivityStudy study;
  OutputResult y;
  y.name = "y";
  y.unit = "nm";
  y.variance = 4.0;
  study.nominal.outputs = {y};
  study.sensitivities = {{"k", "y", "nm", "total", 4.0, 1.0, 0.25}, {"k", "y", "nm", "a", 3.0, 2.0, 2.0 / 3.0}};
  return study;
}

SensitivitySetting Setting() {
  SensitivitySetting setting;
  setting.name = "stage";
  setting.step = 1e-3;
  setting.parameters = {{"k", {50.0, 50.0}}};
  return setting;
}

}  // namespace

TEST_CASE("nominal values read as one value, one value for all, or the list") {
  CHECK(NominalText({}) == "–");
  CHECK(NominalText({50.0}) == "50");
  CHECK(NominalText({50.0, 50.0, 50.0}) == "50 (all 3)");
  CHECK(NominalText({1.5, 2e-7}) == "1.5, 2e-07");
}

TEST_CASE("sensitivity.csv has one row per term, with 10 significant digits") {
  CHECK(SensitivityCsv(Study().sensitivities) ==
        "parameter,output,unit,contributor,variance,d_variance_d_log_p,elasticity,method\n"
        "k,y,nm,total,4,1,0.25,central_difference\n"
        "k,y,nm,a,3,2,0.6666666667,central_difference\n");
}

TEST_CASE("sensitivity.md and .html state the step and nominal parameters, then each output's ranked table and plot") {
  Plot p;
  p.name = "y_tornado";
  p.caption = "tornado of y";
  p.output = 0;
  const std::vector<Plot> plots = {p};
  const std::string md = StudyMarkdown(SensitivityDocument(Setting(), Study(), plots));
  CHECK(md.rfind("# Sensitivities of stage\n\n", 0) == 0);
  CHECK(md.find("1 ± 0.001") != std::string::npos);
  CHECK(md.find("50 (all 2)") != std::string::npos);
  CHECK(md.find("## y\n\nNominal RMS ") != std::string::npos);
  CHECK(md.find("![tornado of y](plots/y_tornado.png)") != std::string::npos);
  // Contributor a: its own elasticity 2/3, its part of the total's 2 / 4 = 0.5 (what the tornado draws).
  CHECK(md.find("| k | a | 3.000 | 2.000 | 0.6667 | 0.5000 |") != std::string::npos);
  CHECK(md.find("| k | total | 4.000 | 1.000 | 0.2500 | 0.2500 |") != std::string::npos);
  const std::string html = StudyHtml(SensitivityDocument(Setting(), Study(), plots));
  CHECK(html.find("<h2>y</h2>\n<p>Nominal RMS ") != std::string::npos);
  CHECK(html.find("<img src=\"plots/y_tornado.png\" alt=\"tornado of y\">") != std::string::npos);
}

TEST_CASE("the sensitivity directory holds sensitivity.csv, .md, .html and .pdf") {
  const fs::path dir = test::TempDir("sensitivity_directory") / "out";
  const SensitivityStudy study = Study();
  WriteSensitivityDirectory(Setting(), study, {}, dir.string(), {}, 1);
  CHECK(ReadAll(dir / "sensitivity.csv") == SensitivityCsv(study.sensitivities));
  CHECK(ReadAll(dir / "sensitivity.md") == StudyMarkdown(SensitivityDocument(Setting(), study, {})));
  CHECK(ReadAll(dir / "sensitivity.html") == StudyHtml(SensitivityDocument(Setting(), study, {})));
  CHECK(ReadAll(dir / "sensitivity.pdf").rfind("%PDF-", 0) == 0);
  CHECK_FALSE(fs::exists(dir / "plots"));
  CHECK(DefaultSensitivityDirectory("stage") == "reports/stage_sensitivity");
}

}  // namespace deb::report
