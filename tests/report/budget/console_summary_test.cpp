#include "deb/report/budget/console_summary.h"

#include <doctest/doctest.h>

#include <string>

#include "deb/report/figure/plot.h"
#include "tests/support/flat_output.h"

namespace deb::report {
namespace {

bool Has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// Output "position" on the grid {1, 2} Hz: contributors a (variance 9) and b (16), RMS 5.
BudgetResult Result(std::optional<double> rms_max) {
  BudgetResult r;
  r.outline.name = "stage";
  r.outputs = {test::FlatOutput({9.0, 16.0}, rms_max)};
  return r;
}

}  // namespace

TEST_CASE("the console summary heads with the budget and grid, then each output's RMS and requirement") {
  const std::string text = ConsoleSummary(Result(6.0), 0.25, 4);
  CHECK(text.rfind("budget stage: 2 frequencies, 1-2 Hz, evaluated in 0.250 s\n", 0) == 0);
  CHECK(Has(text, "\noutput position [nm]: rms " + Sig(5.0, 4) + "  (requirement 6: PASS)\n"));
  CHECK(text.back() == '\n');
  CHECK_FALSE(Has(ConsoleSummary(Result(6.0), std::nullopt, 4), "evaluated in"));
}

TEST_CASE("contributors are listed largest first with their shares, as the report orders them") {
  const std::string text = ConsoleSummary(Result(std::nullopt), std::nullopt, 3);
  const std::size_t b = text.find("  b  "), a = text.find("  a  ");
  REQUIRE(b != std::string::npos);
  REQUIRE(a != std::string::npos);
  CHECK(b < a);
  CHECK(Has(text, Sig(4.0, 3)));  // b's RMS, 3 digits
  CHECK(Has(text, "64.00%"));
  CHECK(Has(text, "36.00%"));
  CHECK_FALSE(Has(text, "requirement"));
}

TEST_CASE("a failing output says FAIL and what would fix it") {
  const std::string text = ConsoleSummary(Result(2.0), std::nullopt, 4);
  CHECK(Has(text, "(requirement 2: FAIL)"));
  CHECK(Has(text, "  to fix: "));
}

}  // namespace deb::report
