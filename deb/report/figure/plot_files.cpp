#include "deb/report/figure/plot_files.h"

#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>

#include "deb/core/error.h"
#include "deb/core/output_dir.h"
#include "deb/core/parallel.h"
#include "deb/report/figure/gnuplot_runner.h"
#include "deb/report/figure/plot_style.h"

namespace deb::report {
namespace fs = std::filesystem;
namespace {

fs::path Directory(const StandalonePlot& p) { return p.directory.empty() ? fs::path(".") : fs::path(p.directory); }

std::vector<std::string> FileNames(const std::string& name, const std::vector<PlotFormat>& formats) {
  std::vector<std::string> names = {StandaloneDataFile(name), name + ".gp"};
  for (PlotFormat f : formats) names.push_back(name + "." + FileExtension(f));
  return names;
}

// A fresh hidden directory inside `parent`, named after the plot.
fs::path MakeTemporaryDirectory(const fs::path& parent, const std::string& name) {
  static std::atomic<int> counter{0};
  for (int attempt = 0; attempt < 100; ++attempt) {
    const fs::path dir = parent / ("." + name + ".deb-plot-" + std::to_string(::getpid()) + "-" +
                                   std::to_string(counter++));
    std::error_code ec;
    if (fs::create_directory(dir, ec)) return dir;
    if (ec && ec != std::errc::file_exists)
      throw WriteError("cannot draw plot " + name + ": cannot create a directory in " + parent.string() + ": " +
                       ec.message());
  }
  throw WriteError("cannot draw plot " + name + ": no free temporary directory name in " + parent.string());
}

}  // namespace

std::string StandaloneDataFile(const std::string& name) { return name + ".plot.csv"; }

std::vector<std::string> StandalonePlotPaths(const StandalonePlot& plot, const std::vector<PlotFormat>& formats) {
  std::vector<std::string> paths;
  for (const std::string& f : FileNames(plot.plot.name, formats))
    paths.push_back(plot.directory.empty() ? f : (fs::path(plot.directory) / f).string());
  return paths;
}

StagedPlots::StagedPlots(const std::vector<StandalonePlot>& plots, const std::vector<PlotFormat>& formats,
                         const std::string& gnuplot, int threads) {
  ReportOptions check;  // the same rules as the formats of a report
  check.formats = formats;
  std::string why;
  if (!check.IsValid(&why)) throw InputError("plots: " + why);
  if (plots.empty()) return;
  try {
    const std::string executable = FindGnuplot(gnuplot);
    struct Draw {
      std::string dir, script, file, what;
      PlotFormat format;
    };
    std::vector<Draw> draws;
    for (const StandalonePlot& p : plots) {
      const std::vector<std::string> names = FileNames(p.plot.name, formats);
      const std::vector<std::string> paths = StandalonePlotPaths(p, formats);
      std::error_code ec;
      if (!fs::is_directory(Directory(p), ec))
        throw WriteError(p.directory + ": no such directory, for the plot " + paths.back());
      const fs::path dir = MakeTemporaryDirectory(Directory(p), p.plot.name);
      temporary_dirs_.push_back(dir.string());
      WriteTextFile((dir / StandaloneDataFile(p.plot.name)).string(), p.plot.csv);
      WriteGnuplotScript((dir / (p.plot.name + ".gp")).string(), p.plot.script);
      for (PlotFormat t : formats) {
        const std::string file = p.plot.name + "." + FileExtension(t);
        // One gnuplot per file: a PDF of one page, a PNG or an SVG.
        draws.push_back({dir.string(), FormatDrawCommands(t, file, p.plot.name + ".gp"),
                         file, "plot " + (p.directory.empty() ? file : (fs::path(p.directory) / file).string()), t});
      }
      for (std::size_t i = 0; i < names.size(); ++i) moves_.push_back({(dir / names[i]).string(), paths[i]});
    }
    ParallelForEach(
        draws.size(),
        [&](std::size_t i) {
          const Draw& d = draws[i];
          RunGnuplot(executable, d.dir, d.script, d.what);
          const fs::path made = fs::path(d.dir) / d.file;
          std::error_code ec;
          if (!fs::is_regular_file(fs::path(d.dir) / GnuplotOutputFile(d.format, d.file), ec))
            throw WriteError("cannot draw " + d.what + ": gnuplot reported success but wrote no " + d.file);
          FinishPlotFile(d.format, made.string());
          if (!fs::is_regular_file(made, ec) || fs::file_size(made, ec) == 0)
            throw WriteError("cannot draw " + d.what + ": gnuplot reported success but wrote no " + d.file);
        },
        threads);
  } catch (...) {
    for (const std::string& d : temporary_dirs_) {
      std::error_code ec;
      fs::remove_all(d, ec);
    }
    temporary_dirs_.clear();
    moves_.clear();
    throw;
  }
}

StagedPlots::~StagedPlots() {
  for (const std::string& d : temporary_dirs_) {
    std::error_code ec;
    fs::remove_all(d, ec);
  }
}

std::vector<std::string> StagedPlots::Commit() {
  std::vector<std::string> written;
  for (const Move& m : moves_) {
    std::error_code ec;
    fs::rename(m.from, m.to, ec);
    if (ec) throw InputError(m.to + ": cannot be written: " + ec.message());
    written.push_back(m.to);
  }
  moves_.clear();
  for (const std::string& d : temporary_dirs_) {
    std::error_code ec;
    fs::remove_all(d, ec);
  }
  temporary_dirs_.clear();
  return written;
}

}  // namespace deb::report
