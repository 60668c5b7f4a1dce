#include "deb/systems/control_blocks.h"

#include <cmath>
#include <complex>
#include <string>

#include "deb/core/error.h"
#include "deb/core/math_constants.h"
#include "deb/core/number_text.h"
#include "deb/systems/polynomial_product.h"

namespace deb {
namespace {

constexpr int kMaxFilterOrder = 10;

// Polynomials here are highest power first, as TransferFunction takes them.
using Poly = std::vector<double>;

std::string Text(double v) { return SignificantText(v, 6); }

void RequirePositive(double v, const char* what) {
  if (!(v > 0.0) || !std::isfinite(v)) throw InputError(std::string(what) + " must be a finite number > 0, not " + Text(v));
}

void RequireNonNegative(double v, const char* what) {
  if (!(v >= 0.0) || !std::isfinite(v))
    throw InputError(std::string(what) + " must be a finite number >= 0, not " + Text(v));
}

double Omega(double f_hz) { return 2.0 * kPi * f_hz; }

Poly Factor(const ZpkRoot& r, const char* what) {
  if (!std::isfinite(r.f_hz)) throw InputError(std::string(what) + ": f_hz " + Text(r.f_hz) + " is not finite");
  if (!r.zeta) return {1.0, Omega(r.f_hz)};
  const double z = *r.zeta;
  if (!(r.f_hz > 0.0)) throw InputError(std::string(what) + ": a pair needs f_hz > 0, not " + Text(r.f_hz));
  if (!(std::abs(z) < 1.0))
    throw InputError(std::string(what) + ": a pair needs |zeta| < 1 (give two real roots otherwise), not " + Text(z));
  const double w = Omega(r.f_hz);
  return {1.0, 2.0 * z * w, w * w};
}

Poly Product(const std::vector<ZpkRoot>& roots, const char* what) {
  Poly p{1.0};
  for (const ZpkRoot& r : roots) p = PolynomialProduct(p, Factor(r, what));
  return p;
}

// The reverse Bessel polynomial of order n, lowest power first:
// a_k = (2n - k)! / (2^(n - k) k! (n - k)!).
std::vector<double> ReverseBessel(int n) {
  std::vector<double> a(n + 1);
  for (int k = 0; k <= n; ++k) {
    double v = 1.0;
    for (int i = n - k + 1; i <= 2 * n - k; ++i) v *= i;  // (2n - k)! / (n - k)!
    for (int i = 2; i <= k; ++i) v /= i;                  // / k!
    a[k] = std::ldexp(v, -(n - k));                       // / 2^(n - k)
  }
  return a;
}

// The normalised low-pass prototype of unit -3 dB frequency, lowest power
// first: H(s) = den[0] / sum den[k] s^k.
std::vector<double> Prototype(int order, FilterShape shape) {
  if (order < 1 || order > kMaxFilterOrder)
    throw InputError("filter order must be 1 to " + std::to_string(kMaxFilterOrder) + ", not " + std::to_string(order));
  if (shape == FilterShape::kButterworth) {
    Poly p{1.0};  // highest first, poles on the unit circle
    for (int k = 1; k <= order; ++k) {
      const double angle = kPi * (2.0 * k + order - 1) / (2.0 * order);
      const std::complex<double> pole = std::polar(1.0, angle);
      if (std::abs(pole.imag()) < 1e-12) {
        p = PolynomialProduct(p, {1.0, 1.0});
      } else if (pole.imag() > 0.0) {
        p = PolynomialProduct(p, {1.0, -2.0 * pole.real(), 1.0});
      }
    }
    return std::vector<double>(p.rbegin(), p.rend());
  }
  // Bessel: theta_n(s), then s scaled so that |H(j)| = 1/sqrt 2.
  std::vector<double> a = ReverseBessel(order);
  const auto gain2 = [&a](double w) {
    std::complex<double> v = 0.0;
    for (std::size_t k = a.size(); k-- > 0;) v = v * std::complex<double>(0.0, w) + a[k];
    return std::norm(a[0] / v);
  };
  double lo = 0.0, hi = 1.0;
  while (gain2(hi) > 0.5) hi *= 2.0;
  for (int it = 0; it < 200 && hi - lo > 1e-16 * hi; ++it) {
    const double mid = 0.5 * (lo + hi);
    (gain2(mid) > 0.5 ? lo : hi) = mid;
  }
  const double w3 = 0.5 * (lo + hi);
  // H(s) = a0 / theta(s w3): coefficient k times w3^k.
  for (std::size_t k = 0; k < a.size(); ++k) a[k] *= std::pow(w3, static_cast<double>(k));
  return a;
}

}  // namespace

TransferFunction Zpk(const std::vector<ZpkRoot>& zeros, const std::vector<ZpkRoot>& poles, double gain) {
  if (!std::isfinite(gain)) throw InputError("zpk: gain " + Text(gain) + " is not finite");
  const Poly num = Product(zeros, "zpk zero"), den = Product(poles, "zpk pole");
  if (num.size() > den.size())
    throw InputError("zpk: " + std::to_string(num.size() - 1) + " zeros but " + std::to_string(den.size() - 1) +
                     " poles: improper (give at least as many poles as zeros)");
  Poly scaled = num;
  for (double& c : scaled) c *= gain;
  return TransferFunction(scaled, den);
}

TransferFunction ZpkWithGainAt(const std::vector<ZpkRoot>& zeros, const std::vector<ZpkRoot>& poles, double f_hz,
                               double magnitude) {
  RequirePositive(magnitude, "zpk gain_at value");
  RequireNonNegative(f_hz, "zpk gain_at f_hz");
  const TransferFunction unit = Zpk(zeros, poles, 1.0);
  const double at = std::abs(unit.Evaluate(std::complex<double>(0.0, Omega(f_hz))));
  if (!(at > 0.0) || !std::isfinite(at))
    throw InputError("zpk gain_at: |H| at " + Text(f_hz) + " Hz is " + Text(at) +
                     " (a zero or pole there); give the gain at another frequency");
  return Zpk(zeros, poles, magnitude / at);
}

TransferFunction SecondOrder(double f_hz, double zeta, double gain) {
  RequirePositive(f_hz, "second_order f_hz");
  RequirePositive(zeta, "second_order zeta");
  if (!std::isfinite(gain)) throw InputError("second_order: gain " + Text(gain) + " is not finite");
  const double w = Omega(f_hz);
  return TransferFunction({gain * w * w}, {1.0, 2.0 * zeta * w, w * w});
}

TransferFunction MassSpringDamper(double m_kg, double k_n_per_m, double d_n_s_per_m) {
  RequirePositive(m_kg, "mass_spring_damper m");
  RequireNonNegative(k_n_per_m, "mass_spring_damper k");
  RequireNonNegative(d_n_s_per_m, "mass_spring_damper d");
  return TransferFunction({1.0}, {m_kg, d_n_s_per_m, k_n_per_m});
}

TransferFunction PidParallel(double kp, double ki, double kd, std::optional<double> f_lp_hz) {
  for (double v : {kp, ki, kd})
    if (!std::isfinite(v)) throw InputError("pid: kp, ki and kd must be finite, not " + Text(v));
  if (kd != 0.0 && !f_lp_hz)
    throw InputError("pid: kd = " + Text(kd) + " needs f_lp_hz (a pure derivative is improper)");
  // kp + ki / s + kd s / (1 + s / w_lp), over the common denominator
  // s^[ki != 0] (1 + s / w_lp)^[f_lp given]; no factor that would cancel.
  Poly num{kp}, den{1.0};
  if (ki != 0.0) {
    num = {kp, ki};
    den = {1.0, 0.0};
  }
  if (f_lp_hz) {
    RequirePositive(*f_lp_hz, "pid f_lp_hz");
    const double w = Omega(*f_lp_hz);
    const Poly lp{1.0 / w, 1.0};
    // (num / den) + kd s / (1 + s / w) = (num lp + kd s den) / (den lp)
    Poly a = PolynomialProduct(num, lp), b = PolynomialProduct({kd, 0.0}, den);
    if (b.size() > a.size()) a.insert(a.begin(), b.size() - a.size(), 0.0);
    if (a.size() > b.size()) b.insert(b.begin(), a.size() - b.size(), 0.0);
    for (std::size_t i = 0; i < a.size(); ++i) a[i] += b[i];
    num = a;
    den = PolynomialProduct(den, lp);
  }
  return TransferFunction(num, den);
}

TransferFunction PidSeries(double gain, std::optional<double> f_i_hz, std::optional<double> f_d_hz,
                           std::optional<double> f_lp_hz) {
  if (!std::isfinite(gain)) throw InputError("pid: gain " + Text(gain) + " is not finite");
  if (f_d_hz && !f_lp_hz) throw InputError("pid: f_d_hz needs f_lp_hz (a pure derivative is improper)");
  Poly num{gain}, den{1.0};
  if (f_i_hz) {
    RequirePositive(*f_i_hz, "pid f_i_hz");
    num = PolynomialProduct(num, {1.0, Omega(*f_i_hz)});  // (s + w_i) / s
    den = PolynomialProduct(den, {1.0, 0.0});
  }
  if (f_d_hz) {
    RequirePositive(*f_d_hz, "pid f_d_hz");
    num = PolynomialProduct(num, {1.0 / Omega(*f_d_hz), 1.0});
  }
  if (f_lp_hz) {
    RequirePositive(*f_lp_hz, "pid f_lp_hz");
    den = PolynomialProduct(den, {1.0 / Omega(*f_lp_hz), 1.0});
  }
  return TransferFunction(num, den);
}

TransferFunction LeadLag(double f_hz, double phase_deg) {
  RequirePositive(f_hz, "lead_lag f_hz");
  if (!(std::abs(phase_deg) < 90.0))
    throw InputError("lead_lag: phase_deg must be between -90 and 90 (exclusive), not " + Text(phase_deg));
  const double s = std::sin(phase_deg * kPi / 180.0);
  const double a = (1.0 + s) / (1.0 - s), root = std::sqrt(a), w = Omega(f_hz);
  const double wz = w / root, wp = w * root;
  return TransferFunction({1.0 / (root * wz), 1.0 / root}, {1.0 / wp, 1.0});
}

TransferFunction Notch(double f_hz, double depth_db, double width_hz) {
  RequirePositive(f_hz, "notch f_hz");
  RequirePositive(depth_db, "notch depth_db");
  RequirePositive(width_hz, "notch width_hz");
  const double zeta_p = width_hz / (2.0 * f_hz);
  if (!(zeta_p < 1.0))
    throw InputError("notch: width_hz " + Text(width_hz) + " must be below 2 f_hz (" + Text(2.0 * f_hz) + ")");
  const double zeta_z = zeta_p * std::pow(10.0, -depth_db / 20.0), w = Omega(f_hz);
  return TransferFunction({1.0, 2.0 * zeta_z * w, w * w}, {1.0, 2.0 * zeta_p * w, w * w});
}

TransferFunction Lowpass(double f_hz, int order, FilterShape shape) {
  RequirePositive(f_hz, "lowpass f_hz");
  const std::vector<double> p = Prototype(order, shape);  // lowest first, s in units of w
  const double w = Omega(f_hz);
  // den(s) = sum p_k (s / w)^k, highest first.
  Poly den(p.size());
  for (std::size_t k = 0; k < p.size(); ++k) den[p.size() - 1 - k] = p[k] / std::pow(w, static_cast<double>(k));
  return TransferFunction({p[0]}, den);
}

TransferFunction Highpass(double f_hz, int order, FilterShape shape) {
  RequirePositive(f_hz, "highpass f_hz");
  const std::vector<double> p = Prototype(order, shape);
  const double w = Omega(f_hz);
  // H(s) = p0 / sum p_k (w / s)^k = p0 s^n / sum p_k w^k s^(n - k).
  const std::size_t n = p.size() - 1;
  Poly den(n + 1), num(n + 1, 0.0);
  for (std::size_t k = 0; k <= n; ++k) den[k] = p[k] * std::pow(w, static_cast<double>(k));
  num[0] = p[0];
  return TransferFunction(num, den);
}

TransferFunction Integrator(double f_hz) {
  RequirePositive(f_hz, "integrator f_hz");
  return TransferFunction({Omega(f_hz)}, {1.0, 0.0});
}

}  // namespace deb
