#include "deb/systems/irrational_block.h"

#include <cmath>
#include <string>
#include <utility>

#include "deb/core/error.h"
#include "deb/core/math_constants.h"
#include "deb/core/number_text.h"
#include "deb/systems/frequency_response.h"
#include "deb/systems/interconnect.h"
#include "deb/systems/polynomial_product.h"
#include "deb/systems/transfer_function.h"

namespace deb {
namespace {

// Polynomials lowest power first here; TransferFunction takes highest first.
using Poly = std::vector<double>;

Poly Power(const Poly& p, int k) {
  Poly r{1.0};
  for (int i = 0; i < k; ++i) r = PolynomialProduct(r, p);
  return r;
}

Poly Add(Poly a, const Poly& b) {
  if (b.size() > a.size()) a.resize(b.size(), 0.0);
  for (std::size_t i = 0; i < b.size(); ++i) a[i] += b[i];
  return a;
}

Poly HighestFirst(Poly p) { return Poly(p.rbegin(), p.rend()); }

std::string Text(double v) { return SignificantText(v, 6); }

void RequirePadeOrder(int n) {
  if (n < kMinPadeOrder || n > kMaxPadeOrder)
    throw InputError("the Pade order must be " + std::to_string(kMinPadeOrder) + " to " +
                     std::to_string(kMaxPadeOrder) + ", not " + std::to_string(n));
}

// c_k of the Pade (n, n) approximant of e^(-x) = N(-x) / N(x), N(x) = sum c_k x^k.
Poly PadeCoefficients(int n) {
  Poly c(static_cast<std::size_t>(n) + 1);
  c[0] = 1.0;
  for (int k = 0; k < n; ++k) c[k + 1] = c[k] * (n - k) / ((2.0 * n - k) * (k + 1.0));
  return c;
}

// The realisation of g(x) = num(x) / den(x) (lowest power first) as a
// function of s with x = s * scale_s: (A / scale, B / scale, C, D).
StateSpace InTimeScale(const Poly& num, const Poly& den, double scale_s) {
  const StateSpace g = ToStateSpace(TransferFunction(HighestFirst(num), HighestFirst(den)));
  if (g.states() == 0) return g;
  return StateSpace(g.A() / scale_s, g.B() / scale_s, g.C(), g.D());
}

// e^(-s tau) ~ N(-s tau) / N(s tau).
StateSpace PadeDelay(double tau_s, int n) {
  const Poly c = PadeCoefficients(n);
  Poly num = c;
  for (std::size_t k = 1; k < num.size(); k += 2) num[k] = -num[k];
  return InTimeScale(num, c, tau_s);
}

// (1 - e^(-sT)) / (sT) with e^(-sT) ~ N(-y)/N(y), y = sT:
// (N(y) - N(-y)) / (y N(y)) = 2 sum_{k odd} c_k y^(k - 1) / N(y), 1 at DC.
StateSpace PadeHold(double t_s, int n) {
  const Poly c = PadeCoefficients(n);
  Poly num(static_cast<std::size_t>(n), 0.0);
  for (int k = 1; k <= n; k += 2) num[k - 1] = 2.0 * c[k];
  return InTimeScale(num, c, t_s);
}

Poly Trimmed(std::vector<double> highest_first, const char* what) {
  for (double v : highest_first)
    if (!std::isfinite(v)) throw InputError(std::string(what) + ": coefficient " + Text(v) + " is not finite");
  std::size_t lead = 0;
  while (lead < highest_first.size() && highest_first[lead] == 0.0) ++lead;
  return Poly(highest_first.begin() + static_cast<std::ptrdiff_t>(lead), highest_first.end());
}

std::complex<double> Horner(const Poly& highest_first, std::complex<double> z) {
  std::complex<double> v = 0.0;
  for (double c : highest_first) v = v * z + c;
  return v;
}

// num(z) / den(z) at z = (1 + x) / (1 - x), both times (1 - x)^n, n = deg den:
// sum_j b_j (1 + x)^(m - j) (1 - x)^(n - m + j) over sum_j a_j (1 + x)^(n - j) (1 - x)^j.
std::pair<Poly, Poly> InverseTustin(const Poly& num, const Poly& den) {
  const int n = static_cast<int>(den.size()) - 1, m = static_cast<int>(num.size()) - 1;
  const Poly p{1.0, 1.0}, q{1.0, -1.0};
  Poly b{0.0}, a{0.0};
  for (int j = 0; j <= m; ++j) {
    Poly t = PolynomialProduct(Power(p, m - j), Power(q, n - m + j));
    for (double& v : t) v *= num[j];
    b = Add(b, t);
  }
  for (int j = 0; j <= n; ++j) {
    Poly t = PolynomialProduct(Power(p, n - j), Power(q, j));
    for (double& v : t) v *= den[j];
    a = Add(a, t);
  }
  return {b, a};
}

std::string Duration(double s) {
  if (s == 0.0) return "0 s";
  if (s < 1e-3) return Text(s * 1e6) + " us";
  if (s < 1.0) return Text(s * 1e3) + " ms";
  return Text(s) + " s";
}

std::string Rate(double hz) { return hz >= 1e3 ? Text(hz / 1e3) + " kHz" : Text(hz) + " Hz"; }

}  // namespace

std::complex<double> IrrationalBlock::At(double f_hz) const {
  const double w = 2.0 * kPi * f_hz;
  if (kind == Kind::kDelay) return std::polar(1.0, -w * delay_s);
  const double wt = w / sample_hz;
  const std::complex<double> z = std::polar(1.0, wt);
  std::complex<double> h = Horner(num_z, z) / Horner(den_z, z);
  if (zoh && wt != 0.0) h *= std::polar(std::sin(wt / 2.0) / (wt / 2.0), -wt / 2.0);
  return h;
}

std::complex<double> IrrationalBlock::ApproximationAt(double f_hz) const {
  return FrequencyResponse(approximation).At(f_hz)(0, 0);
}

std::string IrrationalBlock::Describe() const {
  if (kind == Kind::kDelay) return "a delay of " + Duration(delay_s);
  return "a " + Rate(sample_hz) + " sampled block" + (zoh ? " with a zero-order hold" : "");
}

std::string IrrationalBlock::DescribeApproximation() const {
  const std::string pade = "Pade (" + std::to_string(pade_order) + ", " + std::to_string(pade_order) + ")";
  if (kind == Kind::kDelay) return delay_s == 0.0 ? "exact (a unit gain)" : pade;
  return std::string("its Tustin continuous equivalent") + (zoh ? ", the hold by " + pade : "");
}

ApproximationError ApproximationErrorAt(const IrrationalBlock& block, double f_hz) {
  const std::complex<double> ratio = block.ApproximationAt(f_hz) / block.At(f_hz);
  return {std::abs(ratio), std::arg(ratio) * 180.0 / kPi};
}

IrrationalBlock Delay(double tau_s, int pade_order) {
  if (!std::isfinite(tau_s) || !(tau_s >= 0.0))
    throw InputError("a delay must be a finite number of seconds >= 0, not " + Text(tau_s));
  RequirePadeOrder(pade_order);
  IrrationalBlock b;
  b.kind = IrrationalBlock::Kind::kDelay;
  b.delay_s = tau_s;
  b.pade_order = pade_order;
  if (tau_s > 0.0) b.approximation = PadeDelay(tau_s, pade_order);
  return b;
}

IrrationalBlock Discrete(double sample_hz, std::vector<double> num_z, std::vector<double> den_z, bool zoh,
                         int pade_order) {
  if (!std::isfinite(sample_hz) || !(sample_hz > 0.0))
    throw InputError("sample_hz must be a finite number > 0, not " + Text(sample_hz));
  RequirePadeOrder(pade_order);
  const Poly num = Trimmed(std::move(num_z), "num"), den = Trimmed(std::move(den_z), "den");
  if (den.empty()) throw InputError("den: the denominator is zero");
  if (num.size() > den.size())
    throw InputError("the block is not causal: num has degree " + std::to_string(num.size() - 1) +
                     " in z, den degree " + std::to_string(den.size() - 1) + " (num's may not be higher)");
  IrrationalBlock b;
  b.kind = IrrationalBlock::Kind::kDiscrete;
  b.sample_hz = sample_hz;
  b.num_z = num.empty() ? Poly{0.0} : num;
  b.den_z = den;
  b.zoh = zoh;
  b.pade_order = pade_order;
  double size = 0.0;
  for (double a : den) size += std::abs(a);
  if (std::abs(Horner(den, -1.0)) <= 1e-12 * size)
    throw InputError("den has a root at z = -1 (the Nyquist frequency), which no continuous equivalent has: the "
                     "Tustin map sends it to infinity");
  const double t = 1.0 / sample_hz;
  const auto [b_x, a_x] = InverseTustin(b.num_z, den);
  StateSpace equivalent = InTimeScale(b_x, a_x, t / 2.0);
  b.approximation = zoh ? Series(equivalent, PadeHold(t, pade_order)) : equivalent;
  return b;
}

}  // namespace deb
