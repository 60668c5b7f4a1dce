#include "deb/systems/frf_csv.h"

#include <doctest/doctest.h>

#include <cmath>
#include <sstream>

#include "test_util.h"

namespace deb {
namespace {

using testing::Contains;
using testing::MessageOf;
constexpr double kPi = 3.141592653589793238462643383279502884;

FrfCsv Parse(const std::string& text, const std::vector<std::string>& outputs = {},
             const std::vector<std::string>& inputs = {}) {
  std::istringstream in(text);
  return ParseFrfCsv(in, "plant.csv", outputs, inputs);
}

std::string ErrorOf(const std::string& text, const std::vector<std::string>& outputs = {},
                    const std::vector<std::string>& inputs = {}) {
  return MessageOf([&] { Parse(text, outputs, inputs); });
}

TEST_CASE("re/im, magnitude/phase and dB/phase columns give the same response") {
  // H = -1 + 1j at 1 Hz and 2j at 2 Hz: |H| = sqrt 2, 135 degrees; 2, 90 degrees.
  const FrfCsv a = Parse("f_hz, z/F.re, z/F.im\n1, -1, 1\n2, 0, 2\n");
  const FrfCsv b = Parse("f_hz, z/F.mag, z/F.phase_deg\n1, 1.4142135623730951, 135\n2, 2, 90\n");
  const FrfCsv c = Parse("f_hz z/F.db z/F.phase_deg\n1 3.0102999566398121 135\n2 6.0205999132796242 90\n");
  for (const FrfCsv* x : {&a, &b, &c}) {
    CHECK(x->outputs == std::vector<std::string>{"z"});
    CHECK(x->inputs == std::vector<std::string>{"F"});
    CHECK(std::abs(x->response.At(1.0)(0, 0) - std::complex<double>(-1, 1)) < 1e-14);
    CHECK(std::abs(x->response.At(2.0)(0, 0) - std::complex<double>(0, 2)) < 1e-14);
  }
}

TEST_CASE("a MIMO table is placed by the names in its header, or by the lists given") {
  const std::string text =
      "f, y/u2.re, y/u2.im, x/u1.re, x/u1.im, x/u2.re, x/u2.im, y/u1.re, y/u1.im\n"
      "1, 1, 0, 2, 0, 3, 0, 4, 0\n"
      "2, 1, 0, 2, 0, 3, 0, 4, 0\n";
  const FrfCsv found = Parse(text);
  CHECK(found.outputs == std::vector<std::string>{"y", "x"});
  CHECK(found.inputs == std::vector<std::string>{"u2", "u1"});
  CHECK(found.response.At(1.0)(0, 0) == std::complex<double>(1, 0));  // y/u2
  const FrfCsv given = Parse(text, {"x", "y"}, {"u1", "u2"});
  Eigen::MatrixXcd expected(2, 2);
  expected << 2, 3, 4, 1;
  CHECK(given.response.At(1.0) == expected);
}

TEST_CASE("a malformed frequency response file names the position and the rule") {
  CHECK(Contains(ErrorOf("1, 2, 3\n2, 2, 3\n"), "plant.csv:1:1: a frequency response file needs a header row"));
  CHECK(Contains(ErrorOf("f, zF.re, zF.im\n1, 1, 1\n2, 1, 1\n"), "plant.csv:1:4: column 'zF.re' is not named OUTPUT/INPUT.PART"));
  CHECK(Contains(ErrorOf("f, z/F.real, z/F.im\n1, 1, 1\n2, 1, 1\n"), "unknown part 'real'; allowed: re, im, mag, db, phase_deg"));
  CHECK(Contains(ErrorOf("f, z/F.re, z/F.phase_deg\n1, 1, 1\n2, 1, 1\n"), "entry z/F needs two columns"));
  CHECK(Contains(ErrorOf("f, z/F.re, z/F.im, z/F.re\n1, 1, 1, 1\n2, 1, 1, 1\n"), "plant.csv:1:20: column 'z/F.re' is given twice"));
  CHECK(Contains(ErrorOf("f, z/F.re, z/F.im\n1, 1, 1\n2, 1, 1\n", {"x"}), "output 'z' is not one of the path's outputs (x)"));
  CHECK(Contains(ErrorOf("f, z/F.re, z/F.im\n1, 1, 1\n2, 1, 1\n", {"z", "y"}), "entry y/F needs two columns"));
  CHECK(Contains(ErrorOf("f, z/F.mag, z/F.phase_deg\n1, 1, 1\n2, -1, 1\n"), "plant.csv:3:4: column 'z/F.mag': a magnitude must be >= 0"));
  CHECK(Contains(ErrorOf("f, z/F.re, z/F.im\n1, 1, 1\n1, 1, 1\n"), "plant.csv:3:1: frequency 1 Hz is not greater than 1 Hz on line 2"));
  CHECK(Contains(ErrorOf("f, z/F.re, z/F.im\n0, 1, 1\n1, 1, 1\n"), "frequency 0 Hz is not > 0"));
  CHECK(Contains(ErrorOf("f, z/F.re, z/F.im\n1, 1, nan\n2, 1, 1\n"), "plant.csv:2:7: column 'z/F.im': 'nan' is not finite"));
  CHECK(Contains(ErrorOf("f, z/F.re, z/F.im\n1, 1, 1\n"), "1 data rows; a frequency response needs at least 2"));
}

TEST_CASE("a missing file is an error naming it") {
  CHECK(Contains(MessageOf([] { ReadFrfCsv("/nonexistent/plant.csv"); }),
                 "/nonexistent/plant.csv: cannot open frequency response file"));
}

TEST_CASE("phases in degrees are converted exactly at the quarter turns") {
  const FrfCsv r = Parse("f, a/b.mag, a/b.phase_deg\n1, 1, -90\n2, 1, -270\n");
  CHECK(std::abs(r.response.At(1.0)(0, 0) - std::complex<double>(0, -1)) < 1e-15);
  CHECK(std::abs(r.response.At(2.0)(0, 0) - std::complex<double>(0, 1)) < 1e-15);
  // Unwrapped from -90 to -270 degrees: the log midpoint is at -180.
  CHECK(std::abs(r.response.At(std::sqrt(2.0))(0, 0) - std::polar(1.0, -kPi)) < 1e-12);
}

}  // namespace
}  // namespace deb
