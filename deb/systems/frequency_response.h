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
//  - block Schur form (fallback when cond(V) is large: defective or nearly
//    repeated poles): A = S T S^-1 with T block diagonal, upper triangular
//    blocks, S well conditioned (block_schur.h). A 1x1 block is a modal term
//    with a complex residue; a block of a few states contributes
//      sum_{a<=b} [(sI - T_c)^-1]_ab (C S)_a (S^-1 B)_b;
//    a larger block is solved by triangular substitution on the cheaper side,
//    min(outputs, inputs) right-hand sides. With one block this is the plain
//    Schur method, backward stable for any A.
//
// Before either reduction the state is balanced (StateSpace::Balanced), which
// changes nothing in H but reduces cond(V) for models in mixed units.
//
// Measured with bench/bench_response (12 states, 6 outputs, 10 inputs,
// 10^5 frequencies, one core, CPU time): modal 17 ms, block Schur 37 ms, a
// dense LU solve per frequency 480 ms. The modal form is the cheaper one: two
// real multiply-adds per pole and entry of H, against four for the complex
// residues of the block Schur form.
//
// A frequency at which j 2 pi f is (numerically) a pole has no finite response;
// such a frequency comes from the user's grid (e.g. f = 0 with an integrator
// in the path), so it is reported as InputError rather than returned as
// inf/NaN. "Numerically" means within 64 eps (|A| + |omega|) of a computed
// eigenvalue; a pole of multiplicity k is only known to about eps^(1/k) |A|,
// so right next to a multiple pole H may come out large but finite.
#pragma once

#include <Eigen/Dense>
#include <cstddef>
#include <functional>
#include <vector>

#include "deb/systems/state_space.h"

namespace deb {

class FrequencyResponse {
 public:
  enum class Method { kAuto, kModal, kSchur, kHessenberg };

  // Largest 1-norm condition number of the (unit-column) eigenvector matrix
  // for which Method::kAuto picks the modal form; relative errors scale like
  // 1e-16 * cond(V), so this keeps them near 1e-10 or below.
  static constexpr double kMaxModalCondition = 1e6;

  // Reduces A once. kModal forces the modal form even when cond(V) is large
  // (for benchmarks and tests); kSchur forces the block Schur form;
  // kHessenberg the Hessenberg form, solved at every frequency (O(n^2 m)
  // each, backward stable whatever the poles: the reference kAuto checks the
  // fast forms against and falls back to).
  // @throws InputError if kModal is forced on a numerically defective A
  //         (cond(V) > 1e-3 / eps), or if A is too badly scaled (balanced
  //         norm above limits::kMaxStateMatrixNorm, or an eigenvalue
  //         iteration that does not converge).
  explicit FrequencyResponse(const StateSpace& sys, Method method = Method::kAuto);

  int states() const { return n_; }
  int inputs() const { return m_; }
  int outputs() const { return p_; }
  // The reduction in use: kModal or kSchur.
  Method method() const { return method_; }
  // 1-norm condition number of the unit-column eigenvector matrix (computed
  // also when kSchur is forced; huge or infinite if A is defective).
  double eigenvector_condition() const { return eigenvector_condition_; }
  // Size of the largest diagonal block of the block Schur form (1 for the
  // modal form): 2 for a double pole, n if no eigenvalue could be split off.
  int largest_block() const { return largest_block_; }
  // The eigenvalues of A [rad/s] (empty without states), found block by
  // block on its block triangular form (block_triangular.h).
  const Eigen::VectorXcd& poles() const { return poles_; }

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
  enum class TermKind { kRealPole, kPolePair, kBlock, kLargeBlock };
  // kRealPole at re, kPolePair at re +- j im (modal form); kBlock and
  // kLargeBlock: diagonal block [start, start + size) of the block Schur T.
  struct Term {
    TermKind kind;
    double re, im;
    int start, size;
  };
  void EvaluateInto(double f_hz, Workspace& w, Eigen::MatrixXcd& h) const;
  // Complex weight of every residue column at omega; throws on a pole.
  void ComputeWeights(double omega, Workspace& w) const;
  // g += L_c (j omega I - T_c)^-1 R_c for a large block, by substitution.
  void AddLargeBlock(const Term& term, double omega, Workspace& w,
                     std::complex<double>* g) const;
  [[noreturn]] void ThrowOnPole(double f_hz, std::complex<double> pole) const;
  // Two eigenvalues within kClusterGap of each other (relative).
  static bool HasClusteredPoles(const Eigen::VectorXcd& lambda);
  // The nonzero poles' magnitudes span more than kVerifySpan.
  static bool SpansDecades(const Eigen::VectorXcd& lambda);
  // This form and `other` agree to kAgreement at 0.5, 1 and 2 times |lambda|
  // (at most kMaxChecks frequencies) and beyond the poles' range, relative
  // to the larger of |H| there and 1e-8 of the largest |H| seen.
  bool AgreesNear(const FrequencyResponse& other, const Eigen::VectorXcd& lambda) const;
  // H by a Hessenberg solve at omega (Method::kHessenberg).
  void SolveHessenberg(double omega, Workspace& w, Eigen::MatrixXcd& h) const;
  static constexpr double kClusterGap = 1e-3;
  static constexpr double kAgreement = 1e-8;
  static constexpr double kVerifyCondition = 1e2;
  static constexpr double kVerifySpan = 1e3;
  static constexpr int kMaxChecks = 24;

  int n_ = 0, m_ = 0, p_ = 0;
  Method method_ = Method::kModal;
  double eigenvector_condition_ = 1.0;
  double pole_tolerance_ = 0.0;  // |j omega - lambda| below this counts as on a pole
  int largest_block_ = 1;
  Eigen::VectorXcd poles_;

  // Everything is computed as G = H, or as G = H^T when the block Schur form
  // has fewer inputs than outputs (then its substitutions run on the inputs);
  // G is rows_ x cols_, and d_ is D in the layout of G.
  bool transposed_ = false;
  int rows_ = 0, cols_ = 0;
  Eigen::MatrixXd d_;

  // G = D + sum over columns c of residues_ of (weight_c) * residues_.col(c),
  // a column holding a real (rows_*cols_) matrix in column-major order, plus
  // the large blocks.
  std::vector<Term> terms_;
  Eigen::MatrixXd residues_;
  int columns_ = 0;

  // Block Schur form, real and imaginary parts apart for the inner loops:
  // T (n x n, block diagonal with upper triangular blocks), and for large
  // blocks L = C S (rows_ x n) and R = S^-1 B (n x cols_).
  Eigen::MatrixXd tr_, ti_, lr_, li_, rr_, ri_;

  // Hessenberg form: A = Q H Q^T; C Q and Q^T B.
  Eigen::MatrixXd hess_, cq_, qb_;
};

}  // namespace deb
