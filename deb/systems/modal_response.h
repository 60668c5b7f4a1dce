// Internal: not part of the public API.
// A modal model (modal_model.h) evaluated in modal form, with no state-space
// realisation and no eigendecomposition: per mode k the scalar
//   g_k(j w) = (j w)^n / (w_k^2 - w^2 + 2 j zeta_k w_k w),   n = 0, 1, 2
// (displacement, velocity, acceleration), and
//   H(j w) = Phi_out diag(g(j w)) Phi_in^T  (+ the static residual, if any),
// which costs p n m complex-by-real multiply-adds per frequency for p output
// rows, n modes and m inputs. Frequencies are taken in blocks so that the
// product is one matrix product per block. The pair form: every entry
// h_rj = sum_k phi_out(r,k) phi_in(j,k) g_k, so with the products of the
// shapes formed once as a (p m) x n matrix P, a block's H is P [Re g, Im g]
// over its frequencies: a product whose small factor (the gains, n x 2 per
// frequency) is formed per block while the large one is fixed, which runs
// near the processor's peak (the row form below formed and packed n p values
// per frequency, for m multiply-adds each: memory-bound, 3x slower at 1000
// modes x 20 x 20). Models whose P would exceed 2^24 entries use the row
// form: H^T = Phi_in X^T with X^T holding one column phi_out(r,:) .* g per
// output row and frequency.
// w_k^2 - w^2 is formed as (w_k - w)(w_k + w), so a lightly damped peak keeps
// full relative accuracy.
//
// The exact covariance under white input noise is closed-form in modal
// coordinates (no Lyapunov equation): with the partial fractions
//   g_k(s) = sum over a in {lambda_k, conj lambda_k} of r_a / (s - a),
//   lambda_k = -zeta_k w_k + j w_k sqrt(1 - zeta_k^2),
// and  integral of (j w - a)^-1 conj((j w - b)^-1) dw / 2 pi = -1 / (a + conj b),
//   E[q_k q_l] / (phi_in,k^T W phi_in,l) = sum_a sum_b r_a conj(r_b) (-1 / (a + conj b)),
// so the variance of output row r is sum_kl phi_out(r,k) phi_out(r,l) M_kl,
// O(n^2) per row after M (the modal covariance) is formed once.
#pragma once

#include <Eigen/Dense>
#include <cstddef>
#include <functional>
#include <vector>

#include "deb/systems/modal_model.h"

namespace deb {

class ModalResponse {
 public:
  // kAuto: the pair form where its (rows x inputs) x modes shape products
  // fit 2^24 entries, else the row form; kRows: the row form always (for
  // tests and benchmarks).
  enum class Form { kAuto, kRows };
  // The output rows `rows` of the model (indices into phi_out; may repeat).
  // Calls model.Validate().
  ModalResponse(const ModalModel& model, const std::vector<int>& rows, Form form = Form::kAuto);

  int modes() const { return static_cast<int>(w_.size()); }
  int inputs() const { return static_cast<int>(phi_in_.rows()); }
  int outputs() const { return static_cast<int>(phi_out_t_.cols()); }

  // H(j 2 pi f), outputs x inputs.
  // @throws InputError if f_hz is not finite or j 2 pi f is (numerically) a
  //   pole: f = 0 with a rigid-body mode.
  Eigen::MatrixXcd At(double f_hz) const;

  // fn(k, H(j 2 pi f_hz[k])) for every k, on worker threads (threads <= 0:
  // the default count); fn is called concurrently with distinct k, and the
  // matrix is valid only during the call. Equal to At() to rounding, and
  // independent of the thread count.
  using Visitor = std::function<void(std::size_t k, const Eigen::MatrixXcd& h)>;
  void ForEach(const std::vector<double>& f_hz, const Visitor& fn, int threads = 0) const;

  // The split over the modes of an output PSD Re(h_r S h_r^H) at f_hz, h_r
  // row r of H: mode k carries Re(phi_out(r,k) g_k phi_in,k^T S h_r^H),
  // and the parts of all modes add up to the PSD less the static
  // residual's part Re(d_r S h_r^H). For each column j of t, holding
  // t_j = S h_r^H for row r = columns[j] (an index into this response's
  // rows), adds weight[j] times the parts to column j of parts (modes x
  // columns). Costs about n m + n per column.
  // @throws InputError as At() does.
  void AddModeParts(double f_hz, const std::vector<int>& columns, const Eigen::MatrixXcd& t,
                    const std::vector<double>& weight, Eigen::MatrixXd& parts) const;

 private:
  // g_k(j 2 pi f_hz) of every mode into gr, gi (modes() entries each).
  // @throws InputError if f_hz is not finite or j 2 pi f is (numerically) a pole.
  void Gains(double f_hz, double* gr, double* gi) const;
  // hr, hi: H^T of the block, inputs x (count * rows), column i * rows + r.
  void EvaluateBlock(const double* f_hz, int count, Eigen::MatrixXd& xr, Eigen::MatrixXd& xi,
                     Eigen::MatrixXd& hr, Eigen::MatrixXd& hi) const;
  // The pair form: g the gains (modes x 2 count, Re and Im of frequency i in
  // columns 2i, 2i+1) and h = P g (+ the residual in the real columns).
  bool PairForm() const { return pair_shapes_.size() > 0; }
  void EvaluatePairs(const double* f_hz, int count, Eigen::MatrixXd& g, Eigen::MatrixXd& h) const;
  // H of the block's frequency i from h into out (outputs x inputs).
  void PairColumnsTo(const Eigen::MatrixXd& h, int i, Eigen::MatrixXcd& out) const;

  int derivative_ = 0;
  std::vector<double> w_, two_zeta_w_;  // per mode [rad/s]
  Eigen::MatrixXd phi_out_t_;           // modes x rows (Phi_out^T of the rows)
  Eigen::MatrixXd phi_in_;              // inputs x modes
  Eigen::MatrixXd residual_t_;          // inputs x rows: the static residual's rows, transposed (or empty)
  Eigen::MatrixXd pair_shapes_;         // (rows x inputs) x modes, row r + rows j: phi_out(r,.) .* phi_in(j,.); empty: row form
  Eigen::VectorXd pair_residual_;       // the residual's entries in the same order (or empty)
};

// The exact variance of each output row of `model` under white input noise
// of two-sided intensity `w_two_sided` (inputs x inputs, symmetric), with the
// split of each variance over the modes: share(r, k) = phi_out(r,k) sum_l
// phi_out(r,l) M_kl, the symmetric split of the modal covariance (row sums of
// the output's covariance terms), so that the shares of a row add up to its
// variance exactly; a share is negative where a mode cancels part of others.
struct ModalCovariance {
  Eigen::VectorXd variance;  // one per row
  Eigen::MatrixXd share;     // rows x modes
};

// @throws InputError if W has the wrong size, is not symmetric or has a
//   negative diagonal; if the model has a rigid-body mode (poles at the
//   origin); if a static residual passes the noise (infinite variance); for an acceleration output that the feedthrough Phi_out
//   Phi_in^T exposes to the noise (infinite variance); or "exact variance is
//   not reliable" when a variance is negative or not finite, or its rounding
//   bound (8 n eps times the sum of the absolute terms) exceeds 1e-6 of it.
ModalCovariance ModalOutputCovariance(const ModalModel& model, const std::vector<int>& rows,
                                      const Eigen::MatrixXd& w_two_sided);

// The covariance matrix of the output rows under the same noise (rows x
// rows), from the same modal covariance M: E[y_r y_s] = sum_kl phi_out(r,k)
// phi_out(s,l) M_kl, O(n^2 p) like the variances, no 2n-state Lyapunov
// equation. Its diagonal is ModalOutputCovariance's variances to the bit.
// @throws InputError as ModalOutputCovariance (each row's variance is checked).
Eigen::MatrixXd ModalOutputCovarianceMatrix(const ModalModel& model, const std::vector<int>& rows,
                                            const Eigen::MatrixXd& w_two_sided);

}  // namespace deb
