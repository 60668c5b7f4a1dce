// Small, independent numerics for the model tests: frequency response by a
// dense complex solve and the H2 norm from a Kronecker-form Lyapunov solve.
// Deliberately naive, so that they check the model rather than share its code.
#pragma once

#include <Eigen/Dense>
#include <complex>

#include "deb/systems/state_space.h"

namespace deb::test {

// H(j omega) = C (j omega I - A)^-1 B + D.
inline Eigen::MatrixXcd Response(const StateSpace& g, double omega) {
  const Eigen::Index n = g.states();
  const Eigen::MatrixXcd s_minus_a =
      std::complex<double>(0.0, omega) * Eigen::MatrixXcd::Identity(n, n) -
      g.A().cast<std::complex<double>>();
  return g.C().cast<std::complex<double>>() *
             s_minus_a.partialPivLu().solve(g.B().cast<std::complex<double>>()) +
         g.D().cast<std::complex<double>>();
}

// ||G||_2^2 = trace(C P C^T), A P + P A^T + B B^T = 0 (D = 0, A stable),
// solved as (I (x) A + A (x) I) vec(P) = -vec(B B^T).
inline double H2NormSquared(const StateSpace& g) {
  const Eigen::Index n = g.states();
  const Eigen::MatrixXd eye = Eigen::MatrixXd::Identity(n, n);
  Eigen::MatrixXd kron(n * n, n * n);
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j)
      kron.block(i * n, j * n, n, n) = eye(i, j) * g.A() + g.A()(i, j) * eye;
  const Eigen::MatrixXd q = g.B() * g.B().transpose();
  const Eigen::VectorXd vec_p =
      kron.fullPivLu().solve(-Eigen::Map<const Eigen::VectorXd>(q.data(), n * n));
  const Eigen::MatrixXd p = Eigen::Map<const Eigen::MatrixXd>(vec_p.data(), n, n);
  return (g.C() * p * g.C().transpose()).trace();
}

}  // namespace deb::test
