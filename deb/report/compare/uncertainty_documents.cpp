#include "deb/report/compare/uncertainty_documents.h"

#include <cmath>

#include "deb/report/compare/uncertainty_plots.h"
#include "deb/uncertainty/sample_statistics.h"
#include "deb/version.h"

namespace deb::report {

namespace {

std::string Shown(const UncertainParameter& p, double si) {
  return Sig(si / p.unit_si, 4) + (p.unit.empty() ? "" : " " + UnitText(p.unit));
}

Table ParameterTable(const UncertaintyResult& r) {
  Table t;
  // The box's ends of an unbounded distribution are quantiles: samples lie
  // beyond them (s_geo's log-normal reached 42.8 beside a box to 41.9).
  t.title = "Uncertain parameters; tolerance box: the bounds of a bounded distribution, else its 0.135 % and "
            "99.865 % quantiles (a few samples lie beyond), where the worst corners are sought";
  t.header = {"parameter", "nominal", "distribution", "mean", "sd", "tolerance box"};
  t.numeric = {false, true, false, true, true, false};
  for (const UncertainParameter& p : r.spec.parameters)
    t.rows.push_back({p.name, Shown(p, p.nominal),
                      p.distribution.Text(p.unit_si) + (p.unit.empty() ? "" : " " + UnitText(p.unit)),
                      Shown(p, p.distribution.Mean()), Shown(p, p.distribution.StandardDeviation()),
                      Shown(p, p.distribution.BoxLow()) + " to " + Shown(p, p.distribution.BoxHigh())});
  return t;
}

Table StatisticsTable(const UncertaintyResult& r, const std::string& output) {
  Table t;
  t.title = "RMS over the samples";
  t.header = {"", "nominal", "mean", "sd (first-order)", "P5", "P50", "P95", "P99", "P(RMS ≤ limit), 95 % interval"};
  t.numeric = {false, true, true, true, true, true, true, true, false};
  for (const StudyMetric& m : r.metrics) {
    if (m.output != output) continue;
    const std::string name = !m.band.empty() ? "band " + m.band : m.contributor.empty() ? "total" : m.contributor;
    t.rows.push_back({name, Sig(m.nominal, 4), Sig(m.moments.mean, 4),
                      Sig(m.moments.sd, 3) + " (" + Sig(m.fosm_sd, 3) + ")", Sig(m.p5, 4), Sig(m.p50, 4),
                      Sig(m.p95, 4), Sig(m.p99, 4),
                      m.limit ? ProbabilityText(static_cast<double>(m.met) / static_cast<double>(r.samples)) + " of ≤ " +
                                    Short(*m.limit) + " (" + ProbabilityText(m.p_meet.low) + " to " + ProbabilityText(m.p_meet.high) +
                                    ")"
                              : "–"});
  }
  return t;
}

Table DriverTable(const UncertaintyResult& r, const StudyMetric& m) {
  Table t;
  const double bound = RankCorrelationNoise(r.samples);
  t.title = "Drivers of the total RMS; a rank correlation within ±" + Sig(bound, 2) +
            " is marked 'noise': " + std::to_string(r.samples) +
            " independent samples reach it by chance (95 %), so its sign says nothing (d RMS / d parameter is "
            "the local slope)";
  const bool sobol = !m.sobol.empty();
  t.header = {"parameter", "rank correlation", "d RMS / d parameter", "worst corner"};
  if (sobol) t.header.insert(t.header.begin() + 2, {"Sobol S", "Sobol ST"});
  t.numeric = std::vector<bool>(t.header.size(), true);
  t.numeric[0] = false;
  for (std::size_t i : DriverOrder(m)) {
    const UncertainParameter& p = r.spec.parameters[i];
    std::vector<std::string> row = {p.name,
                                    Sig(m.spearman[i], 2) + (std::abs(m.spearman[i]) < bound ? " noise" : "")};
    if (sobol) row.insert(row.end(), {Sig(m.sobol[i].first, 2), Sig(m.sobol[i].total, 2)});
    row.push_back(Sig(m.gradient[i] * p.unit_si, 3) + " " + UnitText(m.unit) + (p.unit.empty() ? "" : " per " + UnitText(p.unit)));
    row.push_back(Shown(p, m.worst_corner[i]));
    t.rows.push_back(row);
  }
  return t;
}

}  // namespace

StudyDocument UncertaintyDocument(const std::string& budget_name, const UncertaintyResult& r,
                                  const std::vector<Plot>& plots) {
  StudyDocument doc;
  doc.title = "Uncertainty of " + budget_name;
  doc.footer = "deb " + std::string(DEB_VERSION) + " · uncertainty of " + budget_name;
  doc.lead = std::to_string(r.samples) + " samples (" + ToString(r.options.method) + ", seed " +
             std::to_string(r.options.seed) + "), " + std::to_string(r.evaluations) +
             " budgets evaluated in all (the nominal design, the gradient's steps and the tolerance box's corners "
             "besides the samples). All requirements met in " +
             ProbabilityText(static_cast<double>(r.all_met) / static_cast<double>(r.samples)) + " of the samples (95 %: " +
             ProbabilityText(r.p_all_met.low) + " to " + ProbabilityText(r.p_all_met.high) +
             "). The first-order sd is the gradient's estimate: where it is close to the sampled sd, the RMS is "
             "about linear in the tolerances.";
  StudySection parameters;
  parameters.heading = "Parameters";
  parameters.tables.push_back(ParameterTable(r));
  parameters.bullets.push_back("Worst corners: " + r.corner_method + ".");
  for (const std::string& note : r.notes) parameters.bullets.push_back(note);
  doc.sections.push_back(parameters);
  for (const StudyMetric& m : r.metrics) {
    if (!m.contributor.empty() || !m.band.empty()) continue;
    StudySection s;
    s.heading = m.output + " [" + UnitText(m.unit) + "]";
    s.new_page = true;
    s.text = "Nominal RMS " + Sig(m.nominal, 4) + ", over the samples " + Sig(m.p50, 4) + " (median), " +
             Sig(m.p95, 4) + " (P95); worst corner " + Sig(m.worst_corner_value, 4) + "." +
             (m.limit ? " P(RMS ≤ " + Short(*m.limit) + (m.unit.empty() ? "" : " " + UnitText(m.unit)) + ") = " +
                            ProbabilityText(static_cast<double>(m.met) / static_cast<double>(r.samples)) + " (95 %: " +
                            ProbabilityText(m.p_meet.low) + " to " + ProbabilityText(m.p_meet.high) + ")."
                      : "");
    s.tables.push_back(StatisticsTable(r, m.output));
    s.tables.push_back(DriverTable(r, m));
    for (const Plot& p : plots)
      if (p.name == FileStem(m.output) + "_uncertainty" || p.name == FileStem(m.output) + "_drivers" ||
          p.name == FileStem(m.output) + "_scatter")
        s.figures.push_back(&p);
    doc.sections.push_back(s);
  }
  return doc;
}

}  // namespace deb::report
