#include "deb/systems/modes.h"

#include <algorithm>
#include <cmath>

#include "deb/core/math_constants.h"

namespace deb {

double Mode::damped_f_hz() const { return pole_rad_s.imag() / kTwoPi; }

std::vector<Mode> ModesFromPoles(const Eigen::VectorXcd& poles_rad_s) {
  std::vector<Mode> modes;
  for (Eigen::Index k = 0; k < poles_rad_s.size(); ++k) {
    const std::complex<double> p = poles_rad_s(k);
    if (p.imag() < 0.0) continue;
    Mode m;
    m.pole_rad_s = p;
    m.pair = p.imag() > 0.0;
    const double mag = std::abs(p);
    m.f_n_hz = mag / kTwoPi;
    m.damping_ratio = mag > 0.0 ? -p.real() / mag : 1.0;
    modes.push_back(m);
  }
  std::sort(modes.begin(), modes.end(), [](const Mode& a, const Mode& b) {
    if (a.f_n_hz != b.f_n_hz) return a.f_n_hz < b.f_n_hz;
    return a.damping_ratio < b.damping_ratio;
  });
  return modes;
}

namespace {
double AxisTolerance(std::complex<double> p) { return 1e-9 * std::max(1.0, std::abs(p)); }
}  // namespace

bool IsStrictlyStable(std::complex<double> pole_rad_s) { return pole_rad_s.real() < -AxisTolerance(pole_rad_s); }

PoleStability ClassifyPoles(const Eigen::VectorXcd& poles_rad_s) {
  PoleStability s;
  for (Eigen::Index i = 0; i < poles_rad_s.size(); ++i) {
    const std::complex<double> p = poles_rad_s(i);
    if (p.real() > AxisTolerance(p)) s.unstable.push_back(p);
    else if (!IsStrictlyStable(p)) s.marginal.push_back(p);
  }
  return s;
}

std::vector<Mode> Modes(const StateSpace& sys) { return ModesFromPoles(sys.Poles()); }

}  // namespace deb
