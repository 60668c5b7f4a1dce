// A path: a linear MIMO transfer from a source's channels to named signals,
// with a unit per input and per output so that deb can check and convert
// units at every connection (a path from floor velocity in um/s to body
// velocity in um/s is a transmissibility; to a position in nm it is not).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "deb/systems/frequency_model.h"
#include "deb/systems/state_space.h"

namespace deb {

struct Path {
  std::string name;
  std::string description;
  StateSpace system = StateSpace::Gain(Eigen::MatrixXd::Zero(0, 0));
  // Set when the path holds measured frequency data (type: frf, or a series,
  // parallel or feedback path with such a part): H is evaluated frequency by
  // frequency from it, and `system` is only a zero gain of the path's size,
  // carrying its dimensions (no poles, no Lyapunov variance).
  std::shared_ptr<const FrequencyModel> measured;
  std::vector<std::string> input_names;   // one per input column
  std::vector<std::string> output_names;  // one per output row ("signals")
  std::vector<std::string> input_units;   // one per input column
  std::vector<std::string> output_units;  // one per output row

  // @throws InputError (key path "paths[...]" is the caller's) if the name
  // lists do not match the system's size or names repeat.
  void Validate() const;

  // Row of the output named `signal`, or -1.
  int OutputIndex(const std::string& signal) const;

  bool HasMeasuredData() const { return measured != nullptr; }
  // The path as a block diagram evaluated per frequency (measured, or the
  // state space wrapped); for interconnecting it with a measured path.
  FrequencyModel Model() const;

  // fn(k, H_rows(j 2 pi f_hz[k])) for the rows `rows` at every frequency: from
  // the state space reduced once, or from the measured data. fn is called
  // concurrently (threads <= 0: the default count), with distinct k.
  // @throws InputError where H is not finite (a pole on the grid) or measured
  //   data do not reach (Extrapolation::kError).
  void ForEachResponse(const std::vector<int>& rows, const std::vector<double>& f_hz,
                       const FrequencyModel::Visitor& fn, int threads = 0) const;
};

}  // namespace deb
