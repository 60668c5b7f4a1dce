#include "deb/spectra/peterson_noise_model.h"

#include <cmath>

#include "deb/core/error.h"
#include "deb/core/limits.h"
#include "deb/core/number_text.h"

namespace deb {

double PetersonAccelerationPsd(PetersonModel model, double f_hz) {
  if (!(f_hz >= PetersonSpectrum::kMinHz && f_hz <= PetersonSpectrum::kMaxHz))
    throw InputError("Peterson " + ToString(model) + ": " + NumberText(f_hz) +
                     " Hz is outside the model's range, 1e-05-10 Hz (periods 0.1-100000 s)");
  const double period = 1.0 / f_hz;
  const std::vector<PetersonSegment>& segments = PetersonSegments(model);
  const PetersonSegment* s = &segments.back();
  for (const PetersonSegment& candidate : segments) {
    if (period < candidate.period_to_s) {
      s = &candidate;
      break;
    }
  }
  const double db = s->a_db + s->b_db * std::log10(period);
  return std::pow(10.0, db / 10.0);
}

PetersonSpectrum::PetersonSpectrum(PetersonModel model, Extrapolation extrapolation)
    : model_(model), extrapolation_(extrapolation) {}

double PetersonSpectrum::PsdAt(double f_hz) const {
  if (f_hz < kMinHz || f_hz > kMaxHz) {
    if (extrapolation_ == Extrapolation::kZero) return 0.0;
    if (extrapolation_ == Extrapolation::kHold) return PetersonAccelerationPsd(model_, f_hz < kMinHz ? kMinHz : kMaxHz);
    throw InputError("Peterson " + ToString(model_) + ": " + NumberText(f_hz) +
                     " Hz is outside the model's range, 1e-05-10 Hz (periods 0.1-100000 s; extrapolation: error); "
                     "keep the frequency range inside it or choose extrapolation zero or hold");
  }
  return PetersonAccelerationPsd(model_, f_hz);
}

Eigen::MatrixXcd PetersonSpectrum::Csd(double f_hz) const { return Eigen::MatrixXcd::Constant(1, 1, PsdAt(f_hz)); }

Eigen::VectorXd PetersonSpectrum::Psd(double f_hz) const { return Eigen::VectorXd::Constant(1, PsdAt(f_hz)); }

std::vector<double> PetersonSpectrum::BreakpointsHz() const {
  std::vector<double> f;
  const std::vector<PetersonSegment>& segments = PetersonSegments(model_);
  f.push_back(1.0 / segments.back().period_to_s);
  for (auto it = segments.rbegin(); it != segments.rend(); ++it) f.push_back(1.0 / it->period_from_s);
  return f;
}

std::string PetersonSpectrum::Describe() const {
  return std::string("Peterson (1993) ") + (model_ == PetersonModel::kLow ? "New Low" : "New High") +
         " Noise Model, vertical acceleration, 1e-05-10 Hz; PSD in (m/s^2)^2/Hz; outside: " +
         ToString(extrapolation_);
}

std::vector<double> PetersonFrequencies(double points_per_decade) {
  if (!(points_per_decade >= 1.0 && points_per_decade <= limits::kMaxPointsPerDecade))
    throw InputError("points per decade " + NumberText(points_per_decade) + " is invalid; it must be from 1 to " +
                     std::to_string(static_cast<long long>(limits::kMaxPointsPerDecade)));
  std::vector<double> f;
  const int n = static_cast<int>(std::ceil(6.0 * points_per_decade));
  for (int i = 0; i <= n; ++i) f.push_back(PetersonSpectrum::kMinHz * std::pow(10.0, 6.0 * i / n));
  f.back() = PetersonSpectrum::kMaxHz;
  return f;
}

}  // namespace deb
