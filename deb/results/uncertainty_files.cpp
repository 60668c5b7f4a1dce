#include "deb/results/uncertainty_files.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>

#include "deb/core/number_text.h"
#include "deb/formats/hdf5_file.h"
#include "deb/version.h"

namespace deb {

using Json = nlohmann::ordered_json;

namespace {

// A parameter's value in its unit.
double Shown(const UncertainParameter& p, double si) { return si / p.unit_si; }

Json ParameterJson(const UncertainParameter& p) {
  Json j;
  j["name"] = p.name;
  j["unit"] = p.unit;
  j["nominal"] = Shown(p, p.nominal);
  j["distribution"] = p.distribution.Text() + (p.unit.empty() ? "" : " (SI)");
  j["mean"] = Shown(p, p.distribution.Mean());
  j["sd"] = Shown(p, p.distribution.StandardDeviation());
  j["box"] = {Shown(p, p.distribution.BoxLow()), Shown(p, p.distribution.BoxHigh())};
  return j;
}

Json MetricJson(const UncertaintyResult& r, const StudyMetric& m) {
  Json j;
  j["name"] = m.Name();
  j["output"] = m.output;
  if (!m.contributor.empty()) j["contributor"] = m.contributor;
  if (!m.band.empty()) j["band"] = m.band;
  j["unit"] = m.unit;
  j["nominal_rms"] = m.nominal;
  j["mean"] = m.moments.mean;
  j["sd"] = m.moments.sd;
  j["fosm_sd"] = m.fosm_sd;
  j["p5"] = m.p5;
  j["p50"] = m.p50;
  j["p95"] = m.p95;
  j["p99"] = m.p99;
  if (m.limit) {
    j["rms_max"] = *m.limit;
    j["met"] = m.met;
    j["p_meet"] = static_cast<double>(m.met) / static_cast<double>(r.samples);
    j["p_meet_95"] = {m.p_meet.low, m.p_meet.high};
  }
  Json drivers = Json::array();
  for (std::size_t i = 0; i < r.spec.parameters.size(); ++i) {
    Json d;
    d["parameter"] = r.spec.parameters[i].name;
    d["spearman"] = m.spearman[i];
    d["gradient"] = m.gradient[i] * r.spec.parameters[i].unit_si;  // per unit of the parameter
    if (!m.sobol.empty()) {
      d["sobol_first"] = m.sobol[i].first;
      d["sobol_total"] = m.sobol[i].total;
    }
    drivers.push_back(d);
  }
  j["drivers"] = drivers;
  Json corner;
  for (std::size_t i = 0; i < r.spec.parameters.size(); ++i)
    corner[r.spec.parameters[i].name] = Shown(r.spec.parameters[i], m.worst_corner[i]);
  j["worst_corner"] = {{"rms", m.worst_corner_value}, {"values", corner}};
  return j;
}

}  // namespace

std::string UncertaintySummaryJson(const std::string& budget_name, const UncertaintyResult& r) {
  Json j;
  j["deb_version"] = DEB_VERSION;
  j["study"] = "uncertainty";
  j["budget"] = budget_name;
  j["method"] = ToString(r.options.method);
  j["seed"] = r.options.seed;
  j["samples"] = r.samples;
  j["evaluations"] = r.evaluations;
  Json parameters = Json::array();
  for (const UncertainParameter& p : r.spec.parameters) parameters.push_back(ParameterJson(p));
  j["parameters"] = parameters;
  if (r.spec.Correlated()) {
    Json c = Json::array();
    for (Eigen::Index a = 0; a < r.spec.correlation.rows(); ++a) {
      Json row = Json::array();
      for (Eigen::Index b = 0; b < r.spec.correlation.cols(); ++b) row.push_back(r.spec.correlation(a, b));
      c.push_back(row);
    }
    j["correlation"] = c;
  }
  j["all_requirements_met"] = {{"met", r.all_met},
                               {"p_meet", static_cast<double>(r.all_met) / static_cast<double>(r.samples)},
                               {"p_meet_95", {r.p_all_met.low, r.p_all_met.high}}};
  j["worst_corner_method"] = r.corner_method;
  Json metrics = Json::array();
  for (const StudyMetric& m : r.metrics) metrics.push_back(MetricJson(r, m));
  j["metrics"] = metrics;
  j["notes"] = r.notes;
  return j.dump(2) + "\n";
}

void UncertaintySamplesCsv(const UncertaintyResult& r, const TextSink& put) {
  std::string line = "sample";
  for (const UncertainParameter& p : r.spec.parameters) line += "," + p.name + (p.unit.empty() ? "" : " [" + p.unit + "]");
  for (const StudyMetric& m : r.metrics) line += "," + m.Name() + " rms [" + m.unit + "]";
  put(line + "\n");
  for (std::size_t s = 0; s < r.samples; ++s) {
    line = std::to_string(s + 1);
    for (std::size_t i = 0; i < r.spec.parameters.size(); ++i)
      line += "," + NumberText(Shown(r.spec.parameters[i], r.parameter_values[i][s]));
    for (const StudyMetric& m : r.metrics) line += "," + NumberText(m.values[s]);
    put(line + "\n");
  }
}

std::string UncertaintySamplesCsv(const UncertaintyResult& r) {
  std::string csv;
  UncertaintySamplesCsv(r, [&csv](const std::string& piece) { csv += piece; });
  return csv;
}

void WriteUncertaintyStore(const std::string& path, const std::string& budget_name, const UncertaintyResult& r) {
  formats::Hdf5Writer h(path);
  const double nan = std::nan("");
  const std::size_t p = r.spec.parameters.size();
  h.Text("uncertainty/budget", budget_name);
  h.Text("uncertainty/deb_version", DEB_VERSION);
  h.Text("uncertainty/method", ToString(r.options.method));
  h.Integer("uncertainty/seed", static_cast<std::int64_t>(r.options.seed));
  h.Integer("uncertainty/samples", static_cast<std::int64_t>(r.samples));
  h.Integer("uncertainty/evaluations", static_cast<std::int64_t>(r.evaluations));
  std::vector<std::string> names, units;
  std::vector<double> nominal;
  for (const UncertainParameter& q : r.spec.parameters) {
    names.push_back(q.name);
    units.push_back(q.unit);
    nominal.push_back(Shown(q, q.nominal));
  }
  h.Texts("uncertainty/parameters/names", names);
  h.Texts("uncertainty/parameters/units", units);
  h.Numbers("uncertainty/parameters/nominal", nominal);
  {  // the samples' table, row by row, without a row's vector each
    std::vector<double> values(r.samples * p);
    for (std::size_t s = 0; s < r.samples; ++s)
      for (std::size_t i = 0; i < p; ++i) values[s * p + i] = Shown(r.spec.parameters[i], r.parameter_values[i][s]);
    h.Matrix("uncertainty/parameters/values", r.samples, p, values);
  }

  std::vector<std::string> metric_names, metric_units;
  std::vector<double> limit, nominal_rms, mean, sd, fosm, p5, p50, p95, p99, p_meet, low, high, corner_rms;
  const std::size_t metrics = r.metrics.size();
  std::vector<double> rms(r.samples * metrics);  // row-major, samples x metrics
  std::vector<std::vector<double>> spearman, first, total, corner;
  for (std::size_t k = 0; k < r.metrics.size(); ++k) {
    const StudyMetric& m = r.metrics[k];
    metric_names.push_back(m.Name());
    metric_units.push_back(m.unit);
    limit.push_back(m.limit ? *m.limit : nan);
    nominal_rms.push_back(m.nominal);
    mean.push_back(m.moments.mean);
    sd.push_back(m.moments.sd);
    fosm.push_back(m.fosm_sd);
    p5.push_back(m.p5);
    p50.push_back(m.p50);
    p95.push_back(m.p95);
    p99.push_back(m.p99);
    p_meet.push_back(m.limit ? static_cast<double>(m.met) / static_cast<double>(r.samples) : nan);
    low.push_back(m.limit ? m.p_meet.low : nan);
    high.push_back(m.limit ? m.p_meet.high : nan);
    corner_rms.push_back(m.worst_corner_value);
    for (std::size_t s = 0; s < r.samples; ++s) rms[s * metrics + k] = m.values[s];
    spearman.push_back(m.spearman);
    std::vector<double> f, t, c;
    for (std::size_t i = 0; i < p; ++i) {
      if (!m.sobol.empty()) {
        f.push_back(m.sobol[i].first);
        t.push_back(m.sobol[i].total);
      }
      c.push_back(Shown(r.spec.parameters[i], m.worst_corner[i]));
    }
    if (!m.sobol.empty()) {
      first.push_back(f);
      total.push_back(t);
    }
    corner.push_back(c);
  }
  h.Texts("uncertainty/metrics/names", metric_names);
  h.Texts("uncertainty/metrics/units", metric_units);
  h.Numbers("uncertainty/metrics/limit", limit);
  h.Numbers("uncertainty/metrics/nominal", nominal_rms);
  h.Matrix("uncertainty/metrics/rms", r.samples, metrics, rms);
  h.Numbers("uncertainty/metrics/mean", mean);
  h.Numbers("uncertainty/metrics/sd", sd);
  h.Numbers("uncertainty/metrics/fosm_sd", fosm);
  h.Numbers("uncertainty/metrics/p5", p5);
  h.Numbers("uncertainty/metrics/p50", p50);
  h.Numbers("uncertainty/metrics/p95", p95);
  h.Numbers("uncertainty/metrics/p99", p99);
  h.Numbers("uncertainty/metrics/p_meet", p_meet);
  h.Numbers("uncertainty/metrics/p_meet_low", low);
  h.Numbers("uncertainty/metrics/p_meet_high", high);
  h.Rows("uncertainty/metrics/spearman", spearman);
  if (!first.empty()) {
    h.Rows("uncertainty/metrics/sobol_first", first);
    h.Rows("uncertainty/metrics/sobol_total", total);
  }
  h.Numbers("uncertainty/metrics/worst_corner_rms", corner_rms);
  h.Rows("uncertainty/metrics/worst_corner", corner);
  h.Close();
}

}  // namespace deb
