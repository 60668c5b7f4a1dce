// Internal: not part of the public API.
// A plot that stands on its own beside the data file it shows, as the
// commands that write one CSV (`deb spectrum ...`) draw them: for the stem
// "psd" in a directory, psd.png (and/or .svg, .pdf), the script psd.gp and
// the data it reads, psd.plot.csv (never psd.csv, which is usually the
// command's own output). The script is the same text for every format, so a
// reader can redraw or restyle it with `gnuplot -e "set terminal ..." psd.gp`.
//
// Plots are drawn into a hidden directory beside their final place and moved
// there only by Commit(), after every plot has been drawn: a missing or
// failing gnuplot leaves no file behind, and a rename within one directory
// never leaves a half-written image.
#pragma once

#include <string>
#include <vector>

#include "deb/report/figure/plot.h"
#include "deb/report/figure/report_options.h"

namespace deb::report {

// The data file the script of a standalone plot named `name` reads.
std::string StandaloneDataFile(const std::string& name);  // "<name>.plot.csv"

struct StandalonePlot {
  Plot plot;              // plot.name is the stem of its files (no directory)
  std::string directory;  // where the files go; "" is the working directory
};

// Every path a standalone plot writes: data, script, then one per format.
std::vector<std::string> StandalonePlotPaths(const StandalonePlot& plot, const std::vector<PlotFormat>& formats);

class StagedPlots {
 public:
  // Draws every plot in every format with gnuplot (FindGnuplot(gnuplot):
  // "" means $DEB_GNUPLOT, else gnuplot on PATH), each into a hidden
  // temporary directory inside its directory, which must exist; `threads`
  // gnuplot processes at a time (<= 0: DefaultThreadCount()).
  // @throws InputError if formats is empty or repeats one; WriteError if gnuplot is
  //   missing or fails (naming the plot), or a file cannot be written; the
  //   temporary directories are removed first.
  StagedPlots(const std::vector<StandalonePlot>& plots, const std::vector<PlotFormat>& formats,
              const std::string& gnuplot = "", int threads = 0);
  // Removes whatever has not been committed.
  ~StagedPlots();
  StagedPlots(const StagedPlots&) = delete;
  StagedPlots& operator=(const StagedPlots&) = delete;

  // Moves every file into place, replacing older files of the same name,
  // and returns their paths (as StandalonePlotPaths).
  // @throws InputError naming the file that cannot be moved.
  std::vector<std::string> Commit();

 private:
  struct Move {
    std::string from, to;
  };
  std::vector<std::string> temporary_dirs_;
  std::vector<Move> moves_;
};

}  // namespace deb::report
