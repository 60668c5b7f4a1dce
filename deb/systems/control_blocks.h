// The blocks control engineers write, as transfer functions in s (rad/s),
// each from the formula stated here and in docs/method.md. Frequencies are
// in Hz (omega = 2 pi f); every function checks its arguments and throws
// InputError naming the rule broken.
#pragma once

#include <optional>
#include <vector>

#include "deb/systems/transfer_function.h"

namespace deb {

// A root of a zpk block, in Hz: real, s = -2 pi f_hz (f_hz < 0: the right
// half plane; 0: the origin), the factor (s + 2 pi f_hz); or, with zeta, the
// pair of s^2 + 2 zeta omega s + omega^2 (|zeta| < 1, f_hz > 0).
struct ZpkRoot {
  double f_hz = 0.0;
  std::optional<double> zeta;
};

// gain * prod(zero factors) / prod(pole factors), the factors monic in s.
// More zeros than poles is an error (improper).
TransferFunction Zpk(const std::vector<ZpkRoot>& zeros, const std::vector<ZpkRoot>& poles, double gain);
// The same with the gain that makes |H(j 2 pi f_hz)| = magnitude (> 0).
TransferFunction ZpkWithGainAt(const std::vector<ZpkRoot>& zeros, const std::vector<ZpkRoot>& poles, double f_hz,
                               double magnitude);

// gain omega^2 / (s^2 + 2 zeta omega s + omega^2): a resonance at f_hz with
// DC gain `gain` (zeta > 0).
TransferFunction SecondOrder(double f_hz, double zeta, double gain);

// Force to displacement of a mass on a spring and damper, SI:
// 1 / (m s^2 + d s + k) in m/N (m > 0, k >= 0, d >= 0).
TransferFunction MassSpringDamper(double m_kg, double k_n_per_m, double d_n_s_per_m);

// Parallel PID: kp + ki / s + kd s / (1 + s / omega_lp). Without f_lp_hz
// kd must be 0 (a pure derivative is improper).
TransferFunction PidParallel(double kp, double ki, double kd, std::optional<double> f_lp_hz);
// Series ("engineering") PID: gain (1 + omega_i / s) (1 + s / omega_d) /
// (1 + s / omega_lp), each factor present only if its frequency is given;
// f_d_hz needs f_lp_hz.
TransferFunction PidSeries(double gain, std::optional<double> f_i_hz, std::optional<double> f_d_hz,
                           std::optional<double> f_lp_hz);

// Lead (phase_deg > 0) or lag (< 0) of phase_deg at f_hz, the most it gives
// there, and unit gain at f_hz: (1 / sqrt(a)) (1 + s / omega_z) / (1 + s /
// omega_p), omega_z = omega / sqrt(a), omega_p = omega sqrt(a),
// a = (1 + sin phi) / (1 - sin phi); |phase_deg| < 90.
TransferFunction LeadLag(double f_hz, double phase_deg);

// A notch at f_hz: (s^2 + 2 zeta_z omega s + omega^2) / (s^2 + 2 zeta_p
// omega s + omega^2), zeta_p = width_hz / (2 f_hz) (the width of the pole
// pair's half-power band), zeta_z = zeta_p 10^(-depth_db / 20): |H| is 1 at
// DC and far above, 10^(-depth_db / 20) at f_hz. depth_db > 0, width_hz > 0.
TransferFunction Notch(double f_hz, double depth_db, double width_hz);

enum class FilterShape { kButterworth, kBessel };
// Low- or high-pass of order 1..10 with -3 dB (|H| = 1/sqrt 2) at f_hz,
// unit gain in its pass band. Butterworth: the poles omega e^(j pi (2k + n
// - 1) / (2n)); Bessel: the reverse Bessel polynomial, scaled in frequency
// to -3 dB at f_hz; the high-pass is the low-pass with s -> omega^2 / s.
TransferFunction Lowpass(double f_hz, int order, FilterShape shape);
TransferFunction Highpass(double f_hz, int order, FilterShape shape);

// An integrator with unit gain at f_hz: omega / s.
TransferFunction Integrator(double f_hz);

}  // namespace deb
