// A path: a linear MIMO transfer from a source's channels to named signals,
// with a unit per input and per output so that deb can check and convert
// units at every connection (a path from floor velocity in um/s to body
// velocity in um/s is a transmissibility; to a position in nm it is not).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "deb/systems/frequency_model.h"
#include "deb/systems/modal_model.h"
#include "deb/systems/state_space.h"

namespace deb {

// A feedback loop closed inside a path (a `feedback` composition): the
// plant G and the controller K, scaled into each other's units, closed as
// H = (I - sign G K)^-1 G. Kept so that the loop itself can be analysed
// (loop gain, margins: deb/systems/loop_margins.h), which the closed
// path's H no longer shows.
// The stability margins a loop must keep (`margins:` on a feedback path):
// a gain margin in dB, a phase margin in degrees (one-channel loops), a
// modulus margin min |1 + L| (min sigma_min(I + L) for several channels).
struct MarginRequirement {
  std::optional<double> gain_db, phase_deg, modulus;
  bool empty() const { return !gain_db && !phase_deg && !modulus; }
};

struct FeedbackLoop {
  std::string plant, controller;  // the names of the paths it closes
  int sign = -1;
  std::shared_ptr<const FrequencyModel> plant_model, controller_model;
  MarginRequirement required;

  int channels() const { return plant_model->outputs(); }
  // The loop gain broken at the plant's outputs, L = -sign G K (j 2 pi f_hz):
  // channels() x channels().
  // @throws InputError as FrequencyModel::At.
  Eigen::MatrixXcd LoopGainAt(double f_hz) const;
  // LoopGainAt at every f_hz, the plant in blocks of frequencies where its
  // model allows (FrequencyModel::ForEach), on worker threads.
  // @throws InputError as FrequencyModel::At.
  std::vector<Eigen::MatrixXcd> LoopGains(const std::vector<double>& f_hz) const;

 private:
  // -sign G K at f_hz from the plant's G there.
  Eigen::MatrixXcd LoopGainOf(const Eigen::MatrixXcd& g, double f_hz) const;
};

struct Path {
  std::string name;
  std::string description;
  StateSpace system = StateSpace::Gain(Eigen::MatrixXd::Zero(0, 0));
  // Set when the path holds measured frequency data (type: frf) or a block
  // that is not rational in s (delay, discrete), or is a series, parallel or
  // feedback path with such a part or with a modal part: H is evaluated
  // frequency by frequency from it. With measured data `system` is only a
  // zero gain of the path's size, carrying its dimensions (no poles, no
  // Lyapunov variance); otherwise `system` is the path's realisation
  // (SystemApproximates()), which gives the poles, stability and the exact
  // variance, while H on the grid is evaluated from the parts: exactly for
  // delays and sampled blocks (the realisation holds their rational
  // approximations), and at the cost of the modal form for modal parts.
  std::shared_ptr<const FrequencyModel> measured;
  // Set for a path of `type: modal`: it is evaluated in modal form
  // (path_analysis.h), and `system` is again only a zero gain of its size.
  std::shared_ptr<const ModalModel> modal;
  // States of a diagram too large to realise densely: a series, parallel or
  // feedback path with modal parts and more than limits::kMaxDenseStates
  // states (a loop around a large modal plant). `system` is then again only
  // a zero gain of its size; its poles and exact variance come from its
  // parts kept as blocks and a low-rank coupling (path_analysis.h). 0: the
  // path is realised (or needs no realisation).
  int unrealised_states = 0;
  std::vector<std::string> input_names;   // one per input column
  std::vector<std::string> output_names;  // one per output row ("signals")
  std::vector<std::string> input_units;   // one per input column
  std::vector<std::string> output_units;  // one per output row
  // Every feedback loop closed inside the path, innermost first (a series
  // or parallel path keeps those of its parts).
  std::vector<FeedbackLoop> loops;

  // @throws InputError (key path "paths[...]" is the caller's) if the name
  // lists do not match the system's size or names repeat.
  void Validate() const;

  // Row of the output named `signal`, or -1.
  int OutputIndex(const std::string& signal) const;

  bool HasMeasuredData() const { return measured && measured->HasData(); }
  // H is evaluated per frequency from `measured`, and `system` realises it
  // (with rational approximations of its delays and sampled blocks).
  bool SystemApproximates() const { return measured && !measured->HasData() && unrealised_states == 0; }
  // A diagram evaluated from its parts with no dense realisation at all
  // (unrealised_states).
  bool KeptAsParts() const { return unrealised_states > 0; }
  bool IsModal() const { return modal != nullptr; }
  // States of the path's rational transfer: `system`'s, 2 per mode of a
  // modal model, or unrealised_states.
  int States() const;
  // The rational transfer as a state space: `system`, or the realisation of
  // the modal model (2 states per mode; for joining it with other paths).
  // The caller checks !KeptAsParts() first.
  StateSpace Rational() const;
  // The path as a block diagram evaluated per frequency (measured, the
  // modal model, or the rational transfer wrapped); for interconnecting it.
  FrequencyModel Model() const;
};

}  // namespace deb
