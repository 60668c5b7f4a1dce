#include "tools/sensitivity_command.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "deb/budget/engine.h"
#include "deb/budget/sensitivity.h"
#include "deb/core/error.h"
#include "deb/core/output_dir.h"
#include "deb/load/budget_yaml.h"
#include "deb/results/result_writer.h"
#include "deb/load/sweep_yaml.h"
#include "deb/report/budget/report_tables.h"
#include "deb/report/compare/overlay_plots.h"
#include "deb/report/compare/sensitivity_plots.h"
#include "deb/report/figure/plot.h"
#include "tools/budget_overrides_option.h"

namespace deb::tools {

struct SensitivityCommand::Options {
  std::string budget_file;
  std::vector<BudgetOverride> overrides;  // --set
  std::vector<std::string> parameters;
  double step = 1e-3;
  std::string out_dir;
  int threads = 0;
  bool quiet = false;
  bool force = false;  // --force: replace an output directory deb did not write
  bool plots = true;
};

namespace {

namespace fs = std::filesystem;



std::string Csv(const std::vector<Sensitivity>& all) {
  std::ostringstream os;
  os.precision(10);
  os << "parameter,output,unit,contributor,variance,d_variance_d_log_p,elasticity\n";
  for (const auto& s : all)
    os << report::CsvField(s.parameter) << ',' << report::CsvField(s.output) << ',' << report::CsvField(s.unit) << ','
       << report::CsvField(s.contributor) << ',' << s.variance << ',' << s.d_variance_d_log_p << ',' << s.elasticity
       << '\n';
  return os.str();
}

std::string Number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", v);
  return text;
}

// "50" for one value, "50 (all 6)" for several equal ones, else the list.
std::string NominalText(const std::vector<double>& values) {
  if (values.empty()) return "–";
  const bool equal = std::all_of(values.begin(), values.end(), [&](double v) { return v == values.front(); });
  if (equal) return Number(values.front()) + (values.size() > 1 ? " (all " + std::to_string(values.size()) + ")" : "");
  std::string s;
  for (double v : values) s += (s.empty() ? "" : ", ") + Number(v);
  return s;
}

std::string Markdown(const std::string& name, double step, const BudgetResult& nominal,
                     const std::vector<std::pair<std::string, std::vector<double>>>& parameters,
                     const std::vector<Sensitivity>& all, const std::vector<report::Plot>& plots) {
  std::ostringstream md;
  md << "# Sensitivities of " << name << "\n\n"
     << "Central differences with the parameter multiplied by 1 ± " << step
     << " (every number its key path reaches), on the nominal frequency grid. "
        "d var / d ln p is the change of variance per relative change of the parameter (divide by p for d var / dp); "
        "the elasticity is (d var / var) / (dp / p).\n\n";
  report::Table nominal_table;
  nominal_table.title = "Nominal parameters";
  nominal_table.header = {"parameter (key path)", "nominal value(s)"};
  nominal_table.numeric = {false, false};
  for (const auto& [key, values] : parameters) nominal_table.rows.push_back({key, NominalText(values)});
  md << "## " << nominal_table.title << "\n\n" << report::ToMarkdown(nominal_table) << "\n";
  for (const OutputResult& out : nominal.outputs) {
    const std::string& o = out.name;
    const auto ranked = RankedForOutput(all, o);
    if (ranked.empty()) continue;
    report::Table t;
    t.title = o;
    t.header = {"parameter", "contributor", "variance [" + report::UnitText(report::VarianceUnit(ranked[0].unit)) + "]",
                "d var / d ln p", "elasticity"};
    t.numeric = {false, false, true, true, true};
    for (const auto& s : ranked)
      t.rows.push_back({s.parameter, s.contributor, report::Sig(s.variance, 4), report::Sig(s.d_variance_d_log_p, 4),
                        report::Sig(s.elasticity, 4)});
    md << "## " << o << "\n\nNominal RMS " << report::Sig(out.rms(), 4) << " " << report::UnitText(out.unit)
       << "; the total first, then the contributors.\n\n"
       << report::ToMarkdown(t) << "\n";
    for (const report::Plot& p : plots)
      if (p.output >= 0 && nominal.outputs[static_cast<std::size_t>(p.output)].name == o)
        md << "![" << p.caption << "](plots/" << p.name << ".png)\n\n" << p.caption << "\n\n";
  }
  return md.str();
}

}  // namespace

SensitivityCommand::SensitivityCommand() : options_(std::make_unique<Options>()) {}
SensitivityCommand::~SensitivityCommand() = default;

CLI::App* SensitivityCommand::Register(CLI::App& app) {
  Options& s = *options_;
  CLI::App* c = app.add_subcommand(
      "sensitivity", "Derivatives of every output's variance with respect to parameters (by key path), ranked");
  c->add_option("budget", s.budget_file, "Budget YAML file")->required()->check(CLI::ExistingFile);
  c->add_option("--parameter,-p", s.parameters, "Key path of a numeric parameter, e.g. paths[0].control.gains")
      ->required();
  c->add_option("--step", s.step, "Relative step h of the central difference (default 1e-3)")
      ->check(CLI::Validator(
          [](std::string& text) -> std::string {
            double h = 0.0;
            try {
              std::size_t used = 0;
              h = std::stod(text, &used);
              if (used != text.size()) return "--step: '" + text + "' is not a number";
            } catch (const std::exception&) {
              return "--step: '" + text + "' is not a number";
            }
            // written so that NaN fails too
            if (!(h >= 1e-8 && h <= 0.5)) return "--step " + text + " must be a relative step in [1e-8, 0.5]";
            return "";
          },
          "H in [1e-8, 0.5]"));
  AddOverridesOption(c, &s.overrides);
  c->add_option("--out,-o", s.out_dir, "Directory (default: reports/<budget-name>_sensitivity)");
  c->add_option("--threads,-j", s.threads, "Worker threads (default: all cores)")->check(CLI::NonNegativeNumber);
  c->add_flag("--quiet,-q", s.quiet, "Print nothing but errors");
  c->add_flag("--force", s.force, "Replace --out even if it is not a directory deb wrote");
  c->add_flag_callback("--no-plots", [&s] { s.plots = false; },
                       "No tornado charts (plots/<output>_tornado.png); gnuplot is not needed");
  return c;
}

int SensitivityCommand::Run() const {
  const Options& s = *options_;
  const Budget budget = LoadBudgetFile(s.budget_file, s.overrides);
  EngineOptions options;
  options.threads = s.threads;
  options.response_traces = false;  // differenced, not drawn
  const SensitivityStudy study = ComputeSensitivities(
      budget, s.parameters, s.step,
      [&s](const std::string& key, double factor) {
        return LoadBudgetWithScaledParameter(s.budget_file, key, factor, s.overrides);
      },
      options);
  const BudgetResult& nominal = study.nominal;
  const std::vector<Sensitivity>& all = study.sensitivities;
  std::vector<std::pair<std::string, std::vector<double>>> parameters;
  for (const std::string& key : s.parameters) parameters.emplace_back(key, ParameterValues(s.budget_file, key, s.overrides));
  const std::vector<report::Plot> plots = s.plots ? report::TornadoPlots(all, nominal) : std::vector<report::Plot>{};
  const std::string dir =
      s.out_dir.empty() ? (fs::path("reports") / (budget.name + "_sensitivity")).string() : s.out_dir;
  ReplaceOptions replace;
  replace.force = s.force;
  ReplaceDirectory(dir, [&](const std::string& tmp) {
    WriteTextFile((fs::path(tmp) / "sensitivity.csv").string(), Csv(all));
    WriteTextFile((fs::path(tmp) / "sensitivity.md").string(),
                  Markdown(budget.name, s.step, nominal, parameters, all, plots));
    if (!plots.empty()) {
      fs::create_directories(fs::path(tmp) / "plots");
      report::WritePlotsAsPng(plots, (fs::path(tmp) / "plots").string(), s.threads);
    }
  }, replace);
  if (!s.quiet) {
    for (const auto& [key, values] : parameters) std::printf("nominal %s = %s\n", key.c_str(), NominalText(values).c_str());
    for (const OutputResult& out : nominal.outputs) {
      const std::string& o = out.name;
      std::printf("output %s: nominal rms %.6g %s; variance per relative change of the parameter, total first\n",
                  o.c_str(), out.rms(), out.unit.c_str());
      for (const auto& r : RankedForOutput(all, o))
        std::printf("  %-36s %-20s d var/d ln p %12.5g  elasticity %9.4g\n", r.parameter.c_str(),
                    r.contributor.c_str(), r.d_variance_d_log_p, r.elasticity);
    }
    std::printf("report: %s\n", dir.c_str());
  }
  return 0;
}

}  // namespace deb::tools
