// Fast evaluation of H(j 2 pi f) = C (j 2 pi f I - A)^-1 B + D at many
// frequencies. A budget evaluates every path at 10^4..10^5 frequencies, so the
// O(n^3) work on A is done once, in the constructor, and each frequency costs
// O(n p m):
//
//  - block-diagonal form (default): A = S D S^-1 with S = U Y, U the real
//    Schur vectors and Y a unit upper triangular decoupling of well-separated
//    blocks (real_block_diagonal.h). A real pole contributes R / (s - re); a
//    pole pair keeps its standardised real 2x2 block [a b; c a] of T, so
//      L (sI - T_2)^-1 R = (s P - Q) / ((s - a)^2 - b c),
//      P = l1 r1 + l2 r2,  Q = a P - b l1 r2 - c l2 r1,
//    with L = C S, R = S^-1 B: the same real second-order term as a modal
//    pair, two real multiply-adds per pair and entry of H, but no eigenvector
//    of the pair is ever formed (a lightly damped pair in physical
//    coordinates has two nearly parallel ones). A cluster of poles that
//    cannot be decoupled (a double pole, a Jordan chain, close modes) is one
//    group, brought to complex Schur form on its own; a group of a few states
//    contributes sum_{a<=b} [(sI - T_c)^-1]_ab L_a R_b, a larger one is solved
//    by triangular substitution on the cheaper side, min(outputs, inputs)
//    right-hand sides. Rounding in this form is that of the Schur form (a
//    backward-stable reduction) amplified by at most about cond(Y); above
//    kMaxBlockCondition the Hessenberg solve is used instead.
//  - modal form (Method::kModal, for comparisons): A = V diag(lambda) V^-1,
//      H(s) = D + sum_k R_k / (s - lambda_k),  R_k = (C V)_k (V^-1 B)_k,
//    pairs merged as above with P = 2 Re R, Q = 2 Re(R conj lambda). Its
//    rounding is amplified by cond(V), which can be large for poles that are
//    far apart (see above).
//  - Hessenberg form (the fallback): A = Q H Q^T, and j omega I - H solved at
//    every frequency (O(n^2 m) each, backward stable whatever the poles).
//
// Before any reduction the state is balanced (StateSpace::Balanced), which
// changes nothing in H but makes models in mixed units better conditioned.
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
#include <string>
#include <vector>

#include "deb/systems/state_space.h"

namespace deb {

class FrequencyResponse {
 public:
  enum class Method { kAuto, kModal, kSchur, kHessenberg };

  // Largest estimated 1-norm condition number of the decoupling Y for which
  // Method::kAuto keeps the block-diagonal form: rounding errors grow by at
  // most about this factor over those of a backward-stable solve.
  static constexpr double kMaxBlockCondition = 1e6;

  // Reduces A once. kAuto and kSchur use the block-diagonal form; kAuto
  // falls back to the Hessenberg form where cond(Y) > kMaxBlockCondition.
  // kModal forces the modal form (for benchmarks and tests); kHessenberg the
  // Hessenberg form, solved at every frequency (O(n^2 m) each).
  // @throws InputError if kModal is forced on a numerically defective A
  //         (cond(V) > 1e-3 / eps), or if A is too badly scaled (balanced
  //         norm above limits::kMaxStateMatrixNorm, or an eigenvalue
  //         iteration that does not converge).
  explicit FrequencyResponse(const StateSpace& sys, Method method = Method::kAuto);

  int states() const { return n_; }
  int inputs() const { return m_; }
  int outputs() const { return p_; }
  // The reduction in use: kSchur (block-diagonal), kModal or kHessenberg.
  Method method() const { return method_; }
  // The 1-norm condition number of the transformation of the form that was
  // computed: cond(Y) for the block-diagonal form (also when the Hessenberg
  // form replaced it), cond(V) of the unit-column eigenvectors for the modal
  // form (huge or infinite if A is defective); 1 for the Hessenberg form asked
  // for directly.
  double condition() const { return condition_; }
  // Which form evaluates H and why, for `deb check`: "the block-diagonal
  // form (996 groups, the largest of 4 states; cond(Y) 1)", "the modal form
  // (eigenvector condition 14)", "the Hessenberg solve at every frequency
  // (...the reason...)", or "a static gain".
  std::string Describe() const;
  // Size of the largest cluster (a group of poles brought to complex Schur
  // form together): 1 if every real pole and pole pair stands alone, 2 for a
  // double pole, n if no pole could be decoupled.
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
  // reference is valid only during the call. The residue sums of a block of
  // frequencies are one matrix product, so H equals At() to rounding (not to
  // the bit), and is independent of the thread count.
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
  // Complex weight of every residue column at omega into wr, wi (columns_
  // entries each); throws on a pole.
  void ComputeWeights(double omega, double* wr, double* wi) const;
  // g += L_c (j omega I - T_c)^-1 R_c for a large block, by substitution.
  void AddLargeBlock(const Term& term, double omega, Workspace& w,
                     std::complex<double>* g) const;
  [[noreturn]] void ThrowOnPole(double f_hz, std::complex<double> pole) const;
  // The modal form if cond(V) <= max_condition; else false (or, if
  // required, InputError).
  // `reducible`: A has several blocks (block_triangular.h), whose poles are
  // then found block by block.
  bool BuildModal(const StateSpace& balanced, bool reducible, double max_condition, bool required);
  void BuildBlockDiagonal(const StateSpace& balanced, bool reducible);
  void StoreResidues(const std::vector<Eigen::VectorXd>& columns);
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

  static constexpr double kMaxModalCondition = 1e6;
  static constexpr double kClusterGap = 1e-3;
  static constexpr double kAgreement = 1e-8;
  static constexpr double kVerifyCondition = 1e2;
  static constexpr double kVerifySpan = 1e3;
  static constexpr int kMaxChecks = 24;

  int n_ = 0, m_ = 0, p_ = 0;
  Method method_ = Method::kModal;
  double condition_ = 1.0;
  std::string hessenberg_reason_ = "asked for";  // why kHessenberg was chosen
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
