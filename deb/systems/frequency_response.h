// Fast evaluation of H(j 2 pi f) = C (j 2 pi f I - A)^-1 B + D at many
// frequencies. A budget evaluates every path at 10^4..10^5 frequencies, so the
// O(n^3) work on A is done once, in the constructor, and each frequency costs
// O(n p m):
//
//  - modal form (default when it is accurate): A = V diag(lambda) V^-1, so
//      H(s) = D + sum_k R_k / (s - lambda_k),  R_k = (C V)_k (V^-1 B)_k,
//    with each complex-conjugate pair merged into one real second-order term
//      (s P - Q) / ((s - lambda)(s - conj lambda)),  P = 2 Re R, Q = 2 Re(R conj lambda).
//    The factor (s - lambda) is formed as a difference before any product, so
//    lightly damped poles (zeta = 1e-4 and below) keep full relative accuracy.
//    Rounding in V^-1 is amplified by cond(V), hence the modal form is used
//    only if cond(V) <= kMaxModalCondition.
//  - Schur form (fallback, backward stable for any A, e.g. defective or
//    nearly repeated poles): A = U T U^H, T upper triangular, and
//      H(s) = (C U) (sI - T)^-1 (U^H B) + D
//    by triangular substitution on the cheaper side, min(outputs, inputs)
//    right-hand sides.
//
// Before either reduction the state is balanced (StateSpace::Balanced), which
// changes nothing in H but reduces cond(V) for models in mixed units.
//
// A frequency at which j 2 pi f is (numerically) a pole has no finite response;
// such a frequency comes from the user's grid (e.g. f = 0 with an integrator
// in the path), so it is reported as InputError rather than returned as
// inf/NaN.
#pragma once

#include <Eigen/Dense>
#include <cstddef>
#include <functional>
#include <vector>

#include "deb/systems/state_space.h"

namespace deb {

class FrequencyResponse {
 public:
  enum class Method { kAuto, kModal, kSchur };

  // Largest 1-norm condition number of the (unit-column) eigenvector matrix
  // for which Method::kAuto picks the modal form; relative errors scale like
  // 1e-16 * cond(V), so this keeps them near 1e-10 or below.
  static constexpr double kMaxModalCondition = 1e6;

  // Reduces A once. kModal forces the modal form even when cond(V) is large
  // (for benchmarks and tests); kSchur forces the Schur form.
  explicit FrequencyResponse(const StateSpace& sys, Method method = Method::kAuto);

  int states() const { return n_; }
  int inputs() const { return m_; }
  int outputs() const { return p_; }
  // The reduction in use: kModal or kSchur.
  Method method() const { return method_; }
  // 1-norm condition number of the unit-column eigenvector matrix (computed
  // also when kSchur is forced; huge or infinite if A is defective).
  double eigenvector_condition() const { return eigenvector_condition_; }

  // H(j 2 pi f), outputs x inputs.
  // @throws InputError if f_hz is not finite or j 2 pi f coincides with a pole.
  Eigen::MatrixXcd At(double f_hz) const;

  // H at every frequency, result[k] = At(f_hz[k]), computed with ParallelFor
  // (threads <= 0: DefaultThreadCount()). Bitwise equal to At() and
  // independent of the thread count.
  std::vector<Eigen::MatrixXcd> Evaluate(const std::vector<double>& f_hz, int threads = 0) const;

  // Calls fn(k, H(j 2 pi f_hz[k])) for every k without storing the matrices:
  // for callers that only need a reduction per frequency (output PSDs). fn is
  // called concurrently from several threads, with distinct k; the matrix
  // reference is valid only during the call.
  using Visitor = std::function<void(std::size_t k, const Eigen::MatrixXcd& h)>;
  void ForEach(const std::vector<double>& f_hz, const Visitor& fn, int threads = 0) const;

 private:
  struct Workspace;
  void EvaluateInto(double f_hz, Workspace& w, Eigen::MatrixXcd& h) const;
  void EvaluateModal(double omega, Workspace& w, Eigen::MatrixXcd& h) const;
  void EvaluateSchur(double omega, Workspace& w, Eigen::MatrixXcd& h) const;
  [[noreturn]] void ThrowOnPole(double f_hz, std::complex<double> pole) const;

  int n_ = 0, m_ = 0, p_ = 0;
  Method method_ = Method::kSchur;
  double eigenvector_condition_ = 0.0;
  double pole_tolerance_ = 0.0;  // |j omega - lambda| below this counts as on a pole
  Eigen::MatrixXd d_;

  // Modal form: one real pole or one conjugate pair (re, im > 0) per term.
  // Real pole: H += R / (s - re), column R of residues_. Pair: columns P, Q.
  struct Term {
    double re, im;
    bool pair;
  };
  std::vector<Term> terms_;
  Eigen::MatrixXd residues_;  // (outputs*inputs) x columns, column-major H layout

  // Schur form, arranged so that the substitution runs on r = min(outputs,
  // inputs) rows: G = L (sI - T)^-1 R with T upper triangular (n x n), L r x n,
  // R n x max(outputs, inputs); H = G + D, or H = G^T + D when the inputs are
  // fewer (then T is J T_schur^T J with J the reversal, still triangular).
  // Real and imaginary parts are stored apart for the inner loops.
  bool schur_transposed_ = false;
  Eigen::VectorXcd schur_diag_;
  Eigen::MatrixXd tr_, ti_, lr_, li_, rr_, ri_;
};

}  // namespace deb
