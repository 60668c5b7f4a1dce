#include "deb/report/compare/sensitivity_directory.h"

#include <algorithm>
#include <filesystem>
#include <sstream>

#include "deb/core/number_text.h"
#include "deb/report/budget/report_tables.h"
#include "deb/report/compare/overlay_plots.h"
#include "deb/version.h"

namespace deb::report {

namespace fs = std::filesystem;

namespace {

std::string Number(double v) { return SignificantText(v, 6); }

}  // namespace

std::string NominalText(const std::vector<double>& values) {
  if (values.empty()) return "–";
  const bool equal = std::all_of(values.begin(), values.end(), [&](double v) { return v == values.front(); });
  if (equal) return Number(values.front()) + (values.size() > 1 ? " (all " + std::to_string(values.size()) + ")" : "");
  std::string s;
  for (double v : values) s += (s.empty() ? "" : ", ") + Number(v);
  return s;
}

std::string SensitivityCsv(const std::vector<Sensitivity>& all) {
  std::ostringstream os;
  os.precision(10);
  os << "parameter,output,unit,contributor,variance,d_variance_d_log_p,elasticity,method\n";
  for (const auto& s : all)
    os << CsvField(s.parameter) << ',' << CsvField(s.output) << ',' << CsvField(s.unit) << ','
       << CsvField(s.contributor) << ',' << s.variance << ',' << s.d_variance_d_log_p << ',' << s.elasticity << ','
       << (s.exact ? "exact" : "central_difference") << '\n';
  return os.str();
}

std::string SensitivitySetting::Label(const std::string& key) const {
  const auto it = labels.find(key);
  return it == labels.end() ? key : it->second;
}

StudyDocument SensitivityDocument(const SensitivitySetting& setting, const SensitivityStudy& study,
                                  const std::vector<Plot>& plots) {
  const BudgetResult& nominal = study.nominal;
  StudyDocument d;
  d.title = "Sensitivities of " + setting.name;
  std::ostringstream lead;
  lead << "d var / d ln p on the nominal frequency grid: exact where the parameter acts only through rational "
          "paths' realisations (the derivative of each realisation, propagated through H and the grid's integral), "
          "else central differences with the parameter multiplied by 1 ± "
       << setting.step
       << " (every number its key path reaches); the table of parameters says which. d var / d ln p is the change "
          "of variance per relative change of the parameter (divide by p for d var / dp); the elasticity is "
          "(d var / var) / (dp / p).";
  d.lead = lead.str();
  d.footer = std::string("deb ") + DEB_VERSION + " · sensitivities of " + setting.name;
  Table nominal_table;
  nominal_table.title = "Nominal parameters";
  nominal_table.header = {"parameter", "key path", "nominal value(s)", "derivative"};
  nominal_table.numeric = {false, false, false, false};
  for (const auto& [key, values] : setting.parameters) {
    std::string method = "–";
    for (const SensitivityMethod& m : study.methods)
      if (m.parameter == key) method = m.note;
    // A budget parameter's value is in the unit it is written in: say which.
    std::string unit;
    for (const ParameterOutline& p : nominal.outline.parameters)
      if (p.name == key && !p.unit.empty()) unit = " " + UnitText(p.unit);
    nominal_table.rows.push_back({setting.Label(key), key, NominalText(values) + unit, method});
  }
  d.sections.push_back({"", "", {nominal_table}, {}, {}, false});
  for (std::size_t o = 0; o < nominal.outputs.size(); ++o) {
    const OutputResult& out = nominal.outputs[o];
    const auto ranked = RankedForOutput(study.sensitivities, out.name);
    if (ranked.empty()) continue;
    Table t;
    t.title = out.name + ": the total first, then the contributors";
    // The elasticity of each term's own variance, and its part of the
    // total's elasticity ((d var_c / d ln p) / var, which the tornado chart
    // draws and which sum over the contributors to the total's).
    t.header = {"parameter", "contributor", "variance [" + UnitText(VarianceUnit(ranked[0].unit)) + "]",
                "d var / d ln p", "elasticity of its own variance", "share of the total's elasticity (charted)"};
    t.numeric = {false, false, true, true, true, true};
    for (const auto& s : ranked)
      t.rows.push_back({setting.Label(s.parameter), s.contributor, Sig(s.variance, 4), Sig(s.d_variance_d_log_p, 4),
                        Sig(s.elasticity, 4),
                        out.variance > 0.0 ? Sig(s.d_variance_d_log_p / out.variance, 4) : "–"});
    StudySection section{out.name, "Nominal RMS " + Sig(out.rms(), 4) + " " + UnitText(out.unit) + ".", {t}, {}, {},
                         false};
    for (const Plot& p : plots)
      if (p.output == static_cast<int>(o)) section.figures.push_back(&p);
    d.sections.push_back(std::move(section));
  }
  return d;
}

std::string DefaultSensitivityDirectory(const std::string& budget_name) {
  return (fs::path("reports") / (budget_name + "_sensitivity")).string();
}

void WriteSensitivityDirectory(const SensitivitySetting& setting, const SensitivityStudy& study,
                               const std::vector<Plot>& plots, const std::string& out_dir,
                               const ReplaceOptions& replace, int threads, const std::vector<StudySource>& sources) {
  ReplaceDirectory(
      out_dir,
      [&](const std::string& tmp) {
        WriteTextFile((fs::path(tmp) / "sensitivity.csv").string(), SensitivityCsv(study.sensitivities));
        StudyDocument doc = SensitivityDocument(setting, study, plots);
        if (!sources.empty()) StampSources(&doc, sources);
        WriteTextFile((fs::path(tmp) / "sensitivity.md").string(), StudyMarkdown(doc));
        WriteTextFile((fs::path(tmp) / "sensitivity.html").string(), StudyHtml(doc));
        const std::string plots_dir = (fs::path(tmp) / "plots").string();
        if (!plots.empty()) {
          fs::create_directories(plots_dir);
          WritePlotsAsPng(plots, plots_dir, threads);
        }
        WriteStudyPdf(doc, plots_dir, (fs::path(tmp) / "sensitivity.pdf").string(), threads);
      },
      replace);
}

}  // namespace deb::report
