#include "deb/report/figure/output_files.h"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <optional>
#include <ostream>
#include <set>
#include <utility>

#include "deb/core/error.h"
#include "deb/core/output_dir.h"

namespace deb::report {
namespace {

namespace fs = std::filesystem;

bool IsStandardOutput(const std::string& path) { return path.empty() || path == "-"; }

}  // namespace

void OutputFiles::Text(const std::string& path, std::string text, const std::string& what) {
  texts_.push_back({path, std::move(text), what});
}

void OutputFiles::Plot(const std::string& directory, report::Plot plot) {
  plots_.push_back({std::move(plot), directory});
}

// Two outputs with one name would overwrite each other (e.g. -o psd.png).
void OutputFiles::RefuseCollisions(const std::vector<PlotFormat>& formats) const {
  std::vector<std::pair<std::string, std::string>> named;  // path, what
  for (const File& f : texts_)
    if (!IsStandardOutput(f.path)) named.push_back({f.path, f.what});
  for (const StandalonePlot& p : plots_)
    for (const std::string& path : StandalonePlotPaths(p, formats))
      named.push_back({path, "a file of the plot " + p.plot.name});
  std::set<std::string> seen;
  for (std::size_t i = 0; i < named.size(); ++i) {
    const std::string key = fs::absolute(named[i].first).lexically_normal().string();
    if (seen.insert(key).second) continue;
    for (std::size_t j = 0; j < i; ++j)
      if (fs::absolute(named[j].first).lexically_normal().string() == key)
        throw InputError(named[i].first + " would be written twice: as " + named[j].second + " and as " +
                         named[i].second + collision_hint_);
  }
}

std::vector<std::string> OutputFiles::Write(const std::vector<PlotFormat>& formats, std::ostream& standard_output,
                                            const std::string& gnuplot, int threads) {
  RefuseCollisions(formats);
  std::optional<StagedPlots> staged;
  if (!plots_.empty()) staged.emplace(plots_, formats, gnuplot, threads);
  std::vector<std::pair<std::string, std::string>> renames;  // temporary, final
  const auto discard = [&] {
    for (const auto& rename : renames) std::remove(rename.first.c_str());
  };
  for (const File& f : texts_) {
    if (IsStandardOutput(f.path)) continue;
    // Beside the output, so that the rename stays in one file system; a
    // link or file planted at that name is removed, never written through.
    const std::string tmp = f.path + ".tmp-" + std::to_string(::getpid());
    std::remove(tmp.c_str());
    try {
      WriteTextFile(tmp, f.text);
    } catch (const WriteError& e) {
      discard();
      throw WriteError(f.path + ": cannot write the output file (" + e.what() + ")");
    }
    renames.push_back({tmp, f.path});
  }
  std::vector<std::string> written;
  for (const auto& rename : renames) {
    std::error_code ec;
    fs::rename(rename.first, rename.second, ec);
    if (ec) {
      discard();
      throw WriteError(rename.second + ": cannot write the output file: " + ec.message());
    }
    written.push_back(rename.second);
  }
  for (const File& f : texts_)
    if (IsStandardOutput(f.path)) standard_output << f.text;
  if (staged)
    for (std::string& p : staged->Commit()) written.push_back(std::move(p));
  return written;
}

}  // namespace deb::report
