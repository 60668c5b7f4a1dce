// A source: a named stationary disturbance with one or more channels, its
// spectrum already in deb's internal convention (one-sided PSD in unit^2/Hz).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "deb/spectra/spectrum.h"

namespace deb {

struct Source {
  std::string name;
  std::string description;
  std::string unit;  // of the signal, e.g. "um/s"; its PSD is in unit^2/Hz
  std::shared_ptr<const Spectrum> spectrum;
  std::vector<std::string> channel_names;  // one per channel
  // What the loader had to assume about the input (e.g. a spectrum file
  // that does not say whether it holds a PSD or an ASD): `deb check` and
  // `deb run` say it as a warning.
  std::vector<std::string> notes;

  int channels() const { return spectrum ? spectrum->channels() : 0; }
};

}  // namespace deb
