// The plots of `deb spectrum ...`: beside the CSV (-o psd.csv -> psd.png,
// psd.gp, psd.plot.csv), where --plot names them, in every --plot-format;
// none with --no-plots or on standard output; and no file at all when
// gnuplot is missing or fails.
#include <doctest/doctest.h>

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <set>
#include <sstream>
#include <string>

#include "tests/support/cli_harness.h"

namespace fs = std::filesystem;
using namespace deb::test;

namespace {

std::set<std::string> Files(const fs::path& dir) {
  std::set<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.insert(e.path().filename().string());
  return names;
}

bool IsPng(const fs::path& p) {
  const std::string s = ReadAll(p);
  return s.size() > 100 && s.compare(0, 8, std::string("\x89PNG\r\n\x1a\n", 8)) == 0;
}

// Two sensors at 200 Hz seeing the same ground motion, each with its own noise.
void WriteRecording(const fs::path& dir) {
  std::ofstream out(dir / "rec.csv");
  out << "# rate_hz: 200\n# unit: um/s\na, b\n";
  std::mt19937_64 rng(11);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (int i = 0; i < 4096; ++i) {
    const double u = normal(rng);
    out << u + 0.1 * normal(rng) << ", " << u + 0.1 * normal(rng) << "\n";
  }
}

// A floor at VC-D in the 8-63 Hz bands, as a band RMS table.
void WriteVcdTable(const fs::path& dir) {
  std::ofstream table(dir / "vcd.csv");
  table << "# unit: um/s\ncentre_hz, floor\n";
  for (double f : {8.0, 10.0, 12.5, 16.0, 20.0, 25.0, 31.5, 40.0, 50.0, 63.0}) table << f << ", 6.25\n";
}

// A stand-in for gnuplot that reads its commands and fails as gnuplot does.
fs::path FailingGnuplot(const fs::path& dir) {
  const fs::path exe = dir / "fake-gnuplot";
  std::ofstream(exe) << "#!/bin/sh\ncat > /dev/null\necho '\"psd.gp\" line 3: undefined variable: nonsense' >&2\n"
                        "exit 1\n";
  ::chmod(exe.c_str(), 0755);
  return exe;
}

}  // namespace

TEST_CASE("deb spectrum welch draws the PSD beside -o and the coherence beside --coherence") {
  const fs::path dir = TempDir("welch");
  WriteRecording(dir);
  const Command r = RunDebIn(dir, "spectrum welch rec.csv --segment 256 --bounds -o psd.csv --coherence coh.csv");
  REQUIRE_MESSAGE(r.exit_code == 0, r.err);
  CHECK(Files(dir) == std::set<std::string>{"rec.csv", "psd.csv", "psd.png", "psd.gp", "psd.plot.csv", "coh.csv",
                                            "coh.png", "coh.gp", "coh.plot.csv"});
  CHECK(IsPng(dir / "psd.png"));
  CHECK(IsPng(dir / "coh.png"));
  const std::string script = ReadAll(dir / "psd.gp");
  CHECK(script.find("'psd.plot.csv'") != std::string::npos);
  CHECK(script.find("set logscale x") != std::string::npos);
  CHECK(script.find("set logscale y") != std::string::npos);
  CHECK(script.find("(µm/s)^{2}/Hz") != std::string::npos);
  CHECK(script.find("256-sample segments") != std::string::npos);
  CHECK(script.find("filledcurves") != std::string::npos);  // the chi-square interval
  CHECK(ReadAll(dir / "psd.plot.csv").find("f_hz,a,a_lo,a_hi,b,b_lo,b_hi\n") != std::string::npos);
  CHECK(ReadAll(dir / "coh.gp").find("set yrange [0:1.02]") != std::string::npos);
  CHECK(r.out.find("wrote psd.csv, coh.csv, psd.plot.csv, psd.gp, psd.png") != std::string::npos);
  fs::remove_all(dir);
}

TEST_CASE("deb spectrum bands draws the band RMS against the criteria with the class and limiting band in the title") {
  const fs::path dir = TempDir("bands");
  WriteVcdTable(dir);
  REQUIRE(RunDebIn(dir, "spectrum convert --from-bands vcd.csv -o floor.csv").exit_code == 0);
  CHECK(IsPng(dir / "floor.png"));
  const Command r = RunDebIn(dir, "spectrum bands floor.csv --lowest 8 --highest 50 --criteria vc -o bands.csv");
  REQUIRE_MESSAGE(r.exit_code == 0, r.err);
  CHECK(IsPng(dir / "bands.png"));
  const std::string script = ReadAll(dir / "bands.gp");
  CHECK(script.find("VC-D met; limiting band") != std::string::npos);
  CHECK(script.find("'VC-A' 50") != std::string::npos);  // criteria named on the right axis at their level
  CHECK(script.find("with steps") != std::string::npos);
  CHECK(ReadAll(dir / "bands.plot.csv").find("criterion,level_um_s,from_hz,to_hz,met\nVC-A,50,") != std::string::npos);
  fs::remove_all(dir);
}

TEST_CASE("deb spectrum selfnoise, convert and reference each draw their spectrum") {
  const fs::path dir = TempDir("others");
  WriteRecording(dir);
  Command r = RunDebIn(dir, "spectrum selfnoise rec.csv --sensors a,b --segment 256 -o noise.csv");
  REQUIRE_MESSAGE(r.exit_code == 0, r.err);
  CHECK(IsPng(dir / "noise.png"));
  CHECK(ReadAll(dir / "noise.plot.csv").find("f_hz,a,a_noise,b,b_noise\n") != std::string::npos);
  r = RunDebIn(dir, "spectrum convert noise.csv --to nm --asd -o asd.csv");
  REQUIRE_MESSAGE(r.exit_code == 0, r.err);
  CHECK(IsPng(dir / "asd.png"));
  CHECK(ReadAll(dir / "asd.gp").find("ASD [nm/√Hz]") != std::string::npos);
  r = RunDebIn(dir, "spectrum reference nlnm --to um/s -o nlnm.csv");
  REQUIRE_MESSAGE(r.exit_code == 0, r.err);
  CHECK(IsPng(dir / "nlnm.png"));
  CHECK(ReadAll(dir / "nlnm.plot.csv").find("f_hz,nhnm,nlnm\n") != std::string::npos);  // both models
  fs::remove_all(dir);
}

TEST_CASE("--no-plots writes the CSV only and needs no gnuplot") {
  const fs::path dir = TempDir("noplots");
  WriteRecording(dir);
  const Command r = RunDebIn(dir, "spectrum welch rec.csv --segment 256 -o psd.csv --coherence coh.csv --no-plots",
                    "DEB_GNUPLOT=/nonexistent/gnuplot");
  REQUIRE_MESSAGE(r.exit_code == 0, r.err);
  CHECK(Files(dir) == std::set<std::string>{"rec.csv", "psd.csv", "coh.csv"});
  CHECK(RunDebIn(dir, "spectrum reference nlnm -o n.csv --no-plots --plot n.png").exit_code == 2);
  fs::remove_all(dir);
}

TEST_CASE("a CSV on standard output has no plot unless --plot names one, in the format of its extension") {
  const fs::path dir = TempDir("stdout");
  Command r = RunDebIn(dir, "spectrum reference nhnm");
  REQUIRE(r.exit_code == 0);
  CHECK(Files(dir).empty());
  r = RunDebIn(dir, "spectrum reference nhnm --plot models.svg");
  REQUIRE_MESSAGE(r.exit_code == 0, r.err);
  CHECK(r.out.rfind("# Peterson", 0) == 0);  // the CSV alone on standard output
  CHECK(r.out.find("wrote") == std::string::npos);
  CHECK(r.err.find("wrote models.plot.csv, models.gp, models.svg") != std::string::npos);
  CHECK(Files(dir) == std::set<std::string>{"models.plot.csv", "models.gp", "models.svg"});
  CHECK(ReadAll(dir / "models.svg").find("<svg") != std::string::npos);
  fs::remove_all(dir);
}

TEST_CASE("--plot-format writes every format asked for, and --plot must agree with it") {
  const fs::path dir = TempDir("formats");
  const Command r = RunDebIn(dir, "spectrum reference nlnm -o n.csv --plot-format png,svg,pdf");
  REQUIRE_MESSAGE(r.exit_code == 0, r.err);
  CHECK(IsPng(dir / "n.png"));
  CHECK(ReadAll(dir / "n.svg").find("<svg") != std::string::npos);
  CHECK(ReadAll(dir / "n.pdf").rfind("%PDF", 0) == 0);
  CHECK(RunDebIn(dir, "spectrum reference nlnm -o m.csv --plot m.svg --plot-format png").exit_code == 3);
  CHECK(RunDebIn(dir, "spectrum reference nlnm -o m.csv --plot m.gif").exit_code == 2);
  CHECK(RunDebIn(dir, "spectrum reference nlnm -o m.csv --plot-format gif").exit_code == 2);
  CHECK_FALSE(fs::exists(dir / "m.csv"));
  fs::remove_all(dir);
}

TEST_CASE("a missing gnuplot is a clear error with a non-zero exit, and nothing is written") {
  const fs::path dir = TempDir("missing");
  WriteRecording(dir);
  const Command r = RunDebIn(dir, "spectrum welch rec.csv --segment 256 -o psd.csv --coherence coh.csv",
                    "DEB_GNUPLOT=/nonexistent/gnuplot");
  CHECK(r.exit_code == 4);
  CHECK(r.err.find("gnuplot executable '/nonexistent/gnuplot' (from DEB_GNUPLOT)") != std::string::npos);
  CHECK(r.err.find("--no-plots") != std::string::npos);
  CHECK(Files(dir) == std::set<std::string>{"rec.csv"});
  fs::remove_all(dir);
}

TEST_CASE("a failing gnuplot quotes gnuplot, keeps the older outputs and leaves no temporary file") {
  const fs::path dir = TempDir("failing");
  WriteRecording(dir);
  REQUIRE(RunDebIn(dir, "spectrum welch rec.csv --segment 256 -o psd.csv").exit_code == 0);
  const std::string csv = ReadAll(dir / "psd.csv"), png = ReadAll(dir / "psd.png");
  const fs::path fake = TempDir("fake");
  const Command r = RunDebIn(dir, "spectrum welch rec.csv --segment 128 -o psd.csv",
                    "DEB_GNUPLOT=" + FailingGnuplot(fake).string());
  fs::remove_all(fake);
  CHECK(r.exit_code == 4);
  CHECK(r.err.find("cannot draw plot psd.png") != std::string::npos);
  CHECK(r.err.find("undefined variable: nonsense") != std::string::npos);
  CHECK(ReadAll(dir / "psd.csv") == csv);
  CHECK(ReadAll(dir / "psd.png") == png);
  CHECK(Files(dir) == std::set<std::string>{"rec.csv", "psd.csv", "psd.png", "psd.gp", "psd.plot.csv"});
  fs::remove_all(dir);
}

TEST_CASE("an output and a plot file of the same name are refused before anything is written") {
  const fs::path dir = TempDir("collide");
  const Command r = RunDebIn(dir, "spectrum reference nlnm -o n.png");
  CHECK(r.exit_code == 3);
  CHECK(r.err.find("n.png would be written twice") != std::string::npos);
  CHECK(Files(dir).empty());
  fs::remove_all(dir);
}

TEST_CASE("a segment too short to give a spectrum is refused: exit 3, naming the rule, nothing written") {
  const fs::path dir = TempDir("onebin");
  WriteRecording(dir);
  for (const char* plots : {"", " --no-plots"}) {
    const Command r = RunDebIn(dir, std::string("spectrum welch rec.csv --segment 2 -o psd.csv") + plots);
    CHECK(r.exit_code == 3);
    CHECK(r.err.find("segment_length 2 is invalid; a segment needs at least 16 samples") != std::string::npos);
    CHECK(Files(dir) == std::set<std::string>{"rec.csv"});
  }
  fs::remove_all(dir);
}
