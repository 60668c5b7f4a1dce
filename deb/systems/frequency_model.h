// A linear transfer evaluated frequency by frequency, for paths that hold
// measured data or blocks that are not rational in s (a delay, a sampled
// block: irrational_block.h), or a modal model (modal_model.h). Rational
// models are joined in state space (interconnect.h), where poles and
// Lyapunov variances stay available; a chain or loop with a measured
// frequency response (measured_response.h) cannot be, so it is kept as a
// block diagram and evaluated at each frequency by the same algebra as
// interconnect.h. A chain or loop with a modal part is kept as a diagram
// too, beside its realisation: H of n modes costs O(n m p) per frequency
// from the modal form, against a 2n-state realisation reduced first:
//   series    H = H_second H_first
//   parallel  H = H_a + H_b
//   feedback  H = (I - sign G K)^-1 G   (sign = -1: negative feedback)
// The stability of a loop closed around measured data cannot be read from a
// table of values (it needs a Nyquist argument over all frequencies), so
// HasLoopAroundData() lets callers say that it was not verified.
#pragma once

#include <Eigen/Dense>
#include <cstddef>
#include <functional>
#include <memory>
#include <vector>

#include "deb/core/frequency_interval.h"
#include "deb/systems/irrational_block.h"
#include "deb/systems/measured_response.h"
#include "deb/systems/modal_model.h"
#include "deb/systems/state_space.h"

namespace deb {

struct CoupledRealisation;  // deb/systems/coupled_realisation.h (internal)

class FrequencyModel {
 public:
  explicit FrequencyModel(const StateSpace& rational);
  explicit FrequencyModel(MeasuredResponse measured);
  // A SISO delay or sampled block, evaluated exactly.
  explicit FrequencyModel(IrrationalBlock block);
  // A modal model, evaluated in modal form (modal_response.h).
  // @throws InputError as ModalModel::Validate.
  explicit FrequencyModel(std::shared_ptr<const ModalModel> modal);

  // @throws InputError if the sizes do not fit (as interconnect.h).
  static FrequencyModel Series(const FrequencyModel& first, const FrequencyModel& second);
  static FrequencyModel Parallel(const FrequencyModel& a, const FrequencyModel& b);
  static FrequencyModel Feedback(const FrequencyModel& plant, const FrequencyModel& controller, int sign = -1);

  // The rows `rows` of H (0-based).
  FrequencyModel SelectOutputs(const std::vector<int>& rows) const;

  int inputs() const;
  int outputs() const;
  // The rational blocks of the diagram, whose poles shape H (for the grid),
  // and its modal blocks (whose poles are their modes').
  std::vector<StateSpace> RationalParts() const;
  std::vector<std::shared_ptr<const ModalModel>> ModalParts() const;
  // The frequencies of every measured table in the diagram, sorted, unique.
  std::vector<double> DataFrequencies() const;
  // The frequencies outside which At() throws because a measured table may
  // not be extrapolated (Extrapolation::kError); nullopt: unlimited.
  std::optional<FrequencyInterval> DefinedRangeHz() const;
  // A feedback loop whose plant or controller holds measured data.
  bool HasLoopAroundData() const;
  // Some block holds measured data (else every block is rational or
  // irrational, and the diagram has a rational approximation).
  bool HasData() const;
  // Every delay and sampled block of the diagram, in diagram order.
  std::vector<IrrationalBlock> IrrationalBlocks() const;

  // The diagram as small blocks joined by a low-rank coupling
  // (coupled_realisation.h): the same system as its dense realisation, for
  // the poles and exact variance of a loop around a modal part. nullopt, with
  // the reason in *why, for measured data, a delay or sampled block, or a
  // rational part of more than kMaxCoupledBlock states.
  // @throws InputError as CoupledFeedback (a singular algebraic loop).
  std::optional<CoupledRealisation> Coupled(std::string* why) const;

  // H(j 2 pi f), outputs x inputs.
  // @throws InputError outside a table's range (Extrapolation::kError), on a
  //   pole of a rational block, or where a loop's I - sign G K is singular.
  Eigen::MatrixXcd At(double f_hz) const;

  // fn(k, H(f_hz[k])) for every k, on worker threads (threads <= 0: the
  // default count); fn is called concurrently with distinct k. A modal
  // model alone is evaluated in blocks of frequencies (ModalResponse::
  // ForEach: equal to At() to rounding), a diagram frequency by frequency.
  using Visitor = std::function<void(std::size_t k, const Eigen::MatrixXcd& h)>;
  void ForEach(const std::vector<double>& f_hz, const Visitor& fn, int threads = 0) const;

 private:
  struct Node;
  explicit FrequencyModel(std::shared_ptr<const Node> node) : node_(std::move(node)) {}
  std::shared_ptr<const Node> node_;
};

}  // namespace deb
