#include "deb/signal/self_noise.h"

#include <cmath>
#include <set>

#include "deb/core/error.h"

namespace deb {
namespace {

void CheckSensors(const CsdEstimate& csd, const std::vector<int>& sensors) {
  for (int s : sensors) {
    if (s < 0 || s >= csd.channels)
      throw InputError("self-noise: sensor index " + std::to_string(s) + " is out of range; the estimate has " +
                       std::to_string(csd.channels) + " channels");
  }
  if (std::set<int>(sensors.begin(), sensors.end()).size() != sensors.size())
    throw InputError("self-noise: the same channel is given twice; the sensors must be distinct recordings");
}

SelfNoiseEstimate Start(const CsdEstimate& csd, const std::vector<int>& sensors, std::string method) {
  SelfNoiseEstimate r;
  r.noise.f_hz = csd.f_hz;
  r.noise.psd.resize(static_cast<Eigen::Index>(csd.f_hz.size()), static_cast<Eigen::Index>(sensors.size()));
  for (int s : sensors) r.noise.channel_names.push_back(csd.channel_names[static_cast<std::size_t>(s)]);
  r.noise.unit = csd.unit;
  r.noise.provenance = csd.provenance;
  r.method = std::move(method);
  r.clamped_bins.assign(sensors.size(), 0);
  return r;
}

void Clamp(SelfNoiseEstimate* r) {
  for (Eigen::Index c = 0; c < r->noise.psd.cols(); ++c) {
    for (Eigen::Index k = 0; k < r->noise.psd.rows(); ++k) {
      double& v = r->noise.psd(k, c);
      if (!(v >= 0.0)) {  // also catches NaN from 0/0
        v = 0.0;
        ++r->clamped_bins[static_cast<std::size_t>(c)];
      }
    }
  }
}

}  // namespace

SelfNoiseEstimate TwoSensorSelfNoise(const CsdEstimate& csd, int a, int b) {
  CheckSensors(csd, {a, b});
  SelfNoiseEstimate r =
      Start(csd, {a, b},
            "two-sensor (Holcomb 1989): N = S_aa (1 - sqrt(coherence)); assumes identical sensors (equal, unit "
            "responses and equal noise)");
  const Eigen::VectorXd gamma = csd.Coherence(a, b).cwiseSqrt();
  const Eigen::VectorXd one = Eigen::VectorXd::Ones(gamma.size());
  r.noise.psd.col(0) = csd.Auto(a).cwiseProduct(one - gamma);
  r.noise.psd.col(1) = csd.Auto(b).cwiseProduct(one - gamma);
  Clamp(&r);
  return r;
}

SelfNoiseEstimate ThreeSensorSelfNoise(const CsdEstimate& csd, int a, int b, int c) {
  CheckSensors(csd, {a, b, c});
  SelfNoiseEstimate r = Start(csd, {a, b, c},
                              "three-sensor (Sleeman et al. 2006): N_aa = Re(S_aa - S_ba S_ac / S_bc); assumes "
                              "independent noises, any responses");
  const int order[3][3] = {{a, b, c}, {b, c, a}, {c, a, b}};
  for (int s = 0; s < 3; ++s) {
    const int i = order[s][0], j = order[s][1], k = order[s][2];
    const Eigen::VectorXcd sji = csd.Cross(j, i), sik = csd.Cross(i, k), sjk = csd.Cross(j, k);
    const Eigen::VectorXd sii = csd.Auto(i);
    for (Eigen::Index f = 0; f < sii.size(); ++f) {
      r.noise.psd(f, s) = std::abs(sjk(f)) > 0.0 ? sii(f) - (sji(f) * sik(f) / sjk(f)).real() : sii(f);
    }
  }
  Clamp(&r);
  return r;
}

}  // namespace deb
