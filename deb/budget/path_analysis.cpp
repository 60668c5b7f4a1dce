#include "deb/budget/path_analysis.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <optional>
#include <sstream>

#include "deb/core/error.h"
#include "deb/core/limits.h"
#include "deb/core/parallel.h"
#include "deb/systems/axis_cancellation.h"
#include "deb/systems/block_triangular.h"
#include "deb/systems/coupled_spectrum.h"
#include "deb/systems/frequency_response.h"
#include "deb/systems/interconnect.h"
#include "deb/systems/lyapunov.h"
#include "deb/systems/modal_response.h"
#include "deb/systems/real_block_diagonal.h"

namespace deb {
namespace {



std::vector<Mode> ModalModes(const ModalModel& model, Eigen::VectorXcd* poles) {
  std::vector<Mode> modes;
  std::vector<std::complex<double>> all;
  for (int k = 0; k < model.modes(); ++k) {
    Mode m;
    if (model.f_hz[k] > 0.0) {
      const double z = model.zeta[k];
      m.f_n_hz = model.f_hz[k];
      m.damping_ratio = z;
      m.pole_rad_s = ModalPole(model.f_hz[k], z);
      m.pair = true;
      all.push_back(m.pole_rad_s);
      all.push_back(std::conj(m.pole_rad_s));
      modes.push_back(m);
    } else {  // a double integrator: two real poles at the origin
      all.insert(all.end(), 2, 0.0);
      modes.insert(modes.end(), 2, m);
    }
  }
  std::stable_sort(modes.begin(), modes.end(), [](const Mode& a, const Mode& b) {
    return a.f_n_hz < b.f_n_hz || (a.f_n_hz == b.f_n_hz && a.damping_ratio < b.damping_ratio);
  });
  *poles = Eigen::Map<const Eigen::VectorXcd>(all.data(), static_cast<Eigen::Index>(all.size()));
  return modes;
}

// The poles of a realisation; a large irreducible one (a loop around a modal
// plant) from the block-diagonal form of its balanced A, which its exact
// variance reduces too (OutputCovariance): one O(n^3) reduction for both.
Eigen::VectorXcd RealisationPoles(const StateSpace& system) {
  if (system.states() < kSharedFormStates) return system.Poles();
  const StateSpace balanced = system.Balanced();
  if (HasCoupledBlocks(balanced.A())) return system.Poles();
  RequireWellScaled(balanced.A());
  return SharedRealBlockDiagonal(balanced.A())->eigenvalues;
}

// A large diagram with modal parts as blocks and a low-rank coupling
// (coupled_spectrum.h): its poles without reducing the dense realisation.
// nullptr, with the reason, where it is not kept so or not solved so. A
// realised loop with a pole on or right of the imaginary axis is left to
// the dense realisation, whose verdict and messages are the reference; a
// loop kept as parts has no other, and keeps its poles.
std::shared_ptr<const CoupledSpectrum> CoupledLoop(const Path& path, std::string* why) {
  if (!path.KeptAsParts() && (path.system.states() < kSharedFormStates || path.measured->ModalParts().empty()))
    return nullptr;
  try {
    const std::optional<CoupledRealisation> coupled = path.measured->Coupled(why);
    if (!coupled) return nullptr;
    CoupledSolve solved = SolveCoupled(*coupled);
    if (!solved.spectrum) {
      *why = solved.why_not;
      return nullptr;
    }
    if (!path.KeptAsParts() && !(solved.spectrum->poles.real().maxCoeff() < 0.0)) {
      *why = "a pole is not in the left half-plane";
      return nullptr;
    }
    return std::make_shared<const CoupledSpectrum>(std::move(*solved.spectrum));
  } catch (const InputError& e) {
    *why = e.what();
    return nullptr;
  }
}

// "its 2004 states are more than the 2000 deb realises densely"
std::string TooManyToRealise(const Path& path) {
  return "its " + std::to_string(path.States()) + " states are more than the " +
         std::to_string(limits::kMaxDenseStates) + " deb realises densely";
}

// The coupled form's covariance of `rows` with, per row, why its variance
// does not hold ("" where it does); nullopt where none is computed (then
// every row has the reason).
std::optional<CoupledCovariance> CoupledRows(const CoupledSpectrum& sp, const std::vector<int>& rows,
                                             const Eigen::MatrixXd& w_two_sided, std::vector<std::string>* why) {
  why->assign(rows.size(), "");
  const auto all = [&](const std::string& reason) {
    why->assign(rows.size(), reason);
    return std::nullopt;
  };
  // Feedthrough of white noise: the dense solve's message says so.
  for (int r : rows)
    if ((sp.d.row(r) * w_two_sided * sp.d.row(r).transpose())(0, 0) != 0.0)
      return all("white noise passes straight through (D W D^T is not 0): the variance is infinite");
  if (!(sp.poles.real().maxCoeff() < 0.0)) return all("a pole is not in the left half-plane");
  CoupledCovariance cov = CoupledOutputCovariance(sp, rows, w_two_sided);
  if (!cov.covariance.allFinite()) return all("the coupled form's covariance is not finite");
  for (Eigen::Index i = 0; i < cov.relative_error.size(); ++i)
    if (!(cov.relative_error(i) <= kCoupledVarianceTolerance) || !(cov.covariance(i, i) >= 0.0)) {
      std::ostringstream os;
      os << std::setprecision(2) << "the coupled form's variance is uncertain to " << cov.relative_error(i)
         << " relative, more than " << kCoupledVarianceTolerance;
      (*why)[static_cast<std::size_t>(i)] = os.str();
    }
  return cov;
}

// The first row's reason not to hold in `why_rows` (CoupledRows), or null
// where every row holds.
const std::string* FirstRefusal(const std::vector<std::string>& why_rows) {
  const auto it = std::find_if(why_rows.begin(), why_rows.end(), [](const std::string& w) { return !w.empty(); });
  return it == why_rows.end() ? nullptr : &*it;
}

}  // namespace

PathAnalysis::PathAnalysis(const Path& path, const std::vector<int>& rows) : path_(path) {
  for (int r : rows)
    if (std::find(rows_.begin(), rows_.end(), r) == rows_.end()) rows_.push_back(r);
  for (int r : rows_) DEB_DEMAND(r >= 0 && r < path.system.outputs());
  Eigen::VectorXcd poles;
  if (path.modal) {
    modes_ = ModalModes(*path.modal, &poles);
    modal_ = std::make_unique<ModalResponse>(*path.modal, rows_);
  } else if (path.measured) {
    measured_ = path.measured->SelectOutputs(rows_);
    if (path.KeptAsParts()) {
      coupled_ = CoupledLoop(path, &coupled_why_);
      if (!coupled_)
        throw InputError(TooManyToRealise(path) + ", and its parts do not hold as coupled blocks (" + coupled_why_ +
                         "): no poles, stability or exact variance");
      poles = coupled_->poles;
      realisation_poles_ = poles;
    } else if (path.SystemApproximates()) {  // the realisation's poles (Pade's too)
      coupled_ = CoupledLoop(path, &coupled_why_);
      poles = coupled_ ? coupled_->poles : RealisationPoles(path.system);
      realisation_poles_ = poles;
    } else {
      std::vector<std::complex<double>> all;
      for (const StateSpace& part : path.measured->RationalParts()) {
        const Eigen::VectorXcd p = part.Poles();
        all.insert(all.end(), p.data(), p.data() + p.size());
      }
      for (const auto& part : path.measured->ModalParts()) {
        Eigen::VectorXcd p;
        ModalModes(*part, &p);
        all.insert(all.end(), p.data(), p.data() + p.size());
      }
      poles = Eigen::Map<const Eigen::VectorXcd>(all.data(), static_cast<Eigen::Index>(all.size()));
    }
    modes_ = ModesFromPoles(poles);
  } else {
    rational_ = std::make_unique<FrequencyResponse>(path.system.SelectOutputs(rows_));
    poles = rational_->poles();
    modes_ = ModesFromPoles(poles);
  }
  // The stability of a loop around measured data is not known from its parts.
  if (!loop_around_data()) {
    PoleStability s = ClassifyPoles(poles);
    unstable_ = std::move(s.unstable);
    marginal_ = std::move(s.marginal);
  }
  // Axis poles the transfer cancels (an integrator before a loop's zero at DC).
  if (!marginal_.empty() && unstable_.empty() && (rational_ || path.SystemApproximates())) {
    if (std::optional<AxisCancellation> c = CancelAxisPoles(path.system.SelectOutputs(rows_))) {
      marginal_.clear();
      modes_ = ModesFromPoles(c->system.Poles());
      reduced_ = std::move(c->system);
    }
  }
}

StateSpace PathAnalysis::Realisation() const {
  DEB_DEMAND(!path_.KeptAsParts());
  return reduced_ ? *reduced_ : path_.system.SelectOutputs(rows_);
}

PathAnalysis::~PathAnalysis() = default;

int PathAnalysis::Position(int row) const {
  const auto it = std::find(rows_.begin(), rows_.end(), row);
  return it == rows_.end() ? -1 : static_cast<int>(it - rows_.begin());
}

std::vector<Resonance> PathAnalysis::Resonances() const {
  std::vector<Resonance> r;
  for (const Mode& m : modes_)
    if (m.f_n_hz > 0.0) r.push_back({m.f_n_hz, m.damping_ratio});
  return r;
}

std::string PathAnalysis::ResponseForm() const {
  if (rational_) return rational_->Describe();
  // A diagram of delays and sampled blocks says so on its own line (its
  // approximations); one with modal parts says what H costs here.
  if (!path_.SystemApproximates() && !path_.KeptAsParts()) return "";
  int modes = 0;
  for (const auto& part : path_.measured->ModalParts()) modes += part->modes();
  if (modes == 0) return "";
  const std::string head = "its parts at each frequency (the modal form of " + std::to_string(modes) + " mode(s)); ";
  const std::string states = std::to_string(path_.States());
  if (coupled_) {
    std::ostringstream os;
    os << std::setprecision(2) << coupled_->eigenvalue_condition;
    return head + "poles of its " + states + " states from " + std::to_string(coupled_->blocks) +
           " block(s) coupled at rank " + std::to_string(coupled_->rank) +
           (path_.KeptAsParts() ? " (no dense realisation: more than " + std::to_string(limits::kMaxDenseStates) + " states)"
                                : " (no dense reduction)") +
           ", exact variance in closed form on their eigenvectors (eigenvalue condition up to " +
           os.str() + ")";
  }
  return head + "poles and exact variance by its " + states + "-state realisation" +
         (coupled_why_.empty() ? "" : " (not kept as coupled blocks: " + coupled_why_ + ")");
}

Eigen::VectorXcd PathAnalysis::StateSpacePoles() const {
  return rational_ ? rational_->poles() : realisation_poles_;
}

void PathAnalysis::ForEachResponse(const std::vector<double>& f_hz, const FrequencyModel::Visitor& fn,
                                   int threads) const {
  if (modal_) return modal_->ForEach(f_hz, fn, threads);
  if (rational_) return rational_->ForEach(f_hz, fn, threads);
  try {
    measured_->ForEach(f_hz, fn, threads);
  } catch (const InputError& e) {
    throw InputError("path '" + path_.name + "': " + e.what());
  }
}

Eigen::MatrixXd PathAnalysis::ModeParts(const std::vector<double>& f_hz, const std::vector<double>& q,
                                        const std::vector<int>& positions,
                                        const std::vector<std::vector<double>>& weight, const CsdAt& csd,
                                        int threads) const {
  DEB_DEMAND(modal_ && q.size() == f_hz.size() && weight.size() == positions.size());
  for (const std::vector<double>& w : weight) DEB_DEMAND(w.size() == f_hz.size());
  // Frequencies per block: each block sums into its own matrix, and the
  // blocks are added in order.
  constexpr std::size_t kBlock = 1024;
  const std::size_t blocks = (f_hz.size() + kBlock - 1) / kBlock;
  const Eigen::Index n = modal_->modes(), m = modal_->inputs(), columns = static_cast<Eigen::Index>(positions.size());
  std::vector<Eigen::MatrixXd> sums(blocks, Eigen::MatrixXd::Zero(n, columns));
  ParallelFor(
      blocks,
      [&](std::size_t b0, std::size_t b1) {
        Eigen::MatrixXcd scratch, t(m, columns);
        std::vector<double> w(static_cast<std::size_t>(columns));
        for (std::size_t b = b0; b < b1; ++b) {
          const std::size_t lo = b * kBlock, hi = std::min(f_hz.size(), lo + kBlock);
          const std::vector<double> block(f_hz.begin() + static_cast<std::ptrdiff_t>(lo),
                                          f_hz.begin() + static_cast<std::ptrdiff_t>(hi));
          modal_->ForEach(
              block,
              [&](std::size_t i, const Eigen::MatrixXcd& h) {
                const std::size_t k = lo + i;
                const Eigen::MatrixXcd& s = csd(f_hz[k], scratch);
                for (Eigen::Index c = 0; c < columns; ++c) {
                  t.col(c).noalias() = s * h.row(positions[static_cast<std::size_t>(c)]).adjoint();
                  w[static_cast<std::size_t>(c)] = q[k] * weight[static_cast<std::size_t>(c)][k];
                }
                modal_->AddModeParts(f_hz[k], positions, t, w, sums[b]);
              },
              1);
        }
      },
      threads, 1);
  Eigen::MatrixXd parts = Eigen::MatrixXd::Zero(n, columns);
  for (const Eigen::MatrixXd& s : sums) parts += s;
  return parts;
}

const PathAnalysis::Cached& PathAnalysis::AllRows(const Eigen::MatrixXd& w_two_sided) const {
  if (cache_ && cache_->w.rows() == w_two_sided.rows() && cache_->w.cols() == w_two_sided.cols() &&
      cache_->w == w_two_sided)
    return *cache_;
  Cached c;
  c.w = w_two_sided;
  c.rows.resize(rows_.size());
  c.errors.resize(rows_.size());
  const auto one_by_one = [&](auto&& solve) {
    for (std::size_t i = 0; i < rows_.size(); ++i) {
      try {
        c.rows[i] = solve(static_cast<int>(i));
      } catch (const InputError& e) {
        c.errors[i] = e.what();
      }
    }
  };
  if (modal_) {
    try {
      const ModalCovariance all = ModalOutputCovariance(*path_.modal, rows_, w_two_sided);
      for (std::size_t i = 0; i < rows_.size(); ++i)
        c.rows[i] = ExactVariance{all.variance(i), all.share.row(i).transpose()};
    } catch (const InputError&) {
      one_by_one([&](int i) {
        const ModalCovariance one = ModalOutputCovariance(*path_.modal, {rows_[i]}, w_two_sided);
        return ExactVariance{one.variance(0), one.share.row(0).transpose()};
      });
    }
  } else if (coupled_ && CoupledRowsInto(c, w_two_sided)) {
    // Filled from the coupled form (CoupledRowsInto).
  } else if (rational_ || path_.SystemApproximates()) {
    try {
      const StateSpace all = Realisation();
      const Eigen::MatrixXd cov = OutputCovariance(all, w_two_sided);
      for (std::size_t i = 0; i < rows_.size(); ++i) c.rows[i] = ExactVariance{cov(i, i), {}};
    } catch (const InputError&) {
      const StateSpace all = Realisation();
      one_by_one([&](int i) { return ExactVariance{OutputCovariance(all.SelectOutputs({i}), w_two_sided)(0, 0), {}}; });
    }
  } else {
    for (auto& e : c.errors) e = "the path holds measured frequency data (no state-space model for a Lyapunov solution)";
  }
  cache_ = std::move(c);
  return *cache_;
}

PathAnalysis::ExactVariance PathAnalysis::Exact(int row, const Eigen::MatrixXd& w_two_sided,
                                                const StateSpace* weighting) const {
  const int i = Position(row);
  DEB_DEMAND(i >= 0);
  if (!weighting) {
    const Cached& c = AllRows(w_two_sided);
    if (!c.rows[i]) throw InputError(c.errors[i]);
    return *c.rows[i];
  }
  return ExactVariance{ExactCovariance({row}, {weighting}, w_two_sided)(0, 0), {}};
}

Eigen::MatrixXd PathAnalysis::ExactCovariance(const std::vector<int>& rows,
                                              const std::vector<const StateSpace*>& weightings,
                                              const Eigen::MatrixXd& w_two_sided) const {
  DEB_DEMAND(!rows.empty() && rows.size() == weightings.size());
  if (measured_ && !path_.SystemApproximates() && !path_.KeptAsParts()) throw InputError("the path holds measured frequency data (no state-space model for a Lyapunov solution)");
  const bool unweighted =
      std::all_of(weightings.begin(), weightings.end(), [](const StateSpace* w) { return w == nullptr; });
  // Unweighted rows of a modal path: the modal covariance's closed form, as
  // their variances (AllRows), O(n^2 p) instead of a 2n-state Lyapunov solve.
  if (modal_ && unweighted) return ModalOutputCovarianceMatrix(*path_.modal, rows, w_two_sided);
  // Weighted rows of a modal path too large to realise densely: its modes as
  // coupled blocks, the weighting in series (as for a path kept as parts).
  // The largest modal path with the largest weighting fits.
  static_assert(2 * limits::kMaxModes + kMaxCoupledBlock <= limits::kMaxCoupledStates);
  if (modal_ && path_.States() > limits::kMaxDenseStates) return WeightedCoupledCovariance(rows, weightings, w_two_sided);
  std::string why;
  if (unweighted)
    if (std::optional<Eigen::MatrixXd> cov = CoupledCovarianceOf(rows, w_two_sided, &why)) return *cov;
  if (path_.KeptAsParts()) {
    if (unweighted) RefuseKeptVariance(why);
    return WeightedCoupledCovariance(rows, weightings, w_two_sided);
  }
  // The reduced realisation (its rows numbered as the evaluated rows) where
  // it holds every row asked for; else the path's own.
  const bool reduced =
      reduced_ && std::all_of(rows.begin(), rows.end(), [&](int row) { return Position(row) >= 0; });
  const StateSpace rational = reduced ? *reduced_ : path_.Rational();
  std::optional<StateSpace> stacked;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const StateSpace row = rational.SelectOutputs({reduced ? Position(rows[i]) : rows[i]});
    const StateSpace one = weightings[i] ? Series(row, *weightings[i]) : row;
    stacked = stacked ? StackOutputs(*stacked, one) : one;
  }
  return OutputCovariance(*stacked, w_two_sided);
}

bool PathAnalysis::CoupledRowsInto(Cached& c, const Eigen::MatrixXd& w_two_sided) const {
  std::vector<std::string> why_rows;
  const std::optional<CoupledCovariance> cov = CoupledCovarianceRows(rows_, w_two_sided, &why_rows);
  if (!(cov && !FirstRefusal(why_rows)) && !path_.KeptAsParts()) return false;
  for (std::size_t i = 0; i < rows_.size(); ++i) {
    if (cov && why_rows[i].empty())
      c.rows[i] = ExactVariance{cov->covariance(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(i)), {}};
    else
      c.errors[i] = KeptVarianceRefusal(why_rows[i]);
  }
  return true;
}

std::optional<CoupledCovariance> PathAnalysis::CoupledCovarianceRows(const std::vector<int>& rows,
                                                                   const Eigen::MatrixXd& w_two_sided,
                                                                   std::vector<std::string>* why) const {
  if (!coupled_ || reduced_) {
    why->assign(rows.size(), "the path is not kept as coupled blocks");
    return std::nullopt;
  }
  return CoupledRows(*coupled_, rows, w_two_sided, why);
}

std::optional<Eigen::MatrixXd> PathAnalysis::CoupledCovarianceOf(const std::vector<int>& rows,
                                                               const Eigen::MatrixXd& w_two_sided,
                                                               std::string* why) const {
  std::vector<std::string> why_rows;
  std::optional<CoupledCovariance> cov = CoupledCovarianceRows(rows, w_two_sided, &why_rows);
  if (const std::string* reason = FirstRefusal(why_rows)) {
    if (why) *why = *reason;
    return std::nullopt;
  }
  return std::move(cov->covariance);
}

Eigen::MatrixXd PathAnalysis::WeightedCoupledCovariance(const std::vector<int>& rows,
                                                        const std::vector<const StateSpace*>& weightings,
                                                        const Eigen::MatrixXd& w_two_sided) const {
  std::string why;
  const std::optional<CoupledRealisation> loop = path_.modal ? CoupledOf(*path_.modal) : path_.measured->Coupled(&why);
  if (!loop) RefuseKeptVariance(why);
  // The rows, each through its weighting (none: a unit gain), as one block
  // after the loop.
  std::optional<StateSpace> filters;
  for (const StateSpace* w : weightings) {
    const StateSpace f = w ? *w : StateSpace::Gain(Eigen::MatrixXd::Identity(1, 1));
    filters = filters ? Append(*filters, f) : f;
  }
  if (filters->states() > kMaxCoupledBlock)
    RefuseKeptVariance("the output weightings have " + std::to_string(filters->states()) +
                       " states together, more than the " + std::to_string(kMaxCoupledBlock) +
                       " of one coupled block");
  const CoupledSolve solved = SolveCoupled(CoupledSeries(CoupledSelectOutputs(*loop, rows), CoupledOf(*filters)));
  if (!solved.spectrum) RefuseKeptVariance("with its output weighting, " + solved.why_not);
  std::vector<int> all(rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) all[i] = static_cast<int>(i);
  std::vector<std::string> why_rows;
  const std::optional<CoupledCovariance> cov = CoupledRows(*solved.spectrum, all, w_two_sided, &why_rows);
  if (const std::string* reason = FirstRefusal(why_rows)) RefuseKeptVariance("with its output weighting, " + *reason);
  return cov->covariance;
}

std::string PathAnalysis::KeptVarianceRefusal(const std::string& why) const {
  return TooManyToRealise(path_) + " for a Lyapunov solve, and " + why;
}

void PathAnalysis::RefuseKeptVariance(const std::string& why) const { throw InputError(KeptVarianceRefusal(why)); }

}  // namespace deb
