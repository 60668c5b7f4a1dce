#include "deb/spectra/spectrum_csv.h"

#include <doctest/doctest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "deb/core/error.h"
#include "tests/support/cli_harness.h"

namespace deb {
namespace {

namespace fs = std::filesystem;

SpectrumCsv Parse(const std::string& text, const std::string& name = "floor.csv") {
  std::istringstream in(text);
  return ParseSpectrumCsv(in, name);
}

std::string ErrorOf(const std::string& text) {
  try {
    Parse(text);
  } catch (const InputError& error) {
    return error.what();
  }
  return "(no InputError thrown)";
}

TEST_CASE("a comma-separated file with a header row gives named channels and its declared unit") {
  const SpectrumCsv csv = Parse(
      "# floor velocity, lab 3\n"
      "# unit: um/s\n"
      "f_hz, x, y\n"
      "0.5, 1.0, 2.0\n"
      "1.0, 3.0, 4.0   # trailing comment\n"
      "\n"
      "2.0, 5.0, 6.0\n");
  CHECK(csv.path == "floor.csv");
  CHECK(csv.f_hz == std::vector<double>{0.5, 1.0, 2.0});
  CHECK(csv.channel_names == std::vector<std::string>{"x", "y"});
  REQUIRE(csv.unit.has_value());
  CHECK(*csv.unit == "um/s");
  REQUIRE(csv.psd.rows() == 3);
  REQUIRE(csv.psd.cols() == 2);
  CHECK(csv.psd(1, 0) == 3.0);
  CHECK(csv.psd(2, 1) == 6.0);
  CHECK(csv.quantity == SpectrumQuantity::kPsd);
  CHECK(csv.sides == SpectrumSides::kOne);
}

TEST_CASE("a whitespace-separated file without header gets channels ch1, ch2 and no unit") {
  const SpectrumCsv csv = Parse("1\t2  3\r\n2 4 +5e-1\r\n");
  CHECK(csv.channel_names == std::vector<std::string>{"ch1", "ch2"});
  CHECK_FALSE(csv.unit.has_value());
  CHECK_FALSE(csv.quantity_declared);
  CHECK(csv.psd(1, 1) == 0.5);
}

TEST_CASE("ASD columns are squared and two-sided values doubled at load (exact)") {
  const SpectrumCsv asd = Parse("# quantity: asd\n1, 3\n2, 0.5\n");
  CHECK(asd.quantity == SpectrumQuantity::kAsd);
  CHECK(asd.quantity_declared);
  CHECK(asd.psd(0, 0) == 9.0);
  CHECK(asd.psd(1, 0) == 0.25);
  const SpectrumCsv two = Parse("# sides: two\n1, 20\n2, 20\n");
  CHECK(two.sides == SpectrumSides::kTwo);
  CHECK(two.psd(0, 0) == 40.0);
  const SpectrumCsv both = Parse("# Quantity: ASD\n# sides: two\n1, 3\n2, 3\n");
  CHECK(both.psd(1, 0) == 18.0);  // 2 x 3^2
}

TEST_CASE("a non-numeric cell is reported with file, line, column and the text") {
  const std::string message = ErrorOf("f, x\n1, 2\n2, abc\n");
  CHECK(message.find("floor.csv:3:4:") == 0);
  CHECK(message.find("column 'x'") != std::string::npos);
  CHECK(message.find("'abc' is not a number") != std::string::npos);
}

TEST_CASE("NaN, infinity and an empty cell are rejected with their position") {
  CHECK(ErrorOf("1, 2\n2, nan\n").find("floor.csv:2:4: column 'ch1': 'nan' is not finite") == 0);
  CHECK(ErrorOf("1, 2\ninf, 3\n").find("floor.csv:2:1: frequency: 'inf' is not finite") == 0);
  CHECK(ErrorOf("1, 2, 3\n2, , 3\n").find("floor.csv:2:4:") == 0);
  CHECK(ErrorOf("1, 2, 3\n2, , 3\n").find("empty cell") != std::string::npos);
  CHECK(ErrorOf("1, 1e999\n2, 1\n").find("outside the range") != std::string::npos);
}

TEST_CASE("a negative PSD is rejected naming the value and the column") {
  const std::string message = ErrorOf("f z\n1 2\n2 -1\n");
  CHECK(message.find("floor.csv:3:3:") == 0);
  CHECK(message.find("'-1' in column 'z' is negative") != std::string::npos);
}

TEST_CASE("a non-increasing frequency is rejected quoting both values and lines") {
  const std::string message = ErrorOf("# c\n1, 1\n2, 1\n1.5, 1\n");
  CHECK(message.find("floor.csv:4:1:") == 0);
  CHECK(message.find("frequency 1.5 Hz is not greater than 2 Hz on line 3") != std::string::npos);
  CHECK(ErrorOf("0, 1\n1, 1\n").find("frequency 0 Hz is not > 0") != std::string::npos);
}

TEST_CASE("a row with the wrong number of cells is rejected naming the expected count") {
  const std::string message = ErrorOf("f, x, y\n1, 2, 3\n2, 3\n");
  CHECK(message.find("floor.csv:3:") == 0);
  CHECK(message.find("row has 2 cells; expected 3 as on line 1") != std::string::npos);
  CHECK(ErrorOf("1, 2\n2, 3, 4\n").find("floor.csv:2:7:") == 0);
  CHECK(ErrorOf("f\n1\n").find("needs a frequency and at least one channel") != std::string::npos);
}

TEST_CASE("fewer than two data rows is an error") {
  CHECK(ErrorOf("# only a comment\n").find("floor.csv: 0 data rows") == 0);
  CHECK(ErrorOf("f, x\n1, 2\n").find("1 data rows; a spectrum needs at least 2") != std::string::npos);
}

TEST_CASE("bad or repeated header keys are rejected listing the allowed values") {
  CHECK(ErrorOf("# quantity: rms\n1, 2\n2, 3\n").find("floor.csv:1:13: unknown spectrum quantity 'rms'; allowed: psd, asd") == 0);
  CHECK(ErrorOf("# sides: double\n1, 2\n2, 3\n").find("allowed: one, two") != std::string::npos);
  CHECK(ErrorOf("# unit: m\n# unit: um\n1, 2\n2, 3\n").find("floor.csv:2:") == 0);
  CHECK(ErrorOf("# unit:\n1, 2\n2, 3\n").find("has no value") != std::string::npos);
  // Other "key: value" comments are ordinary comments.
  CHECK_NOTHROW(Parse("# measured: 2015-03-02\n1, 2\n2, 3\n"));
}

TEST_CASE("a spectrum file is read from disk and becomes a measured spectrum that names it") {
  const auto dir = test::TempDir("spectrum_csv");
  const std::string path = (dir / "noise.csv").string();
  {
    std::ofstream out(path);
    out << "# unit: V\n# quantity: asd\nf_hz, amp\n1, 1e-3\n10, 1e-4\n100, 1e-5\n";
  }
  const SpectrumCsv csv = ReadSpectrumCsv(path);
  const auto spectrum = MakeMeasuredSpectrum(csv, Extrapolation::kZero);
  CHECK(spectrum->unit() == "V");
  CHECK(spectrum->channel_names() == std::vector<std::string>{"amp"});
  CHECK(spectrum->Psd(10.0)(0) == doctest::Approx(1e-8).epsilon(1e-15));
  // ASD 1e-3/f is a PSD 1e-6/f^2: log-log interpolation is exact (rel 1e-12).
  CHECK(spectrum->Psd(3.0)(0) == doctest::Approx(1e-6 / 9.0).epsilon(1e-12));
  CHECK(spectrum->Psd(1000.0)(0) == 0.0);
  CHECK(spectrum->Describe().find("noise.csv") != std::string::npos);
  std::filesystem::remove_all(dir);

  try {
    ReadSpectrumCsv(path);
    FAIL("missing file read without error");
  } catch (const InputError& error) {
    CHECK(std::string(error.what()).find(path + ": cannot open") == 0);
  }
}

TEST_CASE("quantity and sides names round-trip") {
  for (auto q : {SpectrumQuantity::kPsd, SpectrumQuantity::kAsd}) CHECK(ParseSpectrumQuantity(ToString(q)) == q);
  for (auto s : {SpectrumSides::kOne, SpectrumSides::kTwo}) CHECK(ParseSpectrumSides(ToString(s)) == s);
}


TEST_CASE("a file may declare that its rows are the bins of a spectral estimate") {
  const SpectrumCsv bins = Parse("# interpolation: bins\n1, 2\n2, 3\n");
  CHECK(bins.interpolation == SpectrumInterpolation::kBins);
  CHECK(MakeMeasuredSpectrum(bins)->Psd(2.4)(0) == 3.0);
  CHECK(Parse("1, 2\n2, 3\n").interpolation == SpectrumInterpolation::kLogLog);
  CHECK(ErrorOf("# interpolation: cubic\n1, 2\n2, 3\n").find("floor.csv:1:18: unknown spectrum interpolation 'cubic'") == 0);
}

TEST_CASE("a written spectrum CSV reads back to the same table (PSD to 1e-10, frequencies exactly)") {
  const std::vector<double> f = {0.0, 0.1, 1.0 + 1e-9, 1.0 + 2e-9, 37.3};
  Eigen::MatrixXd psd(5, 2);
  psd << 9.0, 1.0, 1.234567890123e-7, 4.0, 2.5e-12, 3.0, 2.5e-12, 3.5, 1e300, 0.0;
  const std::string text = SpectrumCsvText({"a comment", "interpolation: bins"}, "um/s", SpectrumQuantity::kPsd, f,
                                           psd, {"x", "y"});
  CHECK(text.find("# a comment\n# interpolation: bins\n# unit: um/s\n# quantity: psd\n# sides: one\nf_hz, x, y\n") == 0);
  const SpectrumCsv back = Parse(text);
  REQUIRE(back.f_hz.size() == 4);  // the 0 Hz row is not written
  for (std::size_t k = 0; k < 4; ++k) CHECK(back.f_hz[k] == f[k + 1]);
  CHECK(back.channel_names == std::vector<std::string>{"x", "y"});
  CHECK(back.unit == std::optional<std::string>("um/s"));
  CHECK(back.interpolation == SpectrumInterpolation::kBins);
  for (Eigen::Index k = 0; k < 4; ++k)
    for (Eigen::Index c = 0; c < 2; ++c)
      CHECK(back.psd(k, c) == doctest::Approx(psd(k + 1, c)).epsilon(1e-10));
}

TEST_CASE("an ASD is written as the square root and read back as the PSD; extra columns follow the channels") {
  const std::vector<double> f = {1.0, 2.0};
  Eigen::MatrixXd psd(2, 1), extra(2, 1);
  psd << 4.0, 0.25;
  extra << 7.0, 8.0;
  const std::string text = SpectrumCsvText({}, "", SpectrumQuantity::kAsd, f, psd, {"z"}, &extra, {"z_hi"});
  CHECK(text == "# quantity: asd\n# sides: one\nf_hz, z, z_hi\n1, 2, 7\n2, 0.5, 8\n");
  const fs::path file = fs::temp_directory_path() / ("deb_spectrum_write_" + std::to_string(::getpid()) + ".csv");
  WriteSpectrumCsv(file.string(), {}, "nm", SpectrumQuantity::kAsd, f, psd, {"z"});
  const SpectrumCsv back = ReadSpectrumCsv(file.string());
  fs::remove(file);
  CHECK(back.quantity == SpectrumQuantity::kAsd);
  CHECK(back.psd(0, 0) == doctest::Approx(4.0).epsilon(1e-12));
  CHECK(back.psd(1, 0) == doctest::Approx(0.25).epsilon(1e-12));
  CHECK_THROWS_AS(WriteSpectrumCsv("/nonexistent-dir/x.csv", {}, "nm", SpectrumQuantity::kPsd, f, psd, {"z"}),
                  WriteError);
}

}  // namespace
}  // namespace deb
