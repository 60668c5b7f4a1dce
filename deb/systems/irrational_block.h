// Blocks whose transfer is not a ratio of polynomials in s: a time delay and
// a sampled (discrete-time) controller. On a frequency grid each is
// evaluated exactly; poles, stability and the Lyapunov variance need a
// rational model, so each also carries a stated rational approximation:
//   delay       e^(-s tau)                       Pade (n, n) approximant
//   discrete    H_d(e^(s T)) [zoh (1 - e^(-sT))/(sT)]   H_d at the inverse
//               Tustin map z = (1 + sT/2)/(1 - sT/2), the hold by the Pade
//               approximant of e^(-sT) in it
// The formulas, and how good each approximation is, are in docs/method.md
// ("Delays and sampled blocks").
#pragma once

#include <complex>
#include <string>
#include <vector>

#include "deb/systems/state_space.h"

namespace deb {

struct IrrationalBlock {
  enum class Kind { kDelay, kDiscrete };
  Kind kind = Kind::kDelay;
  double delay_s = 0.0;                 // kDelay
  double sample_hz = 0.0;               // kDiscrete
  std::vector<double> num_z, den_z;     // kDiscrete, highest power of z first
  bool zoh = false;                     // kDiscrete: a zero-order hold at the output
  int pade_order = 0;                   // of the delay, or of the hold's e^(-sT)
  StateSpace approximation = StateSpace::Gain(Eigen::MatrixXd::Ones(1, 1));

  // H(j 2 pi f_hz), exact.
  std::complex<double> At(double f_hz) const;
  // The approximation's H(j 2 pi f_hz).
  std::complex<double> ApproximationAt(double f_hz) const;
  // The sampled block's Nyquist frequency sample_hz / 2; 0 for a delay.
  double nyquist_hz() const { return kind == Kind::kDiscrete ? sample_hz / 2.0 : 0.0; }
  // What it is, e.g. "a delay of 100 us" or "a 10 kHz sampled block with a
  // zero-order hold".
  std::string Describe() const;
  // How it is approximated, e.g. "Pade (6, 6)".
  std::string DescribeApproximation() const;
};

// The error of the approximation at f_hz: approximation / exact, as a gain
// ratio and a phase in degrees (in (-180, 180]).
struct ApproximationError {
  double gain_ratio = 1.0;
  double phase_deg = 0.0;
};
ApproximationError ApproximationErrorAt(const IrrationalBlock& block, double f_hz);

// Pade orders deb accepts, and the one it takes when none is given.
inline constexpr int kMinPadeOrder = 1;
inline constexpr int kMaxPadeOrder = 12;
inline constexpr int kDefaultPadeOrder = 6;

// e^(-s tau), tau >= 0 (0: a unit gain), approximated by the Pade (n, n)
// approximant N(s tau) / N(-s tau), N(x) = sum_k c_k x^k,
// c_k = (2n - k)! n! / ((2n)! k! (n - k)!), an all-pass: |H| = 1 exactly.
// @throws InputError naming the rule (tau finite and >= 0, n in range).
IrrationalBlock Delay(double tau_s, int pade_order = kDefaultPadeOrder);

// num(z) / den(z) at z = e^(j 2 pi f / sample_hz), coefficients highest power
// first (deg num <= deg den: causal), with zoh the hold's
// (1 - e^(-j w T)) / (j w T) = e^(-j w T/2) sinc(w T/2).
// @throws InputError naming the rule (sample_hz > 0, finite coefficients, a
//   causal and non-zero denominator, no pole at z = -1, which the Tustin
//   map sends to infinity).
IrrationalBlock Discrete(double sample_hz, std::vector<double> num_z, std::vector<double> den_z, bool zoh,
                         int pade_order = kDefaultPadeOrder);

}  // namespace deb
