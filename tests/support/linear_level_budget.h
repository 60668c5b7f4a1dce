// A budget whose one contributor's variance is linear in a uniform
// parameter: white noise of level s x 1e-6 N^2/Hz (s uniform on [1, 3])
// through a gain of 1 um/N over 1..100 Hz, so var = 99 s um^2 and
// P(RMS <= 0.014 um) is a closed form; plus d (normal, 10 %) and a derived
// two_s, which the level does not read. The uncertainty study's tests and
// deb merge's share it.
#pragma once

#include <string>

namespace deb::test {

inline const std::string kLinearLevelBudget = R"(name: lin
parameters:
  s: {value: 2, distribution: {uniform: {min: 1, max: 3}}}
  d: {value: 5 mm, distribution: {normal: {sigma: 10 %}}}
  two_s: 2 * s
grid: {type: log, min_hz: 1, max_hz: 100, points: 50}
sources:
  - {name: noise, unit: N, spectrum: {type: flat, level: s * 1e-6}}
paths:
  - {name: plant, type: gain, gain: [[1]], input_unit: N, output_unit: um}
contributors:
  - {name: c1, source: noise, path: plant}
outputs:
  - {name: z, signal: y, unit: um, rms_max: 0.014}
)";

}  // namespace deb::test
