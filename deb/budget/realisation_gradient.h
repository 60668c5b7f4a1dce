// Internal: not part of the public API.
// The exact derivative of every contributor's variance with respect to a
// parameter that acts on the budget only through its rational paths'
// realisations (A, B, C, D): a stiffness, a damping, a gain, a lever arm.
//
// The realisation's derivative dM = p dM/dp (M = A, B, C, D) comes from the
// matrices deb builds at p (1 +- h) and p (1 +- h/2), by the fourth-order
// (Richardson) central difference (4 D(h/2) - D(h)) / 3 with
// D(h) = (M(p (1 + h)) - M(p (1 - h))) / (2 h): no budget is evaluated for
// it, and it is exact to rounding for entries polynomial of degree <= 4 in p
// (a builder's k, c, gains and lever arms), else within ~h^4. From it the
// derivative of H,
//   dH = dC R B + C R dA R B + C R dB + dD,   R = (s I - A)^-1,
// is propagated exactly: the realisation
//   [A 0; dA A], [B; dB], [C + sigma dC, sigma C], D + sigma dD
// has the response H + sigma dH, so that the contributor's PSD derivative
// is dS = (S(H + dH) - S(H - dH)) / 2 exactly (S is quadratic in H), the
// tones' likewise; and the derivative of the variance on the grid is
// sum_i q_i dS_i with the integral's derivative weights q
// (IntegralGradientWeights). Unit conversions, weightings and the source's
// cross-spectra are those of the engine itself, which evaluates both.
//
// Refused, with the reason, where the parameter also changes anything else
// (a source, an output's weighting, a measured, modal, delayed or sampled
// path: found by evaluating the budget at p (1 + h) with only its rational
// paths put back to nominal, which must give the nominal variances), where a
// realisation changes size, or where its matrices are not smooth in p (the
// two central differences disagree: an eigenvector basis that reorders).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "deb/budget/budget.h"
#include "deb/budget/engine.h"
#include "deb/budget/result.h"

namespace deb {

struct RealisationGradient {
  bool exact = false;
  std::string note;  // how it was computed, or why it was not
  // d variance / d ln p (or / dp: see below) per output, per contributor
  // (the nominal's order); the output's total is their sum. Empty unless
  // exact.
  std::vector<std::vector<double>> d_variance;
};

// `scaled` holds the budget with the parameter multiplied by 1 + h, 1 - h,
// 1 + h/2 and 1 - h/2, each on the nominal's grid and bands (as a
// sensitivity's perturbed budgets), for d var / d ln p; or with h added and
// subtracted (p + h, p - h, p + h/2, p - h/2), for d var / dp. `nominal` is
// `budget` evaluated. `verify` evaluates scaled[0] with the rational paths
// put back (the refusal above); a caller that verified the parameter once
// (an optimiser, at the nominal design) may skip it at other designs.
// @throws InputError as Evaluate (of the budgets it evaluates).
RealisationGradient ComputeRealisationGradient(const Budget& budget, const BudgetResult& nominal,
                                               const std::array<Budget, 4>& scaled, double step,
                                               const EngineOptions& options, bool verify = true);

}  // namespace deb
