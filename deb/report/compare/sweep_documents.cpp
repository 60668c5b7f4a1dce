#include "deb/report/compare/sweep_documents.h"

#include <sstream>

#include "deb/budget/sweep_ranking.h"
#include "deb/core/error.h"
#include "deb/version.h"

namespace deb::report {
namespace {

std::string Lead(const SweepSpec& spec, std::size_t variants) {
  std::string parameters;
  for (const SweepParameter& p : spec.parameters) parameters += (parameters.empty() ? "" : ", ") + p.AxisTitle();
  return std::to_string(variants) + " variants (" + ToString(spec.mode) + " of " + parameters +
         "). Best first: fewest failing outputs, then the lowest worst RMS / requirement, then the lowest sum of "
         "RMS relative to each output's highest in the sweep.";
}

}  // namespace

std::string VariantCell(const OutputResult& output, double largest_variance, bool* rounding) {
  const bool has_requirement = output.rms_max || !output.band_requirements.empty();
  const bool zero = output.variance > 0.0 && RoundingZero(output.variance, largest_variance);
  if (zero && rounding) *rounding = true;
  return (zero ? std::string("≈ 0") : Sig(output.rms(), 4)) +
         (has_requirement ? (output.AllPass() ? " PASS" : " FAIL") : "");
}

double LargestVariance(const std::vector<BudgetResult>& results, std::size_t o) {
  double v = 0.0;
  for (const BudgetResult& r : results) v = std::max(v, r.outputs[o].variance);
  return v;
}

constexpr const char* kRoundingNote =
    "≈ 0: at most 1e-12 of the output's largest RMS over the variants, the rounding of a variant the model leaves "
    "unexcited (sweep.csv keeps the computed value).";

std::string VariantSettings(const SweepSpec& spec, const std::vector<double>& row) {
  std::string s;
  for (std::size_t k = 0; k < spec.parameters.size() && k < row.size(); ++k)
    s += (k ? ", " : "") + spec.parameters[k].Setting(row[k]);
  return s;
}

std::vector<Table> SweepTables(const SweepSpec& spec, const std::vector<BudgetResult>& results) {
  const auto rows = spec.Variants();
  DEB_DEMAND(rows.size() == results.size());
  std::vector<Table> tables;
  if (results.empty()) return tables;
  const std::vector<OutputResult>& outputs = results.front().outputs;
  std::vector<double> largest(outputs.size());
  for (std::size_t o = 0; o < outputs.size(); ++o) largest[o] = LargestVariance(results, o);

  Table best;
  best.title = "Best variant per output";
  best.header = {"output", "best variant", "RMS", "requirement", "variants that pass"};
  best.numeric = {false, false, true, true, true};
  bool best_rounding = false;
  for (std::size_t o = 0; o < outputs.size(); ++o) {
    const std::size_t b = BestVariant(results, o);
    std::size_t passing = 0;
    for (const BudgetResult& r : results) passing += r.outputs[o].AllPass() ? 1 : 0;
    const OutputResult& out = results[b].outputs[o];
    const bool has_requirement = out.rms_max || !out.band_requirements.empty();
    best.rows.push_back({out.name + " [" + UnitText(out.unit) + "]", VariantSettings(spec, rows[b]),
                         VariantCell(out, largest[o], &best_rounding), out.rms_max ? Short(*out.rms_max) : (has_requirement ? "bands" : "–"),
                         has_requirement ? std::to_string(passing) + " of " + std::to_string(results.size()) : "–"});
  }
  if (best_rounding) best.notes.push_back(kRoundingNote);
  tables.push_back(best);

  Table all;
  all.title = "Variants, best first";
  all.header = {"rank"};
  all.numeric = {true};
  for (const SweepParameter& p : spec.parameters) {
    all.header.push_back(p.AxisTitle());
    all.numeric.push_back(p.texts.empty());
  }
  for (const OutputResult& out : outputs) {
    all.header.push_back(out.name + " [" + UnitText(out.unit) + "]");
    all.numeric.push_back(true);
  }
  std::vector<std::size_t> best_of(outputs.size());
  for (std::size_t o = 0; o < outputs.size(); ++o) best_of[o] = BestVariant(results, o);
  bool all_rounding = false;
  int rank = 0;
  for (const VariantScore& s : RankVariants(results)) {
    std::vector<std::string> row = {std::to_string(++rank)};
    std::vector<bool> bold(1 + spec.parameters.size(), false);
    for (std::size_t k = 0; k < spec.parameters.size(); ++k)
      row.push_back(spec.parameters[k].ShortText(rows[s.variant][k]));
    for (std::size_t o = 0; o < outputs.size(); ++o) {
      row.push_back(VariantCell(results[s.variant].outputs[o], largest[o], &all_rounding));
      bold.push_back(best_of[o] == s.variant);  // the output's best variant
    }
    all.rows.push_back(row);
    all.emphasis.push_back(bold);
  }
  if (all_rounding) all.notes.push_back(kRoundingNote);
  tables.push_back(all);
  return tables;
}

StudyDocument SweepDocument(const std::string& name, const SweepSpec& spec, const std::vector<BudgetResult>& results,
                            const std::vector<Plot>& plots) {
  StudyDocument d;
  d.title = "Sweep: " + name;
  d.lead = Lead(spec, results.size());
  d.footer = std::string("deb ") + DEB_VERSION + " · sweep of " + name;
  d.sections.push_back({"", "", SweepTables(spec, results), {}, {}, false});
  if (!plots.empty()) {
    StudySection figures{"Figures", "", {}, {}, {}, true};
    for (const Plot& p : plots) figures.figures.push_back(&p);
    d.sections.push_back(std::move(figures));
  }
  return d;
}

}  // namespace deb::report
