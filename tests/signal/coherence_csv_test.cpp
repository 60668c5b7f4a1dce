#include "deb/signal/coherence_csv.h"

#include <doctest/doctest.h>

#include <complex>
#include <sstream>
#include <string>
#include <vector>

namespace deb {
namespace {

// Two bins, channels a and b: S_aa = 1, S_bb = 4, S_ab = 2i (fully coherent, phase pi/2).
CsdEstimate TwoChannels() {
  CsdEstimate e;
  e.f_hz = {0.0, 0.5};
  e.channels = 2;
  e.channel_names = {"a", "b"};
  e.csd.resize(2, 4);
  const std::complex<double> i(0.0, 1.0);
  for (Eigen::Index k = 0; k < 2; ++k) {
    e.csd(k, 0) = 1.0;
    e.csd(k, 3) = 4.0;
    e.csd(k, 2) = 2.0 * i;  // column i + channels j = 0 + 2: S_ab
    e.csd(k, 1) = -2.0 * i;
  }
  return e;
}

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

}  // namespace

TEST_CASE("the coherence file has a column pair per channel pair: coherence and CSD phase in rad") {
  const std::vector<std::string> lines = Lines(CoherenceCsvText(TwoChannels()));
  REQUIRE(lines.size() >= 4);
  CHECK(lines[0].rfind("# coherence |S_ab|^2/(S_aa S_bb)", 0) == 0);
  CHECK(lines[lines.size() - 3] == "f_hz, coherence_a_b, phase_a_b");
  CHECK(lines[lines.size() - 2] == "0, 1, 1.570796327");
  CHECK(lines.back() == "0.5, 1, 1.570796327");
}

TEST_CASE("a single channel's coherence file holds its frequencies only") {
  CsdEstimate e;
  e.f_hz = {0.0, 1.0};
  e.channels = 1;
  e.channel_names = {"a"};
  e.csd = Eigen::MatrixXcd::Ones(2, 1);
  const std::vector<std::string> lines = Lines(CoherenceCsvText(e));
  CHECK(lines[lines.size() - 3] == "f_hz");
  CHECK(lines.back() == "1");
}

}  // namespace deb
