#include "tools/sensitivity_command.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "deb/budget/engine.h"
#include "deb/budget/sensitivity.h"
#include "deb/budget/sweep.h"
#include "deb/core/error.h"
#include "deb/core/output_dir.h"
#include "deb/core/input_file.h"
#include "deb/core/suggest.h"
#include "deb/load/budget_yaml.h"
#include "deb/load/sweep_yaml.h"
#include "deb/report/budget/file_digest.h"
#include "deb/report/compare/sensitivity_directory.h"
#include "deb/report/compare/sensitivity_plots.h"
#include "deb/report/figure/plot.h"
#include "tools/budget_overrides_option.h"

namespace deb::tools {

namespace {

// --label KEY.PATH=TEXT, by key path: the text after the first '=' (a key
// path's brackets hold an index or *) names that -p parameter.
// @throws InputError for a label without '=', naming no -p, or whose text
//         is no label (ParameterLabelProblem: blank, too long, a control character).
std::map<std::string, std::string> ParameterLabels(const std::vector<std::string>& labels,
                                                   const std::vector<std::string>& parameters) {
  std::map<std::string, std::string> out;
  for (const std::string& l : labels) {
    const std::size_t at = l.find('=');
    if (at == std::string::npos || at + 1 == l.size())
      throw InputError("--label '" + Excerpt(l) + "': give KEY.PATH=TEXT, the key path of a -p parameter and its name");
    const std::string key = l.substr(0, at);
    if (std::find(parameters.begin(), parameters.end(), key) == parameters.end())
      throw InputError("--label '" + Excerpt(l) + "': '" + Excerpt(key) + "' is not one of the -p parameters" +
                       DidYouMean(key, parameters));
    const std::string text = l.substr(at + 1);
    if (const std::string why = ParameterLabelProblem(text); !why.empty())
      throw InputError("--label '" + Excerpt(l) + "': " + why);
    out[key] = text;
  }
  return out;
}

}  // namespace

struct SensitivityCommand::Options {
  std::string budget_file;
  std::vector<BudgetOverride> overrides;  // --set
  std::vector<std::string> parameters;
  std::vector<std::string> labels;  // --label KEY.PATH=TEXT
  double step = 1e-3;
  std::string out_dir;
  int threads = 0;
  bool quiet = false;
  bool force = false;  // --force: replace an output directory deb did not write
  bool plots = true;
  bool central_differences = false;  // --central-differences: for every parameter
};

SensitivityCommand::SensitivityCommand() : options_(std::make_unique<Options>()) {}
SensitivityCommand::~SensitivityCommand() = default;

CLI::App* SensitivityCommand::Register(CLI::App& app) {
  Options& s = *options_;
  CLI::App* c = app.add_subcommand(
      "sensitivity", "Derivatives of every output's variance with respect to parameters (by key path), ranked");
  c->add_option("budget", s.budget_file, "Budget YAML file")->required()->check(CLI::ExistingFile);
  c->add_option("--parameter,-p", s.parameters, "A parameter by name (k_iso) or the key path of a number, e.g. paths[0].control.gains")
      ->required();
  c->add_option("--label", s.labels,
                "A parameter's name on the tables and charts, KEY.PATH=TEXT (the KEY.PATH of a -p); repeatable");
  c->add_option("--step", s.step, "Relative step h of the central difference, and of the realisation's derivative where it is exact (default 1e-3)")
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
  c->add_flag("--central-differences", s.central_differences,
              "Central differences for every parameter, also where the realisation's derivative is exact");
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
  std::map<std::string, std::string> labels = ParameterLabels(s.labels, s.parameters);  // before any evaluation
  EngineOptions options;
  options.threads = s.threads;
  options.response_traces = false;  // differenced, not drawn
  const SensitivityStudy study = ComputeSensitivities(
      budget, s.parameters, s.step,
      [&s](const std::string& key, double factor) {
        return LoadBudgetWithScaledParameter(s.budget_file, key, factor, s.overrides);
      },
      options, s.central_differences ? SensitivityMode::kCentralDifferences : SensitivityMode::kExactWherePossible);
  const BudgetResult& nominal = study.nominal;
  report::SensitivitySetting setting;
  setting.name = budget.name;
  setting.step = s.step;
  for (const std::string& key : s.parameters)
    setting.parameters.emplace_back(key, ParameterValues(s.budget_file, key, s.overrides));
  setting.labels = std::move(labels);
  const std::vector<report::Plot> plots =
      s.plots ? report::TornadoPlots(study.sensitivities, nominal, setting.labels) : std::vector<report::Plot>{};
  const std::string dir = s.out_dir.empty() ? report::DefaultSensitivityDirectory(budget.name) : s.out_dir;
  ReplaceOptions replace;
  replace.force = s.force;
  report::WriteSensitivityDirectory(setting, study, plots, dir, replace, s.threads, {{"budget", s.budget_file, report::FileSha256(s.budget_file)}});
  if (!s.quiet) {
    for (const auto& [key, values] : setting.parameters)
      std::printf("nominal %s = %s\n", setting.Label(key).c_str(), report::NominalText(values).c_str());
    for (const SensitivityMethod& m : study.methods)
      std::printf("%s: %s\n", setting.Label(m.parameter).c_str(), m.note.c_str());
    for (const OutputResult& out : nominal.outputs) {
      const std::string& o = out.name;
      std::printf("output %s: nominal rms %.6g %s; variance per relative change of the parameter, total first\n",
                  o.c_str(), out.rms(), out.unit.c_str());
      for (const auto& r : RankedForOutput(study.sensitivities, o))
        std::printf("  %-36s %-20s d var/d ln p %12.5g  elasticity %9.4g\n", setting.Label(r.parameter).c_str(),
                    r.contributor.c_str(), r.d_variance_d_log_p, r.elasticity);
    }
    std::printf("report: %s\n", dir.c_str());
  }
  return 0;
}

}  // namespace deb::tools
