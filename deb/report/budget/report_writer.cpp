#include "deb/report/budget/report_writer.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <functional>
#include <future>
#include <map>
#include <mutex>
#include <optional>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "deb/budget/groups.h"
#include "deb/core/document_date.h"
#include "deb/core/error.h"
#include "deb/core/input_file.h"
#include "deb/core/limits.h"
#include "deb/core/output_dir.h"
#include "deb/core/parallel.h"
#include "deb/results/result_store.h"
#include "deb/report/budget/band_plots.h"
#include "deb/report/budget/band_text.h"
#include "deb/report/budget/figure_traces.h"
#include "deb/report/budget/file_digest.h"
#include "deb/report/budget/loop_plots.h"
#include "deb/report/budget/overview_plots.h"
#include "deb/report/budget/path_plots.h"
#include "deb/report/budget/report_documents.h"
#include "deb/report/budget/report_pdf.h"
#include "deb/report/budget/spectrum_plots.h"
#include "deb/report/figure/gnuplot_runner.h"
#include "deb/report/figure/plot_style.h"
#include "deb/version.h"

namespace deb {
namespace fs = std::filesystem;
using namespace report;

namespace {

class Writer {
 public:
  Writer(fs::path root, ReportManifest* manifest) : root_(std::move(root)), manifest_(manifest) {}
  void Write(const std::string& relative, const std::string& text) {
    WriteTextFile((root_ / relative).string(), text);
    manifest_->files.push_back(relative);
  }
  void WriteScript(const std::string& relative, const std::string& script) {
    WriteGnuplotScript((root_ / relative).string(), script);
    manifest_->files.push_back(relative);
  }

 private:
  fs::path root_;
  ReportManifest* manifest_;
};

// Progress on stderr as one rewritten line; nothing unless enabled.
class Progress {
 public:
  Progress(bool enabled, int steps) : enabled_(enabled && steps > 0), steps_(steps) {}
  ~Progress() {
    if (enabled_) std::fprintf(stderr, "\r%-78s\r", "");
  }
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;
  // Announces `what`, which draws `files` of the steps.
  void Step(const std::string& what, int files = 1) {
    if (!enabled_) return;
    const std::lock_guard<std::mutex> lock(mutex_);
    const int first = done_ + 1;
    done_ += files;
    const std::string range = files > 1 ? std::to_string(first) + "-" + std::to_string(done_) : std::to_string(first);
    std::fprintf(stderr, "\rdeb: drawing %s/%d %-50.50s", range.c_str(), steps_, what.c_str());
    std::fflush(stderr);
  }

 private:
  bool enabled_;
  int steps_, done_ = 0;
  std::mutex mutex_;
};


std::string ColoursCsv(const BudgetOutline& budget) {
  std::ostringstream s;
  s << "# deb " << DEB_VERSION << ": style of each contributor in every plot, keyed by its index in the budget;"
    << " then of each group (its path and '/', as the plots name it \"name/\"), after the contributors\n";
  s << "index,contributor,colour,edge_colour,dash,lightness,fill_pattern,hatch_colour\n";
  const auto row = [&](std::size_t index, const std::string& name, const SeriesStyle& st) {
    s << index << ',' << CsvField(name) << ',' << st.colour << ',' << st.edge_colour << ',' << CsvField(st.dash) << ','
      << st.lightness << ',' << st.fill_pattern << ',' << st.hatch_colour << '\n';
  };
  const std::size_t n = budget.contributors.size();
  for (std::size_t c = 0; c < n; ++c) row(c, budget.contributors[c].name, ContributorStyle(c));
  // The groups in the order the plots number them (every output has every contributor, in budget order).
  OutputResult names;
  for (const Contributor& c : budget.contributors) {
    names.contributors.emplace_back();
    names.contributors.back().name = c.name;
    names.contributors.back().group = c.group;
  }
  const std::vector<GroupResult> groups = ComputeGroups(names);
  for (std::size_t g = 0; g < groups.size(); ++g) row(n + g, groups[g].path + "/", GroupStyle(n, g));
  return s.str();
}

void RequireFile(const fs::path& path, const std::string& what) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec) || fs::file_size(path, ec) == 0)
    throw WriteError("cannot draw " + what + ": gnuplot reported success but wrote no " + path.filename().string());
}

// Every figure of the report: the overview, then per output its spectra and
// bands, then the paths and the loops.
std::vector<Plot> ReportPlots(const BudgetResult& result, const ReportOptions& options) {
  std::vector<Plot> plots = OverviewFigures(result, options.digits);
  for (std::size_t o = 0; o < result.outputs.size(); ++o) {
    for (Plot& p : SpectrumPlots(result, o, options)) plots.push_back(std::move(p));
    plots.push_back(BandsPlot(result, o, options.digits));
  }
  for (Plot& p : PathPlots(result, options.threads)) plots.push_back(std::move(p));
  for (Plot& p : LoopPlots(result, options.digits)) plots.push_back(std::move(p));
  return plots;
}

// One file gnuplot draws: its path relative to the report directory, its
// format and the commands that draw it from the plot's script (into
// GnuplotOutputFile: a PNG's SVG source).
struct DrawJob {
  std::string file;
  PlotFormat format = PlotFormat::kSvg;
  std::string script;
};

// The figures of report.pdf first (when `pdf`; their number in `pdf_jobs`),
// then the PNG and SVG plots.
std::vector<DrawJob> DrawJobs(const std::vector<Plot>& plots, const ReportOptions& options, bool pdf,
                              std::size_t* pdf_jobs) {
  std::vector<DrawJob> jobs;
  // report.pdf places each plot as an SVG drawn for it, in a folder removed
  // once the document is written.
  if (pdf)
    for (const Plot& p : plots)
      if (DrawnInPdf(p))
        jobs.push_back(
            {"plots/" + std::string(kPdfFigureDir) + "/" + p.name + ".svg", PlotFormat::kSvg, PdfFigureCommands(p)});
  *pdf_jobs = jobs.size();
  for (PlotFormat t : {PlotFormat::kPng, PlotFormat::kSvg}) {
    if (!options.Has(t)) continue;
    for (const Plot& p : plots) {
      const std::string file = p.name + "." + FileExtension(t);
      jobs.push_back({"plots/" + file, t, FormatDrawCommands(t, file, p.name + ".gp")});
    }
  }
  return jobs;
}

// gnuplot starts fast but each process pays again for fonts: the files are
// drawn in a few batches, one process each: when `pdf`, the first
// `pdf_jobs` (the figures of report.pdf) in one batch and the others in
// `workers` - 1, else all in `workers`.
std::vector<std::vector<std::size_t>> DrawBatches(bool pdf, std::size_t pdf_jobs, std::size_t jobs,
                                                  std::size_t workers) {
  std::vector<std::vector<std::size_t>> batches;
  if (pdf) {
    batches.emplace_back();
    for (std::size_t i = 0; i < pdf_jobs; ++i) batches.back().push_back(i);
  }
  const std::size_t plot_jobs = jobs - pdf_jobs;
  const std::size_t plot_batches = std::min(std::max<std::size_t>(1, workers - batches.size()), plot_jobs);
  for (std::size_t b = 0; b < plot_batches; ++b) {
    std::vector<std::size_t> batch;
    for (std::size_t i = pdf_jobs + b * plot_jobs / plot_batches; i < pdf_jobs + (b + 1) * plot_jobs / plot_batches;
         ++i)
      batch.push_back(i);
    batches.push_back(std::move(batch));
  }
  return batches;
}

// What report.pdf is typeset from.
ReportPdfInputs PdfInputs(const BudgetResult& result, const ReportFacts& facts, const std::string& sha256,
                          std::time_t when, const std::vector<Plot>& plots, const fs::path& root,
                          const ReportOptions& options) {
  ReportPdfInputs in;
  in.result = &result;
  in.facts = facts;
  in.sha256 = sha256;
  in.create_date = UtcText(when, "%Y-%m-%dT%H:%M:%SZ");
  in.plots = &plots;
  in.figure_dir = (root / "plots" / kPdfFigureDir).string();
  in.digits = options.digits;
  return in;
}

// Draws every plot file and, when `pdf`, typesets report.pdf from the
// figures drawn for it; lists what it wrote in `manifest`. gnuplot writes
// SVG only, a fraction of the time: the work is report.pdf's typesetting
// and the PNGs' rasterising (FinishPlotFile), run as jobs of their own on
// the workers: report.pdf's batch typesets the document when it is drawn,
// while the other workers draw the plots' batches and then take the PNGs,
// one job each, which wait for their batch.
void DrawReport(const BudgetResult& result, const std::vector<Plot>& plots, const ReportFacts& facts,
                const std::string& sha256, std::time_t when, const ReportOptions& options, bool pdf,
                const fs::path& root, ReportManifest& manifest) {
  const fs::path plots_dir = root / "plots";
  const std::string gnuplot = FindGnuplot(options.gnuplot);
  if (pdf) {
    std::error_code ec;
    fs::create_directories(plots_dir / kPdfFigureDir, ec);
    if (ec) throw WriteError("cannot create directory " + (plots_dir / kPdfFigureDir).string() + ": " + ec.message());
  }
  std::size_t pdf_jobs = 0;
  const std::vector<DrawJob> jobs = DrawJobs(plots, options, pdf, &pdf_jobs);
  const std::size_t workers = static_cast<std::size_t>(
      std::max(1, options.threads > 0 ? options.threads : DefaultThreadCount()));
  const std::vector<std::vector<std::size_t>> batches = DrawBatches(pdf, pdf_jobs, jobs.size(), workers);
  const auto what_of = [&](std::size_t i) {
    return (i < pdf_jobs ? "the figure of report.pdf " : "plot ") + fs::path(jobs[i].file).filename().string();
  };
  // The batch that draws each job, and whether it is done.
  std::vector<std::size_t> batch_of(jobs.size());
  for (std::size_t b = 0; b < batches.size(); ++b)
    for (std::size_t i : batches[b]) batch_of[i] = b;
  std::vector<std::promise<void>> drawn(batches.size());
  std::vector<std::shared_future<void>> drawn_batch;
  for (std::promise<void>& p : drawn) drawn_batch.push_back(p.get_future().share());

  Progress progress(options.progress, static_cast<int>(jobs.size() - pdf_jobs) + (pdf ? 1 : 0));
  PdfLayout layout;
  const auto draw_batch = [&](std::size_t b) {
    const std::vector<std::size_t>& batch = batches[b];
    std::string script;
    for (std::size_t i : batch) script += jobs[i].script;
    try {
      if (!batch.empty()) try {
        RunGnuplot(gnuplot, plots_dir.string(), script, batch.size() == 1 ? what_of(batch[0]) : "the plots");
      } catch (const WriteError&) {
        // Name the plot that failed: draw the batch's files one at a time.
        if (batch.size() == 1) throw;
        for (std::size_t i : batch) RunGnuplot(gnuplot, plots_dir.string(), jobs[i].script, what_of(i));
        throw;
      }
      for (std::size_t i : batch) RequireFile(root / GnuplotOutputFile(jobs[i].format, jobs[i].file), what_of(i));
    } catch (...) {
      drawn[b].set_exception(std::current_exception());
      throw;
    }
    drawn[b].set_value();
  };
  const auto typeset = [&] {
    progress.Step("report.pdf");
    layout = WritePdfDocument(ReportPdfSpec(PdfInputs(result, facts, sha256, when, plots, root, options)),
                              (root / "report.pdf").string());
  };
  // Jobs: the batches in order (report.pdf's first), then one per plot file.
  ParallelForEach(batches.size() + jobs.size() - pdf_jobs, [&](std::size_t k) {
    if (k < batches.size()) {
      draw_batch(k);
      if (pdf && k == 0) typeset();
      return;
    }
    const std::size_t i = pdf_jobs + (k - batches.size());
    drawn_batch[batch_of[i]].get();  // started before this job: no wait on a job not yet taken
    progress.Step(jobs[i].file);
    FinishPlotFile(jobs[i].format, (root / jobs[i].file).string());
  }, options.threads);
  for (std::size_t i = pdf_jobs; i < jobs.size(); ++i) manifest.files.push_back(jobs[i].file);
  if (pdf) {
    std::error_code ec;
    fs::remove_all(plots_dir / kPdfFigureDir, ec);
    manifest.files.push_back("report.pdf");
    manifest.title_pages = 1;
    manifest.pdf_pages = layout.pages;
  }
}

}  // namespace

ReportManifest WriteReport(const BudgetResult& result, const RunInfo& info, const ReportOptions& options,
                           const std::string& dir) {
  std::string why;
  if (!options.IsValid(&why)) throw InputError("report options: " + why);
  ReportManifest manifest;
  const fs::path root(dir), plots_dir = root / "plots";
  const bool plot_files = options.plots || options.plot_scripts;
  const fs::path made = plot_files ? plots_dir : root;
  std::error_code ec;
  fs::create_directories(made, ec);
  if (ec) throw WriteError("cannot create directory " + made.string() + ": " + ec.message());
  Writer writer(root, &manifest);

  const std::string sha256 = !info.budget_sha256.empty() ? info.budget_sha256
                             : info.budget_file.empty()  ? ""
                                                         : FileSha256(info.budget_file);
  const std::time_t when = DocumentTime();
  const ReportFacts facts =
      MakeFacts(result, info.budget_file, sha256, UtcText(when, "%Y-%m-%d %H:%M:%S UTC"), info.seconds);

  std::vector<Plot> plots;
  if (plot_files) {
    plots = ReportPlots(result, options);
    for (const Plot& p : plots) {
      writer.Write("plots/" + p.name + ".csv", p.csv);
      writer.WriteScript("plots/" + p.name + ".gp", p.script);
      manifest.plots.push_back(p.name);
    }
    writer.Write("plots/colours.csv", ColoursCsv(result.outline));
  }
  const bool pdf = options.plots && options.Has(PlotFormat::kPdf);
  if (pdf) {
    // Each figure of report.pdf drawn at the height that keeps it on its
    // page, where a little shorter does (FittedFigureHeights).
    const std::map<std::string, int> fitted =
        FittedFigureHeights(ReportPdfSpec(PdfInputs(result, facts, sha256, when, plots, root, options)));
    for (Plot& p : plots)
      if (const auto it = fitted.find(p.name); it != fitted.end()) p.pdf_height_px = it->second;
  }
  if (options.plots) DrawReport(result, plots, facts, sha256, when, options, pdf, root, manifest);

  DocumentInputs doc;
  doc.result = &result;
  doc.facts = facts;
  doc.plots = plots;
  doc.pdf = pdf;
  doc.digits = options.digits;
  doc.asd = options.asd;
  if (options.plots) doc.image_extension = options.Has(PlotFormat::kPng) ? "png" : options.Has(PlotFormat::kSvg) ? "svg" : "";
  std::vector<std::string> data = {"summary.json", kResultStoreFile};
  for (const EnumName<ExportFormat>& f : kExportFormatNames)
    for (const std::string& file : ExportFileNames(result, f.value)) data.push_back(file);
  for (const auto& f : data)
    if (fs::is_regular_file(root / f, ec)) doc.data_files.push_back(f);
  writer.Write("index.html", IndexHtml(doc));
  writer.Write("report.md", ReportMarkdown(doc));
  return manifest;
}

ReportManifest WriteReportDirectory(const BudgetResult& result, const RunInfo& info, const ReportOptions& options,
                                    const std::string& out_dir, const std::vector<ExportFormat>& exports) {
  std::string why;
  if (!options.IsValid(&why)) throw InputError("report options: " + why);
  // What is found wrong only while writing means the report cannot be written.
  try {
    ReportManifest manifest;
    // The budget file as it is now, read once: its text goes into the store
    // and its digest onto every page of the report.
    RunInfo run = info;
    if (!run.budget_text && !run.budget_file.empty())
      run.budget_text = ReadInputFile(run.budget_file, "budget file", limits::kMaxBudgetFileBytes);
    if (run.budget_sha256.empty() && run.budget_text && !run.budget_file.empty())
      run.budget_sha256 = Sha256(*run.budget_text);
    ReplaceOptions replace;
    replace.force = options.force;
    // The path responses at the frequencies the figures need, in the store
    // as in the report (figure_traces.h).
    const BudgetResult drawn = WithFigureTraces(result, options.threads);
    ReplaceDirectory(
        out_dir,
        [&](const std::string& dir) {
          // The store is written beside the rest (HDF5 is used by nothing
          // else meanwhile: the exports do not use it). Its file is made
          // here first, so that index.html links it whatever the timing.
          const std::string store = (fs::path(dir) / kResultStoreFile).string();
          if (!std::ofstream(store)) throw WriteError("cannot write " + store);
          std::future<void> stored =
              std::async(std::launch::async, [&] { WriteResultStore(drawn, run, store); });
          std::vector<std::string> exported;
          try {
            WriteResultFiles(drawn, run, dir);
            exported = WriteResultExports(drawn, exports, dir);
            manifest = WriteReport(drawn, run, options, dir);
          } catch (...) {
            stored.wait();
            throw;
          }
          stored.get();
          manifest.files.push_back(kResultStoreFile);
          manifest.files.insert(manifest.files.end(), exported.begin(), exported.end());
        },
        replace);
    return manifest;
  } catch (const InputError& e) {
    throw WriteError(e.what());
  }
}

}  // namespace deb
