#include "deb/results/result_writer.h"

#include <doctest/doctest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tests/support/flat_output.h"

namespace deb {
namespace {

using test::FlatOutput;


}  // namespace

TEST_CASE("summary.json: a failing output carries guidance with the closed-form figures, a passing one null") {
  BudgetResult result;
  result.outline.name = "guidance";
  result.grid = FrequencyGrid(std::vector<double>{1.0, 2.0});
  OutputResult fails = FlatOutput({49.0, 25.0, 16.0, 10.0}, 6.0, "nm", "position");
  BandRequirementResult band;
  band.requirement = {1.0, 1.5, 4.0};
  band.variance = 50.0;  // half of each flat PSD
  fails.band_requirements = {band};
  result.outputs = {fails, FlatOutput({4.0, 1.0}, 6.0, "nm", "quiet")};

  const auto j = nlohmann::json::parse(SummaryJson(result, {}));
  const auto& g = j["outputs"][0]["guidance"];
  REQUIRE(g.is_object());
  CHECK(g["fail_factor"].get<double>() == doctest::Approx(10.0 / 6.0).epsilon(1e-12));
  CHECK(g["uniform_factor"].get<double>() == doctest::Approx(10.0 / 6.0).epsilon(1e-12));
  CHECK(g["cps_crossing_hz"].get<double>() == doctest::Approx(1.36).epsilon(1e-12));
  CHECK(g["dominant"]["name"] == "a");
  CHECK(g["dominant"]["share"].get<double>() == doctest::Approx(0.49).epsilon(1e-12));
  CHECK(g["dominant"]["band"].is_null());  // the result has no bands
  CHECK(g["remove"] == nlohmann::json({"a", "b"}));
  REQUIRE(g["reduce_each"].size() == 2);
  CHECK(g["reduce_each"][0]["contributors"] == nlohmann::json({"a", "b"}));
  CHECK(g["reduce_each"][0]["rms_factor"].get<double>() == doctest::Approx(std::sqrt(7.4)).epsilon(1e-12));
  CHECK(g["reduce_each"][1]["contributors"] == nlohmann::json({"a", "b", "c"}));
  CHECK(g["reduce_each"][1]["rms_factor"].get<double>() == doctest::Approx(std::sqrt(90.0 / 26.0)).epsilon(1e-12));
  REQUIRE(g["bands"].size() == 1);
  const auto& b = g["bands"][0];
  CHECK(b["lo_hz"] == 1.0);
  CHECK(b["rms"].get<double>() == doctest::Approx(std::sqrt(50.0)).epsilon(1e-12));
  CHECK(b["fail_factor"].get<double>() == doctest::Approx(std::sqrt(50.0) / 4.0).epsilon(1e-12));
  CHECK(b["largest"] == "a");
  CHECK(b["largest_share"].get<double>() == doctest::Approx(24.5 / 50.0).epsilon(1e-12));
  CHECK(b["largest_rms_factor"].is_null());  // the others give 25.5 > 16 in the band
  CHECK(g["sentence"] ==
        "position fails by 1.667×: a (49 %) and b must drop 2.72× each, or a, b and c 1.861× each; the cumulative "
        "RMS reaches 6 nm at 1.36 Hz; band 1–1.5 Hz fails by 1.768× (largest: a, 49 % of the band)");
  CHECK(j["outputs"][1]["guidance"].is_null());
}

}  // namespace deb
