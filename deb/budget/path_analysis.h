// The analysis of one path for one evaluation, built once and shared by
// everything that needs it: the grid builder (resonances, data frequencies),
// propagation (H at every grid frequency, for the output rows the budget
// reads only), the stability check, the exact variance and the report's path
// plots. A path holds one of three models, and each is reduced its own way:
//   - rational (state space): A is reduced once (frequency_response.h), which
//     also gives the poles;
//   - modal: evaluated in modal form (modal_response.h), poles and the exact
//     covariance in closed form, nothing of size 2n x 2n is formed;
//   - measured (a block diagram with frequency data): evaluated per frequency
//     (frequency_model.h); the poles are those of its rational blocks;
//   - with delays, sampled blocks or modal parts (and no data): evaluated
//     per frequency as a diagram (delays exactly, modal parts in modal
//     form); poles, stability and the exact variance are those of its
//     realisation (Path::SystemApproximates), the rational approximation of
//     its delays and sampled blocks;
//   - a loop around modal parts of more than limits::kMaxDenseStates states
//     (Path::KeptAsParts) is never realised densely: its poles, stability
//     and exact variance come from its parts kept as blocks and a low-rank
//     coupling (coupled_spectrum.h), which must hold, or the analysis
//     refuses the path.
#pragma once

#include <Eigen/Dense>
#include <complex>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "deb/budget/path.h"
#include "deb/core/frequency_grid.h"
#include "deb/systems/frequency_model.h"
#include "deb/systems/state_space.h"
#include "deb/systems/modes.h"

namespace deb {

struct CoupledSpectrum;    // deb/systems/coupled_spectrum.h (internal)
struct CoupledCovariance;  // deb/systems/coupled_spectrum.h (internal)

class FrequencyResponse;
class ModalResponse;

class PathAnalysis {
 public:
  // `rows`: the path's output rows to evaluate (each budget output reads one;
  // repeats are kept once). Reduces the model.
  // @throws InputError for a path kept as parts whose coupled form does not
  //   hold (the reason: a part too large, a delay, no convergence).
  PathAnalysis(const Path& path, const std::vector<int>& rows);
  ~PathAnalysis();
  PathAnalysis(const PathAnalysis&) = delete;
  PathAnalysis& operator=(const PathAnalysis&) = delete;

  const Path& path() const { return path_; }
  // Position of path row `row` in the evaluated H, or -1 if it is not evaluated.
  int Position(int row) const;
  int evaluated_rows() const { return static_cast<int>(rows_.size()); }

  // Every pole of the path as a mode (modes.h), sorted by natural frequency;
  // for a measured diagram, those of its rational blocks.
  const std::vector<Mode>& modes() const { return modes_; }
  // Natural frequency and damping of every pole with Im >= 0 (for the grid).
  std::vector<Resonance> Resonances() const;
  // Poles with Re > 1e-9 max(1, |p|) and on the imaginary axis (|Re| within it).
  const std::vector<std::complex<double>>& unstable_poles() const { return unstable_; }
  const std::vector<std::complex<double>>& marginal_poles() const { return marginal_; }
  // How H of a state-space path is evaluated and why (FrequencyResponse::
  // Describe), or of a diagram with modal parts (from its parts); "" for
  // modal paths, other diagrams and block diagrams with measured data.
  std::string ResponseForm() const;
  // The poles of a state-space path as its response found them, or of a
  // diagram's realisation (empty for modal paths and block diagrams with
  // measured data).
  Eigen::VectorXcd StateSpacePoles() const;
  // A loop closed around measured data: its stability is not known.
  bool loop_around_data() const { return path_.measured && path_.measured->HasLoopAroundData(); }

  // fn(k, H_rows(j 2 pi f_hz[k])), H_rows the evaluated rows in order; fn is
  // called concurrently (threads <= 0: the default count) with distinct k.
  // @throws InputError where H is not finite (a pole on the grid) or measured
  //   data do not reach (Extrapolation::kError), naming the path.
  void ForEachResponse(const std::vector<double>& f_hz, const FrequencyModel::Visitor& fn, int threads = 0) const;

  // The exact variance of path row `row` (evaluated) under white input noise
  // of two-sided intensity `w_two_sided`, with the output's weighting if
  // given (in series after the row); for a modal path without weighting also
  // the split over the modes (ModalOutputCovariance). Without weighting all
  // evaluated rows are solved together and kept for the next call with the
  // same W (the contributor's other outputs); not thread-safe.
  // @throws InputError with the reason where none exists (measured data,
  //   unstable or marginal poles, feedthrough of white noise, unreliable).
  struct ExactVariance {
    double variance = 0.0;
    Eigen::VectorXd mode_share;  // one per mode of a modal path, else empty
  };
  ExactVariance Exact(int row, const Eigen::MatrixXd& w_two_sided, const StateSpace* weighting) const;

  // The exact covariance C P C^T of path rows `rows`, row i through
  // weightings[i] (null: none), under white input noise of two-sided
  // intensity `w_two_sided`: one Lyapunov solve of the rows and their
  // weightings stacked. A modal path without weightings takes the modal
  // closed form (ModalOutputCovarianceMatrix), with weightings its
  // state-space form.
  // @throws InputError as Exact (measured data, a weighted modal path too
  //   large to solve densely, a diagram kept as parts whose coupled form
  //   does not hold with the weightings, poles, feedthrough, an unreliable
  //   solution).
  Eigen::MatrixXd ExactCovariance(const std::vector<int>& rows, const std::vector<const StateSpace*>& weightings,
                                  const Eigen::MatrixXd& w_two_sided) const;

  // True for a modal path evaluated in modal form (ModeParts applies).
  bool modal() const { return modal_ != nullptr; }

  // For a modal path and any input spectrum: the split over the modes of the
  // integrals sum_i q[i] weight[c][i] Re(h_r S h_r^H)(f_hz[i]), one per
  // column c with r = the evaluated row positions[c]:
  //   parts(k, c) = sum_i q[i] weight[c][i] Re(phi_out(r,k) g_k phi_in,k^T S h_r^H)(f_hz[i]).
  // The parts of a column add up to its integral less the static residual's
  // part (ModalResponse::AddModeParts). csd(f, scratch) is the inputs'
  // cross-spectral density at f (it may return scratch, filled). The sums
  // run over fixed blocks of frequencies: the result does not depend on the
  // thread count. Costs about one more evaluation of H.
  // @throws InputError as ForEachResponse does.
  using CsdAt = std::function<const Eigen::MatrixXcd&(double f_hz, Eigen::MatrixXcd& scratch)>;
  Eigen::MatrixXd ModeParts(const std::vector<double>& f_hz, const std::vector<double>& q,
                            const std::vector<int>& positions, const std::vector<std::vector<double>>& weight,
                            const CsdAt& csd, int threads = 0) const;

 private:
  const Path path_;  // a copy: results may outlive the budget
  std::vector<int> rows_;
  std::vector<Mode> modes_;
  std::vector<std::complex<double>> unstable_, marginal_;
  // The evaluated rows' realisation without the axis poles their transfer
  // cancels (axis_cancellation.h), if any: modes() and the exact variance
  // are then its, and those poles are not marginal.
  std::optional<StateSpace> reduced_;
  // The evaluated rows' realisation for the exact variance: reduced_ or the path's.
  StateSpace Realisation() const;
  std::unique_ptr<FrequencyResponse> rational_;
  std::unique_ptr<ModalResponse> modal_;
  std::optional<FrequencyModel> measured_;
  Eigen::VectorXcd realisation_poles_;  // of a diagram's realisation (Path::SystemApproximates)
  // A large diagram with modal parts solved as blocks and a low-rank coupling
  // (coupled_spectrum.h), or why not.
  std::shared_ptr<const CoupledSpectrum> coupled_;
  std::string coupled_why_;
  // The coupled form's covariance of `rows` where it holds (D W D^T = 0,
  // every estimate within kCoupledVarianceTolerance), else nullopt and, if
  // `why`, the reason.
  std::optional<Eigen::MatrixXd> CoupledCovarianceOf(const std::vector<int>& rows, const Eigen::MatrixXd& w_two_sided,
                                                     std::string* why = nullptr) const;
  // The coupled form's covariance of `rows` with, per row, why its variance
  // does not hold ("" where it does); nullopt where none is computed (then
  // every row has the reason).
  std::optional<CoupledCovariance> CoupledCovarianceRows(const std::vector<int>& rows,
                                                         const Eigen::MatrixXd& w_two_sided,
                                                         std::vector<std::string>* why) const;
  // The covariance of `rows` through their weightings for a path kept as
  // parts, or a modal path of more than limits::kMaxDenseStates states: the
  // weightings joined in series to its coupled form (the modes as 2 x 2
  // blocks, for a modal path) and solved again (coupled_spectrum.h).
  // @throws InputError (RefuseKeptVariance) where that does not hold.
  Eigen::MatrixXd WeightedCoupledCovariance(const std::vector<int>& rows,
                                            const std::vector<const StateSpace*>& weightings,
                                            const Eigen::MatrixXd& w_two_sided) const;
  // Why a path kept as parts gives no variance, with the reason `why`; and
  // the InputError that says so.
  std::string KeptVarianceRefusal(const std::string& why) const;
  [[noreturn]] void RefuseKeptVariance(const std::string& why) const;
  // All evaluated rows under the last W asked for (no weighting).
  struct Cached {
    Eigen::MatrixXd w;
    std::vector<std::optional<ExactVariance>> rows;
    std::vector<std::string> errors;
  };
  mutable std::optional<Cached> cache_;
  // Fills c's rows from the coupled form's covariance under W where every
  // row holds, or for a path kept as parts (rows that do not hold get their
  // reason); false: the dense realisation solves them instead.
  bool CoupledRowsInto(Cached& c, const Eigen::MatrixXd& w_two_sided) const;
  const Cached& AllRows(const Eigen::MatrixXd& w_two_sided) const;
};

}  // namespace deb
