// `deb spectrum ...` as a user meets it: files in, spectrum CSVs out, exit 3
// with file:line:col messages for bad input.
#include <doctest/doctest.h>

#include <complex>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <unistd.h>

#include "deb/spectra/spectrum_csv.h"
#include "deb/systems/frf_csv.h"
#include "tests/support/cli_harness.h"

namespace fs = std::filesystem;
using namespace deb::test;

namespace {

// Three co-located sensors: common white ground motion (sigma 1 um/s) plus
// independent noise of 0.1, 0.1 and 0.2 um/s, at 200 Hz.
fs::path Recording(const fs::path& dir, const std::string& header = "# rate_hz: 200\n# unit: um/s\n") {
  std::ofstream out(dir / "rec.csv");
  out << header << "a, b, c\n";
  std::mt19937_64 rng(5);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (int i = 0; i < 1 << 15; ++i) {
    const double u = normal(rng);
    out << u + 0.1 * normal(rng) << ", " << u + 0.1 * normal(rng) << ", " << u + 0.2 * normal(rng) << "\n";
  }
  return dir / "rec.csv";
}

}  // namespace

TEST_CASE("deb spectrum welch writes a spectrum CSV that reads back with the white level 2 s^2 / fs (4 sigma)") {
  const fs::path dir = TempDir("welch");
  const Command r = RunDeb("spectrum welch " + Recording(dir).string() + " --segment 512 --columns a -o " +
                       (dir / "psd.csv").string());
  REQUIRE_MESSAGE(r.exit_code == 0, r.err);
  CHECK(r.out.find("127 averages") != std::string::npos);
  const deb::SpectrumCsv csv = deb::ReadSpectrumCsv((dir / "psd.csv").string());
  CHECK(csv.unit == std::string("um/s"));
  CHECK(csv.channel_names == std::vector<std::string>{"a"});
  CHECK(csv.f_hz.front() == doctest::Approx(200.0 / 512));
  const double level = 2.0 * (1.0 + 0.01) / 200.0;
  const double mean = csv.psd.col(0).head(250).mean();
  // nu ~ 1.89 K per bin, Hann neighbours correlated: sigma of the mean of
  // 250 bins ~ sqrt(2 / (1.89 * 127) * 1.944 / 250) = 0.8 %.
  CHECK(std::abs(mean / level - 1.0) < 4.0 * 0.008);
  CHECK(ReadAll(dir / "psd.csv").find("# welch: window hann, segment 512 samples") != std::string::npos);
  fs::remove_all(dir);
}

TEST_CASE("deb spectrum convert --from-bands then bands: a floor built at VC-D is VC-D in every band") {
  const fs::path dir = TempDir("bands");
  {
    std::ofstream table(dir / "vcd.csv");
    table << "# unit: um/s\ncentre_hz, floor\n";
    for (double f : {8.0, 10.0, 12.5, 16.0, 20.0, 25.0, 31.5, 40.0, 50.0, 63.0, 80.0}) table << f << ", 6.25\n";
  }
  Command r =
      RunDeb("spectrum convert --from-bands " + (dir / "vcd.csv").string() + " -o " + (dir / "psd.csv").string());
  REQUIRE_MESSAGE(r.exit_code == 0, r.err);
  // All 11 bands come back, the top one too: its edge is written to every digit.
  r = RunDeb("spectrum bands " + (dir / "psd.csv").string() + " --lowest 8 --highest 80 --criteria vc -o " +
          (dir / "bands.csv").string());
  REQUIRE_MESSAGE(r.exit_code == 0, r.err);
  CHECK(r.out.find("floor: 11 bands, VC-D; limiting band") != std::string::npos);
  const std::string bands = ReadAll(dir / "bands.csv");
  CHECK(bands.find("centre_hz, lo_hz, hi_hz, points, floor, floor_class") != std::string::npos);
  std::size_t count = 0;
  for (std::size_t at = bands.find(", VC-D"); at != std::string::npos; at = bands.find(", VC-D", at + 1)) ++count;
  CHECK(count == 11);
  // The same floor in nm (displacement) converts back through (2 pi f)^2.
  r = RunDeb("spectrum convert " + (dir / "psd.csv").string() + " --to nm -o " + (dir / "nm.csv").string());
  REQUIRE_MESSAGE(r.exit_code == 0, r.err);
  r = RunDeb("spectrum bands " + (dir / "nm.csv").string() + " --lowest 8 --highest 63 --criteria vc");
  count = 0;
  for (std::size_t at = r.out.find(", 6.24999999"); at != std::string::npos; at = r.out.find(", 6.24999999", at + 1)) ++count;
  CHECK(count == 10);  // 6.25 to 1e-9: the table's two points per band carry the (2 pi f)^2 as a power law
  fs::remove_all(dir);
}

TEST_CASE("welch --bounds, bands, convert --from-bands chain: bounds are no channels, a warning is said once") {
  const fs::path dir = TempDir("chain");
  Command r = RunDeb("spectrum welch " + Recording(dir).string() + " --segment 512 --bounds -o " +
                     (dir / "psd.csv").string() + " --no-plots");
  REQUIRE_MESSAGE(r.exit_code == 0, r.err);
  const deb::SpectrumCsv psd = deb::ReadSpectrumCsv((dir / "psd.csv").string());
  CHECK(psd.channel_names == std::vector<std::string>{"a", "b", "c"});
  CHECK(psd.bound_names == std::vector<std::string>{"a_lo", "a_hi", "b_lo", "b_hi", "c_lo", "c_hi"});
  REQUIRE(psd.bounds.cols() == 6);
  CHECK(psd.bounds(10, 0) < psd.psd(10, 0));  // a_lo below a
  CHECK(psd.bounds(10, 1) > psd.psd(10, 0));  // a_hi above it
  r = RunDeb("spectrum bands " + (dir / "psd.csv").string() + " --criteria vc --no-plots -o " +
             (dir / "bands.csv").string());
  REQUIRE_MESSAGE(r.exit_code == 0, r.err);
  CHECK(r.out.find("a: ") != std::string::npos);
  CHECK(r.out.find("a_lo") == std::string::npos);  // classified: the three channels only
  std::size_t warnings = 0;
  for (std::size_t at = r.out.find("warning:"); at != std::string::npos; at = r.out.find("warning:", at + 1)) ++warnings;
  CHECK(warnings == 1);
  CHECK(ReadAll(dir / "bands.csv").find("# unit: um/s\n") != std::string::npos);
  // convert keeps the bounds beside their channels, converted alike: um/s -> mm/s is 1e-6 on a PSD.
  r = RunDeb("spectrum convert " + (dir / "psd.csv").string() + " --to mm/s --no-plots -o " +
             (dir / "mm.csv").string());
  REQUIRE_MESSAGE(r.exit_code == 0, r.err);
  const deb::SpectrumCsv mm = deb::ReadSpectrumCsv((dir / "mm.csv").string());
  REQUIRE(mm.bound_names == psd.bound_names);
  CHECK(mm.bounds(10, 1) == doctest::Approx(1e-6 * psd.bounds(10, 1)).epsilon(1e-9));
  // The bands output, class columns and all, reads back as a band table: the PSD is constant per band at
  // the band's mean square / bandwidth, so the bands of the result are those of the table.
  r = RunDeb("spectrum convert --from-bands " + (dir / "bands.csv").string() + " --no-plots -o " +
             (dir / "back.csv").string());
  REQUIRE_MESSAGE(r.exit_code == 0, r.err);
  const deb::SpectrumCsv back = deb::ReadSpectrumCsv((dir / "back.csv").string());
  CHECK(back.channel_names == std::vector<std::string>{"a", "b", "c"});
  CHECK(back.unit == std::string("um/s"));
  r = RunDeb("spectrum bands " + (dir / "back.csv").string() + " --criteria none --no-plots -o " +
             (dir / "bands2.csv").string());
  REQUIRE_MESSAGE(r.exit_code == 0, r.err);
  const auto first_rms = [](const std::string& text, const std::string& centre) {
    const std::size_t at = text.find("\n" + centre + ", ");
    REQUIRE(at != std::string::npos);
    std::istringstream row(text.substr(at + 1, text.find('\n', at + 1) - at - 1));
    std::string cell;
    for (int k = 0; k < 5; ++k) std::getline(row, cell, ',');
    return std::stod(cell);
  };
  CHECK(first_rms(ReadAll(dir / "bands2.csv"), "16") ==
        doctest::Approx(first_rms(ReadAll(dir / "bands.csv"), "16")).epsilon(1e-6));
  fs::remove_all(dir);
}

TEST_CASE("deb spectrum selfnoise writes one noise spectrum per sensor, usable as a measured source") {
  const fs::path dir = TempDir("selfnoise");
  const Command r = RunDeb("spectrum selfnoise " + Recording(dir).string() + " --sensors a,b,c --segment 512 -o " +
                       (dir / "noise.csv").string());
  REQUIRE_MESSAGE(r.exit_code == 0, r.err);
  CHECK(r.out.find("Sleeman") != std::string::npos);
  const deb::SpectrumCsv noise = deb::ReadSpectrumCsv((dir / "noise.csv").string());
  REQUIRE(noise.psd.cols() == 3);
  // Truth: 2 n^2 / fs = 1e-4 and 4e-4 (um/s)^2/Hz; the mean over 250 bins
  // scatters by a few percent (see tests/signal/self_noise_test.cpp).
  CHECK(noise.psd.col(0).head(250).mean() == doctest::Approx(1e-4).epsilon(0.1));
  CHECK(noise.psd.col(2).head(250).mean() == doctest::Approx(4e-4).epsilon(0.1));
  fs::remove_all(dir);
}

TEST_CASE("deb spectrum frf writes a response that a frf path reads: sensors a, b, c against a") {
  // b = a + noise, c = a + more noise (Recording): H1 from a is 1 with zero
  // phase for both, the coherence 1/(1 + 0.02) and 1/(1 + 0.05) (noise
  // variances 0.01 + 0.01 and 0.01 + 0.04 against 1: H1 ignores the output's
  // share; the input's noise biases |H1| low by 1/(1 + 0.01)).
  const fs::path dir = TempDir("frf");
  const Command r = RunDeb("spectrum frf " + Recording(dir).string() +
                           " --input a --outputs b,c --segment 512 --no-plots -o " + (dir / "frf.csv").string());
  REQUIRE_MESSAGE(r.exit_code == 0, r.err);
  const deb::FrfCsv frf = deb::ReadFrfCsv((dir / "frf.csv").string());
  CHECK(frf.outputs == std::vector<std::string>{"b", "c"});
  CHECK(frf.inputs == std::vector<std::string>{"a"});
  std::complex<double> mean_b = 0.0;
  const std::vector<double>& f = frf.response.f_hz();
  for (double fk : f) mean_b += frf.response.At(fk)(0, 0) / static_cast<double>(f.size());
  CHECK(std::abs(mean_b - 1.0 / 1.01) < 0.005);
  const std::string text = ReadAll(dir / "frf.csv");
  CHECK(text.find("f_hz, b/a.mag, b/a.phase_deg, b/a.coherence, c/a.mag, c/a.phase_deg, c/a.coherence") !=
        std::string::npos);
  CHECK(text.find("# frequency response H1 = S_xy / S_xx from a of rec.csv") == 0);
  // The plot beside it: |H1| above, the phase, the coherence below.
  const Command plotted = RunDeb("spectrum frf " + Recording(dir).string() +
                                 " --input a --outputs b,c --segment 512 -o " + (dir / "frf2.csv").string());
  REQUIRE_MESSAGE(plotted.exit_code == 0, plotted.err);
  CHECK(fs::file_size(dir / "frf2.png") > 1000);
  const std::string script = ReadAll(dir / "frf2.gp");
  CHECK(script.find("set multiplot") != std::string::npos);
  CHECK(script.find("coherence γ^{2}") != std::string::npos);
  CHECK(script.find("set ylabel 'phase [°]'") != std::string::npos);
  const std::string plot_csv = ReadAll(dir / "frf2.plot.csv");
  CHECK(plot_csv.find("f_hz,mag_b,mag_c,coherence_b,coherence_c,phase_deg_b,phase_deg_c\n") != std::string::npos);
  // b and c see the ground motion a sees, in phase: H1 real and positive, the phase near 0 at every bin.
  std::istringstream rows(plot_csv);
  std::string row;
  int phases = 0;
  double worst = 0.0;
  while (std::getline(rows, row)) {
    if (row.empty() || !std::isdigit(static_cast<unsigned char>(row[0]))) continue;
    std::istringstream cells(row);
    std::string cell;
    for (int k = 0; k < 6; ++k) std::getline(cells, cell, ',');
    worst = std::max(worst, std::abs(std::stod(cell)));  // phase_deg_b
    ++phases;
  }
  CHECK(phases > 50);
  CHECK(worst < 15.0);  // coherence ~0.98: the phase scatters by a few degrees
  const Command bad = RunDeb("spectrum frf " + Recording(dir).string() + " --input q --outputs b --no-plots -o " +
                         (dir / "bad.csv").string());
  CHECK(bad.exit_code == 3);
  CHECK(bad.err.find("no channel 'q'") != std::string::npos);
  CHECK_FALSE(fs::exists(dir / "bad.csv"));
  fs::remove_all(dir);
}

TEST_CASE("deb spectrum reference writes Peterson's NLNM in the unit asked for") {
  const Command r = RunDeb("spectrum reference nlnm --to m/s^2 --points-per-decade 1");
  REQUIRE_MESSAGE(r.exit_code == 0, r.err);
  CHECK(r.out.find("f_hz, nlnm") != std::string::npos);
  CHECK(r.out.find("\n1, 2.290867653e-17\n") != std::string::npos);  // -166.4 dB at 1 s
}

TEST_CASE("deb spectrum welch --coherence of two independent channels has a row per bin and a low coherence") {
  // (Its cost, once quadratic in the segment length, is measured by hand, not
  // here: 8 x 1e6 samples at --segment 16384 took 6.7 s, now 0.7 s.)
  const fs::path dir = TempDir("coherence_rows");
  {
    // Two white channels, raw little-endian float64, 2^16 samples each.
    std::ofstream out(dir / "rec.f64", std::ios::binary);
    std::mt19937_64 rng(7);
    std::normal_distribution<double> normal(0.0, 1.0);
    for (int i = 0; i < 2 * (1 << 16); ++i) {
      const double x = normal(rng);
      std::uint64_t bits;
      std::memcpy(&bits, &x, sizeof bits);
      for (int byte = 0; byte < 8; ++byte) out.put(static_cast<char>((bits >> (8 * byte)) & 0xff));
    }
  }
  const Command r = RunDeb("spectrum welch " + (dir / "rec.f64").string() +
                       " --format float64 --rate 1000 --file-channels 2 --segment 1024 --no-plots -o " +
                       (dir / "psd.csv").string() + " --coherence " + (dir / "coh.csv").string());
  REQUIRE_MESSAGE(r.exit_code == 0, r.err);
  std::ifstream coh(dir / "coh.csv");
  std::string line;
  int rows = 0;
  double sum = 0.0;
  while (std::getline(coh, line)) {
    if (line.empty() || line[0] == '#') continue;
    ++rows;
    if (rows == 1) continue;  // header
    const auto comma = line.find(',');
    sum += std::stod(line.substr(comma + 1));
  }
  CHECK(rows == 1 + 1024 / 2 + 1);  // header, 0 Hz .. Nyquist
  // 127 Hann segments at 50 % overlap: the mean gamma^2 of independent noise
  // is about 1/K_eff (K_eff ~ 120), far below 0.05.
  CHECK(sum / (rows - 1) < 0.05);
  fs::remove_all(dir);
}

TEST_CASE("deb spectrum: missing rate, too few samples, non-uniform stamps and unknown options fail cleanly") {
  const fs::path dir = TempDir("errors");
  const fs::path norate = Recording(dir, "# unit: um/s\n");
  Command r = RunDeb("spectrum welch " + norate.string() + " -o " + (dir / "x.csv").string());
  CHECK(r.exit_code == 3);
  CHECK(r.err.find("missing sample rate") != std::string::npos);
  CHECK_FALSE(fs::exists(dir / "x.csv"));
  r = RunDeb("spectrum welch " + norate.string() + " --rate 200 --segment 100000");
  CHECK(r.exit_code == 3);
  CHECK(r.err.find("too few samples") != std::string::npos);
  std::ofstream(dir / "uneven.csv") << "t, x\n0, 1\n0.1, 2\n0.3, 3\n0.4, 4\n";
  r = RunDeb("spectrum welch " + (dir / "uneven.csv").string());
  CHECK(r.exit_code == 3);
  CHECK(r.err.find("uneven.csv:3:1: non-uniform time stamps") != std::string::npos);
  r = RunDeb("spectrum selfnoise " + norate.string() + " --rate 200 --sensors a");
  CHECK(r.exit_code == 3);
  CHECK(r.err.find("give 2 (Holcomb") != std::string::npos);
  r = RunDeb("spectrum welch " + norate.string() + " --window kaiser --rate 200");
  CHECK(r.exit_code == 3);
  CHECK(r.err.find("allowed: rectangular, hann") != std::string::npos);
  CHECK(RunDeb("spectrum welch").exit_code == 2);
  fs::remove_all(dir);
}
