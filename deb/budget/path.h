// A path: a linear MIMO transfer from a source's channels to named signals,
// with a unit per input and per output so that deb can check and convert
// units at every connection (a path from floor velocity in um/s to body
// velocity in um/s is a transmissibility; to a position in nm it is not).
#pragma once

#include <string>
#include <vector>

#include "deb/systems/state_space.h"

namespace deb {

struct Path {
  std::string name;
  std::string description;
  StateSpace system = StateSpace::Gain(Eigen::MatrixXd::Zero(0, 0));
  std::vector<std::string> input_names;   // one per input column
  std::vector<std::string> output_names;  // one per output row ("signals")
  std::vector<std::string> input_units;   // one per input column
  std::vector<std::string> output_units;  // one per output row

  // @throws InputError (key path "paths[...]" is the caller's) if the name
  // lists do not match the system's size or names repeat.
  void Validate() const;

  // Row of the output named `signal`, or -1.
  int OutputIndex(const std::string& signal) const;
};

}  // namespace deb
