#include "deb/load/block_yaml.h"

#include <map>
#include <optional>
#include <utility>
#include <vector>

#include "deb/core/limits.h"
#include "deb/systems/control_blocks.h"
#include "deb/systems/polynomial_product.h"

namespace deb::load {
namespace {

const std::map<std::string, std::set<std::string>>& Keys() {
  static const std::map<std::string, std::set<std::string>> keys = {
      {"zpk", {"zeros", "poles", "gain", "gain_at"}},
      {"second_order", {"f_hz", "zeta", "gain"}},
      {"mass_spring_damper", {"m", "k", "d"}},
      {"pid", {"kp", "ki", "kd", "gain", "f_i_hz", "f_d_hz", "f_lp_hz"}},
      {"lead_lag", {"f_hz", "phase_deg"}},
      {"notch", {"f_hz", "depth_db", "width_hz"}},
      {"lowpass", {"f_hz", "order", "shape"}},
      {"highpass", {"f_hz", "order", "shape"}},
      {"integrator", {"f_hz"}},
  };
  return keys;
}

// A root: f_hz alone, or {f_hz, zeta}.
std::vector<ZpkRoot> Roots(const YamlNode& node) {
  std::vector<ZpkRoot> roots;
  for (const YamlNode& e : node.Elements()) {
    ZpkRoot r;
    if (e.IsMap()) {
      e.AllowOnly({"f_hz", "zeta"});
      r.f_hz = e.Required("f_hz").AsDouble();
      if (auto z = e.Optional("zeta")) r.zeta = z->AsDouble();
    } else {
      r.f_hz = e.AsValueIn("Hz");
    }
    roots.push_back(r);
  }
  return roots;
}

std::optional<double> OptionalNumber(const YamlNode& node, const std::string& key) {
  if (auto v = node.Optional(key)) return v->AsDouble();
  return std::nullopt;
}

FilterShape Shape(const YamlNode& node) {
  const auto s = node.Optional("shape");
  if (!s) return FilterShape::kButterworth;
  const std::string text = s->AsString();
  if (text == "butterworth") return FilterShape::kButterworth;
  if (text == "bessel") return FilterShape::kBessel;
  s->Fail("filter shape '" + text + "' is not known; allowed: butterworth, bessel");
}

}  // namespace

bool IsBlockType(const std::string& type) { return Keys().count(type) > 0; }

bool IsIrrationalType(const std::string& type) { return type == "delay" || type == "discrete"; }

std::set<std::string> IrrationalKeys(const std::string& type) {
  if (type == "delay") return {"seconds", "pade_order"};
  return {"sample_hz", "num", "den", "zeros", "poles", "gain", "zoh", "pade_order"};
}

namespace {

// A sampled block's coefficients in powers of z, highest first: num and den
// as given, or gain * prod(z - z_i) / prod(z - p_i) from its zeros and poles
// in the z-plane, each a real number or a conjugate pair {re, im}.
std::pair<std::vector<double>, std::vector<double>> DiscreteCoefficients(const YamlNode& node) {
  const bool polynomials = node.Has("num") || node.Has("den");
  const bool roots = node.Has("zeros") || node.Has("poles") || node.Has("gain");
  if (polynomials && roots)
    node.Fail("give num and den, or zeros, poles and gain (in the z-plane), not both");
  if (!roots) return {node.Required("num").AsDoubles(), node.Required("den").AsDoubles()};
  const auto product = [](const YamlNode& list) {
    std::vector<double> p{1.0};
    const std::vector<YamlNode> elements = list.Elements();
    if (elements.size() > static_cast<std::size_t>(limits::kMaxStates))
      list.Fail(std::to_string(elements.size()) + " roots give more than the " + std::to_string(limits::kMaxStates) +
                " states a path may have");
    for (const YamlNode& r : elements) {
      if (r.IsMap()) {
        r.AllowOnly({"re", "im"});
        const double re = r.Required("re").AsDouble(), im = r.Required("im").AsDouble();
        if (im == 0.0) r.Required("im").Fail("a conjugate pair needs im != 0 (give a real root as a number)");
        p = PolynomialProduct(p, std::vector<double>{1.0, -2.0 * re, re * re + im * im});
      } else {
        p = PolynomialProduct(p, std::vector<double>{1.0, -r.AsDouble()});
      }
    }
    return p;
  };
  std::vector<double> num = node.Has("zeros") ? product(node.Required("zeros")) : std::vector<double>{1.0};
  const std::vector<double> den = node.Has("poles") ? product(node.Required("poles")) : std::vector<double>{1.0};
  const double gain = node.Has("gain") ? node.Required("gain").AsDouble() : 1.0;
  for (double& c : num) c *= gain;
  return {num, den};
}

}  // namespace

IrrationalBlock ParseIrrationalBlock(const YamlNode& node, const std::string& type) {
  int pade = kDefaultPadeOrder;
  if (auto n = node.Optional("pade_order")) {
    pade = n->AsInt();
    if (pade < kMinPadeOrder || pade > kMaxPadeOrder)
      n->Fail("pade_order must be " + std::to_string(kMinPadeOrder) + " to " + std::to_string(kMaxPadeOrder) +
              ", not " + std::to_string(pade));
  }
  if (type == "delay") {
    const YamlNode seconds = node.Required("seconds");
    const double tau = seconds.AsValueIn("s");
    return AtNode(seconds, [&] { return Delay(tau, pade); });
  }
  const YamlNode rate = node.Required("sample_hz");
  const double sample_hz = rate.AsDouble();
  if (!(sample_hz > 0.0)) rate.Fail("sample_hz must be > 0");
  // Not a structured binding: C++17 lambdas cannot capture those (Clang refuses).
  const std::pair<std::vector<double>, std::vector<double>> coefficients = DiscreteCoefficients(node);
  const std::vector<double>& num = coefficients.first;
  const std::vector<double>& den = coefficients.second;
  const bool zoh = node.Has("zoh") && node.Required("zoh").AsBool();
  const YamlNode at = node.Has("den") ? node.Required("den") : node.Has("poles") ? node.Required("poles") : node;
  return AtNode(at, [&] { return Discrete(sample_hz, num, den, zoh, pade); });
}

std::set<std::string> BlockKeys(const std::string& type) { return Keys().at(type); }

TransferFunction ParseBlock(const YamlNode& node, const std::string& type) {
  return AtNode(node, [&]() -> TransferFunction {
    if (type == "zpk") {
      const std::vector<ZpkRoot> zeros = node.Has("zeros") ? Roots(node.Required("zeros")) : std::vector<ZpkRoot>{};
      const std::vector<ZpkRoot> poles = node.Has("poles") ? Roots(node.Required("poles")) : std::vector<ZpkRoot>{};
      if (node.Has("gain") && node.Has("gain_at")) node.Required("gain_at").Fail("give gain or gain_at, not both");
      if (auto at = node.Optional("gain_at")) {
        at->AllowOnly({"f_hz", "value"});
        const double f = at->Required("f_hz").AsDouble(), value = at->Required("value").AsDouble();
        return AtNode(*at, [&] { return ZpkWithGainAt(zeros, poles, f, value); });
      }
      return Zpk(zeros, poles, node.Has("gain") ? node.Required("gain").AsDouble() : 1.0);
    }
    if (type == "second_order")
      return SecondOrder(node.Required("f_hz").AsDouble(), node.Required("zeta").AsDouble(),
                         node.Has("gain") ? node.Required("gain").AsDouble() : 1.0);
    if (type == "mass_spring_damper")
      return MassSpringDamper(node.Required("m").AsValueIn("kg"), node.Required("k").AsValueIn("N/m"),
                              node.Has("d") ? node.Required("d").AsValueIn("N s/m") : 0.0);
    if (type == "pid") {
      const bool parallel = node.Has("kp") || node.Has("ki") || node.Has("kd");
      const bool series = node.Has("gain") || node.Has("f_i_hz") || node.Has("f_d_hz");
      if (parallel && series)
        node.Fail("a pid is parallel (kp, ki, kd) or series (gain, f_i_hz, f_d_hz), not both");
      if (!parallel && !series) node.Fail("a pid needs kp, ki, kd (parallel) or gain, f_i_hz, f_d_hz (series)");
      if (parallel)
        return PidParallel(node.Has("kp") ? node.Required("kp").AsDouble() : 0.0,
                           node.Has("ki") ? node.Required("ki").AsDouble() : 0.0,
                           node.Has("kd") ? node.Required("kd").AsDouble() : 0.0, OptionalNumber(node, "f_lp_hz"));
      return PidSeries(node.Required("gain").AsDouble(), OptionalNumber(node, "f_i_hz"), OptionalNumber(node, "f_d_hz"),
                       OptionalNumber(node, "f_lp_hz"));
    }
    if (type == "lead_lag") return LeadLag(node.Required("f_hz").AsDouble(), node.Required("phase_deg").AsDouble());
    if (type == "notch")
      return Notch(node.Required("f_hz").AsDouble(), node.Required("depth_db").AsDouble(),
                   node.Required("width_hz").AsDouble());
    if (type == "lowpass" || type == "highpass") {
      const double f = node.Required("f_hz").AsDouble();
      const int order = node.Required("order").AsInt();
      return type == "lowpass" ? Lowpass(f, order, Shape(node)) : Highpass(f, order, Shape(node));
    }
    return Integrator(node.Required("f_hz").AsDouble());
  });
}

}  // namespace deb::load
