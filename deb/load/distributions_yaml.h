// Internal: not part of the public API.
// YAML -> the uncertain parameters of a budget (deb/uncertainty/uncertainty_study.h): the
// `distribution:` of budget parameters and the budget's `correlations:`
// (docs/budget_reference.md, "Uncertain parameters"):
//   parameters:
//     k_iso: {value: 5.2e4 N/m, distribution: {normal: {sigma: 5 %}}}
//     zeta:  {value: 0.02, distribution: {uniform: {min: 0.01, max: 0.03}}}
//     s_geo: {value: 20 (nm/s)^2/Hz, distribution: {lognormal: {p95: 40 (nm/s)^2/Hz}}}
//   correlations: [{between: [k_iso, k_tilt], rho: 0.8}]
// Distributions: normal {sigma}, uniform {min, max}, lognormal {p95 |
// sigma_log} (its median the value), truncated_normal {sigma, min, max},
// triangular {min, max} (its mode the value), discrete {values, p}. A
// number with a unit must be the parameter's quantity; a plain number is in
// the unit the value is written in; sigma may be a percentage of the value.
#pragma once

#include "deb/load/yaml_reader.h"
#include "deb/parameters/parameter_set.h"
#include "deb/uncertainty/uncertainty_study.h"

namespace deb::load {
// The uncertain parameters of `root`'s `parameters:` (evaluated as
// `parameters`) and its `correlations:`; none when no parameter has a
// distribution. @throws InputError located at the key for every rule: an
// unknown distribution or key, a value in another quantity, sigma <= 0,
// min >= max, a log-normal value <= 0 or p95 not above it, probabilities
// that do not add up to 1, a distribution on a derived parameter, a
// correlation of an unknown or certain parameter, of one with itself, given
// twice, |rho| > 1, or a correlation matrix that is not positive definite.
UncertaintySpec ParseUncertainty(const YamlNode& root, const ParameterSet& parameters);

// A number given for parameter `p` (a distribution's sigma, a bound), in SI:
// a quantity of its dimension, a plain number in its unit (one unit is
// unit_si), or with `percent` a percentage of |p's value|.
// @throws InputError located at `node`.
double ParameterValueOf(const YamlNode& node, const Parameter& p, double unit_si, const ParameterSet& parameters,
                        bool percent);

}  // namespace deb::load
