// Internal: not part of the public API.
// Everything one command writes beside its main data: text files (or the
// standard output) and standalone plots (plot_files.h), written as one
// transaction. Write() draws the plots first, in hidden directories, then
// writes every file through a temporary name beside it and renames them all,
// so that a missing gnuplot or an unwritable file leaves nothing
// half-written; two outputs with one name are refused before anything is
// written.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "deb/report/figure/plot.h"
#include "deb/report/figure/plot_files.h"
#include "deb/report/figure/report_options.h"

namespace deb::report {

class OutputFiles {
 public:
  // collision_hint ends the message that refuses two outputs with one name
  // (e.g. how to name them apart).
  explicit OutputFiles(std::string collision_hint = "") : collision_hint_(std::move(collision_hint)) {}

  // path "" or "-": the standard output stream given to Write(). `what`
  // names the file in messages ("the output CSV (-o)").
  void Text(const std::string& path, std::string text, const std::string& what);
  // A plot drawn into `directory`; plot.name is the stem of its files.
  void Plot(const std::string& directory, report::Plot plot);
  bool has_plots() const { return !plots_.empty(); }

  // Writes everything, the plots in `formats` (unused without plots), the
  // texts for the standard output to `standard_output`; gnuplot and
  // `threads` (gnuplot processes at a time) as for StagedPlots. Returns the
  // paths written, texts first.
  // @throws InputError if two outputs share a name (nothing is written);
  //   WriteError if a file cannot be written or gnuplot fails (the files of
  //   this call are removed, older ones stay).
  std::vector<std::string> Write(const std::vector<PlotFormat>& formats, std::ostream& standard_output,
                                 const std::string& gnuplot = "", int threads = 0);

 private:
  struct File {
    std::string path, text, what;
  };
  void RefuseCollisions(const std::vector<PlotFormat>& formats) const;

  std::string collision_hint_;
  std::vector<File> texts_;
  std::vector<StandalonePlot> plots_;
};

}  // namespace deb::report
