// A SISO rational transfer function H(s) = num(s) / den(s), the form in which
// filters, sensors and simple plants are usually written down. deb keeps it
// only as an entry format: everything downstream works on a StateSpace, so a
// transfer function is converted once, by ToStateSpace(). Closed loops are then
// built in state space (interconnect.h), never by multiplying polynomials,
// which loses accuracy quickly.
#pragma once

#include <complex>
#include <vector>

#include "deb/systems/state_space.h"

namespace deb {

class TransferFunction {
 public:
  // Coefficients highest power first, as in MATLAB: {1, 2, 3} = s^2 + 2 s + 3.
  // Leading zeros are trimmed. An empty or all-zero numerator is the zero
  // function.
  // @throws InputError if a coefficient is not finite, if the denominator is
  //         empty or all zero, or if the function is improper
  //         (deg num > deg den; the message states both degrees).
  TransferFunction(std::vector<double> num, std::vector<double> den);

  // A static gain k (= k / 1).
  static TransferFunction Gain(double k);

  const std::vector<double>& num() const { return num_; }
  const std::vector<double>& den() const { return den_; }
  // Degree of the denominator = number of states of ToStateSpace().
  int order() const { return static_cast<int>(den_.size()) - 1; }

  // num(s) / den(s) by Horner's rule. For checks and small orders only: the
  // state-space route (FrequencyResponse) is the accurate one.
  std::complex<double> Evaluate(std::complex<double> s) const;

 private:
  std::vector<double> num_, den_;
};

// Realisation with n = order() states, one input, one output.
// Order <= 2: controllable canonical form (that of MATLAB's tf2ss) with the
// denominator made monic, followed by StateSpace::Balanced().
// Order >= 3: a cascade (Series) of sections, one per real factor of the
// denominator (polynomial_factors.h): a real root or conjugate pair, or two
// real roots, realised in controllable canonical form; each numerator
// factor is paired with the nearest pole. The roots are the eigenvalues of
// the balanced companion matrix polished together (Aberth-Ehrlich) on the
// exact coefficients; (nearly) repeated roots are found together from their
// cluster's factor, computed as a whole from the coefficients, so the
// product of the sections is the given polynomial (separately polished
// repeated roots gave 1/(s + 1)^4 a DC gain 1.6e-5 off; a cluster realised
// as one companion section of high degree gave (s^2 + s/512 + 1)^-5 an H
// 3.1e-2 off).
// The sections' H is checked against num/den evaluated in double-double at
// each pole's frequency, where its error peaks; roots polished in long double
// are polished again in double-double if it is off by more than 1e-9 there
// (clustered modes at zeta 1e-3 as one order-24 polynomial: 2.5e-5 in long
// double, 1e-13 in double-double).
// A companion form of high order is hopelessly conditioned when distinct
// roots cluster (its eigenvector matrix is a Vandermonde matrix): for ten
// resonators at 3 % spacing, the Lyapunov variance of the companion form came
// out negative, that of the cascade is right to ~1e-9. If the factorisation
// fails (no conjugate pairs, non-finite roots) the companion form is used.
// @throws InputError "... cannot be located to the accuracy deb promises ..."
//         with the estimated error if the sections' H is still off by more
//         than 5e-7 relative (the variance then by up to 1e-6).
StateSpace ToStateSpace(const TransferFunction& tf);

// MIMO transfer matrix, tf[i][j] = path from input j to output i. Each entry is
// realised on its own and the realisations are stacked block-diagonally, so the
// result has sum(order) states and is in general NOT minimal (entries sharing a
// denominator get separate copies of its poles). That is harmless for
// frequency responses and Lyapunov variances, which depend only on H(s); call
// a model-reduction step first if the state count matters.
// @throws InputError if the matrix is empty or its rows differ in length.
StateSpace ToStateSpace(const std::vector<std::vector<TransferFunction>>& tf);

}  // namespace deb
