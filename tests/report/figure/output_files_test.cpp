#include "deb/report/figure/output_files.h"

#include <doctest/doctest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "deb/core/error.h"

namespace deb::report {
namespace {

namespace fs = std::filesystem;

struct TempDir {
  fs::path path = fs::temp_directory_path() / ("deb_output_files_" + std::to_string(::getpid()));
  TempDir() {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() { fs::remove_all(path); }
  std::string operator/(const std::string& name) const { return (path / name).string(); }
};

std::string Read(const std::string& file) {
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

report::Plot SomePlot(const std::string& name) {
  report::Plot p;
  p.name = name;
  p.csv = "1, 2\n";
  p.script = "plot '" + name + ".plot.csv' using 1:2\n";
  return p;
}

TEST_CASE("text outputs are written to their files and to the standard output stream, in order") {
  const TempDir dir;
  OutputFiles files;
  files.Text(dir / "a.csv", "A\n", "the output CSV");
  files.Text("-", "to stdout\n", "standard output");
  files.Text(dir / "b.csv", "B\n", "the second CSV");
  std::ostringstream out;
  const std::vector<std::string> written = files.Write({}, out);
  CHECK(written == std::vector<std::string>{dir / "a.csv", dir / "b.csv"});
  CHECK(Read(dir / "a.csv") == "A\n");
  CHECK(Read(dir / "b.csv") == "B\n");
  CHECK(out.str() == "to stdout\n");
  for (const auto& e : fs::directory_iterator(dir.path))  // no temporary left
    CHECK(e.path().filename().string().find(".tmp-") == std::string::npos);
}

TEST_CASE("two outputs with one name are refused before anything is written") {
  const TempDir dir;
  OutputFiles files("; name them apart");
  files.Text(dir / "x.csv", "1\n", "the output CSV (-o)");
  files.Text(dir / "sub/../x.csv", "2\n", "the coherence CSV");
  std::ostringstream out;
  CHECK_THROWS_WITH_AS(files.Write({}, out),
                       (dir / "sub/../x.csv" + " would be written twice: as the output CSV (-o) and as the coherence "
                                               "CSV; name them apart").c_str(),
                       InputError);
  CHECK_FALSE(fs::exists(dir / "x.csv"));
  OutputFiles with_plot;
  with_plot.Text(dir / "p.png", "text\n", "the output CSV (-o)");
  with_plot.Plot(dir.path.string(), SomePlot("p"));
  CHECK_THROWS_WITH_AS(with_plot.Write({PlotFormat::kPng}, out),
                       doctest::Contains("would be written twice: as the output CSV (-o) and as a file of the plot p"),
                       InputError);
}

TEST_CASE("a file that cannot be written leaves the others unwritten and no temporary behind") {
  const TempDir dir;
  OutputFiles files;
  files.Text(dir / "good.csv", "G\n", "the output CSV");
  files.Text(dir / "missing/bad.csv", "B\n", "the other CSV");
  std::ostringstream out;
  CHECK_THROWS_WITH_AS(files.Write({}, out), doctest::Contains("missing/bad.csv: cannot write the output file"),
                       WriteError);
  CHECK(fs::is_empty(dir.path));
  CHECK(out.str().empty());
}

TEST_CASE("a missing gnuplot fails before any text file is written") {
  const TempDir dir;
  OutputFiles files;
  files.Text(dir / "psd.csv", "data\n", "the output CSV (-o)");
  files.Plot(dir.path.string(), SomePlot("psd"));
  CHECK(files.has_plots());
  std::ostringstream out;
  CHECK_THROWS_AS(files.Write({PlotFormat::kPng}, out, dir / "no-gnuplot"), WriteError);
  CHECK(fs::is_empty(dir.path));
}

}  // namespace
}  // namespace deb::report
