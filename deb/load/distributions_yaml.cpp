#include "deb/load/distributions_yaml.h"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <set>

#include "deb/core/error.h"
#include "deb/core/number_text.h"
#include "deb/load/budget_extends.h"
#include "deb/load/budget_overrides.h"
#include "deb/load/key_path.h"
#include "deb/load/parameters_yaml.h"
#include "deb/units/quantity.h"

namespace deb::load {

namespace {

// Phi^-1(0.95): a log-normal's p95 is its median times exp(1.645 sigma_log).
constexpr double kZ95 = 1.6448536269514722;

}  // namespace

double ParameterValueOf(const YamlNode& node, const Parameter& p, double unit_si, const ParameterSet& parameters,
                        bool percent) {
  if (!node.IsScalar()) node.Fail("expected a number, with the parameter's unit or none");
  std::string text = node.AsString();
  while (!text.empty() && text.back() == ' ') text.pop_back();
  if (!text.empty() && text.back() == '%') {
    if (!percent) node.Fail("a percentage is allowed for sigma only; give '" + text + "' as a value");
    char* end = nullptr;
    const std::string number = text.substr(0, text.size() - 1);
    const double v = std::strtod(number.c_str(), &end);
    if (number.empty() || end == nullptr || (*end != '\0' && *end != ' ') || !std::isfinite(v))
      node.Fail("'" + text + "' is not a percentage (write e.g. 5 %)");
    return v / 100.0 * std::abs(p.value.value);
  }
  const Quantity q = AtNode(node, [&] { return parameters.EvaluateText(text); });
  if (!q.has_unit) return q.value * unit_si;
  if (!(q.dimension == p.value.dimension))
    node.Fail("'" + text + "' is not the quantity of " + p.definition.name + " (" +
              (p.unit.empty() ? std::string("a plain number") : p.unit) + ")");
  return q.value;
}

namespace {

Distribution ParseDistribution(const YamlNode& node, const Parameter& p, double unit_si,
                               const ParameterSet& parameters) {
  if (!node.IsMap() || node.size() != 1)
    node.Fail("expected one distribution: {normal: {sigma: S}}, {uniform: {min: A, max: B}}, {lognormal: {p95: X}}, "
              "{truncated_normal: {sigma: S, min: A, max: B}}, {triangular: {min: A, max: B}} or {discrete: "
              "{values: [...], p: [...]}}");
  const std::string kind = node.Keys().front();
  const YamlNode d = node.Required(kind);
  const auto value = [&](const char* key, bool percent = false) {
    return ParameterValueOf(d.Required(key), p, unit_si, parameters, percent);
  };
  Distribution out;
  const double nominal = p.value.value;
  if (kind == "normal") {
    d.AllowOnly({"sigma"});
    out.kind = DistributionKind::kNormal;
    out.mean = nominal;
    out.sigma = value("sigma", true);
  } else if (kind == "uniform") {
    d.AllowOnly({"min", "max"});
    out.kind = DistributionKind::kUniform;
    out.min = value("min");
    out.max = value("max");
  } else if (kind == "lognormal") {
    d.AllowOnly({"p95", "sigma_log"});
    if (d.Has("p95") == d.Has("sigma_log")) d.Fail("give one of p95 (the 95th percentile) and sigma_log");
    out.kind = DistributionKind::kLogNormal;
    out.mean = nominal;
    if (nominal <= 0.0)
      d.Fail("a log-normal parameter's value is its median and must be > 0; " + p.definition.name + " is " +
             NumberText(nominal / unit_si));
    if (d.Has("p95")) {
      const double p95 = value("p95");
      if (!(p95 > nominal))
        d.Required("p95").Fail("p95 " + NumberText(p95 / unit_si) + " must be above the value (the median) " +
                               NumberText(nominal / unit_si));
      out.sigma = std::log(p95 / nominal) / kZ95;
    } else {
      out.sigma = d.Required("sigma_log").AsDouble();
    }
  } else if (kind == "truncated_normal") {
    d.AllowOnly({"sigma", "min", "max"});
    out.kind = DistributionKind::kTruncatedNormal;
    out.mean = nominal;
    out.sigma = value("sigma", true);
    out.min = value("min");
    out.max = value("max");
  } else if (kind == "triangular") {
    d.AllowOnly({"min", "max"});
    out.kind = DistributionKind::kTriangular;
    out.min = value("min");
    out.max = value("max");
    out.mode = nominal;
  } else if (kind == "discrete") {
    d.AllowOnly({"values", "p"});
    out.kind = DistributionKind::kDiscrete;
    for (const YamlNode& v : d.Required("values").Elements())
      out.values.push_back(ParameterValueOf(v, p, unit_si, parameters, false));
    out.probabilities = d.Required("p").AsDoubles();
    if (out.values.size() > 10000) d.Required("values").Fail("more than 10000 values");
  } else {
    node.Required(kind).Fail("unknown distribution '" + kind +
                             "'; allowed: normal, uniform, lognormal, truncated_normal, triangular, discrete");
  }
  if (const std::string why = out.Problem(); !why.empty()) d.Fail(kind + ": " + why);
  return out;
}

}  // namespace

UncertaintySpec ParseUncertainty(const YamlNode& root, const ParameterSet& parameters) {
  UncertaintySpec spec;
  std::map<std::string, std::size_t> index;
  if (const auto section = root.Optional("parameters")) {
    for (const Parameter& p : parameters.parameters()) {
      const YamlNode entry = section->Required(p.definition.name);
      if (!entry.IsMap() || !entry.Has("distribution")) continue;
      const YamlNode d = entry.Required("distribution");
      if (p.derived)
        d.Fail(p.definition.name + " is derived from other parameters ('" + p.definition.expression +
               "'): give the distributions to the parameters it is made of");
      UncertainParameter u;
      u.name = p.definition.name;
      u.unit = p.unit;
      u.unit_si = p.unit.empty() ? 1.0 : AtNode(d, [&] { return QuantityOf(1.0, p.unit).value; });
      u.nominal = p.value.value;
      u.distribution = ParseDistribution(d, p, u.unit_si, parameters);
      index[u.name] = spec.parameters.size();
      spec.parameters.push_back(u);
    }
  }
  const auto n = static_cast<Eigen::Index>(spec.parameters.size());
  spec.correlation = Eigen::MatrixXd::Identity(n, n);
  const auto section = root.Optional("correlations");
  if (!section) return spec;
  if (!section->IsSequence()) section->Fail("expected a list of {between: [A, B], rho: R}");
  std::set<std::pair<std::size_t, std::size_t>> given;
  for (const YamlNode& c : section->Elements()) {
    c.AllowOnly({"between", "rho"});
    const YamlNode between = c.Required("between");
    const std::vector<YamlNode> names = between.Elements();
    if (names.size() != 2) between.Fail("expected two parameter names, [A, B]");
    std::size_t k[2];
    for (int i = 0; i < 2; ++i) {
      const std::string name = names[static_cast<std::size_t>(i)].AsString();
      const auto it = index.find(name);
      if (it == index.end()) {
        std::string uncertain;
        for (const UncertainParameter& p : spec.parameters) uncertain += (uncertain.empty() ? "" : ", ") + p.name;
        names[static_cast<std::size_t>(i)].Fail(
            "'" + name + "' is not a parameter with a distribution" +
            (uncertain.empty() ? std::string(" (no parameter has one)") : " (those with one: " + uncertain + ")"));
      }
      k[i] = it->second;
    }
    if (k[0] == k[1]) between.Fail("a parameter is not correlated with itself: name two different ones");
    if (!given.insert({std::min(k[0], k[1]), std::max(k[0], k[1])}).second)
      between.Fail("the correlation of these two is given twice");
    const YamlNode rho_node = c.Required("rho");
    const double rho = rho_node.AsDouble();
    if (!std::isfinite(rho) || std::abs(rho) > 1.0) rho_node.Fail("rho " + NumberText(rho) + " must be within [-1, 1]");
    spec.correlation(static_cast<Eigen::Index>(k[0]), static_cast<Eigen::Index>(k[1])) = rho;
    spec.correlation(static_cast<Eigen::Index>(k[1]), static_cast<Eigen::Index>(k[0])) = rho;
  }
  const Eigen::LLT<Eigen::MatrixXd> llt(spec.correlation);
  if (llt.info() != Eigen::Success || llt.matrixLLT().diagonal().minCoeff() < 1e-6)
    section->Fail("these correlations are not consistent: their matrix is not positive definite (no set of "
                  "parameters can be correlated so; e.g. A~B and B~C strongly positive forbid A~C strongly negative)");
  return spec;
}

}  // namespace deb::load

