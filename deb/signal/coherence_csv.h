// Internal: not part of the public API.
// The coherence file of `deb spectrum welch --coherence`: for every pair of
// channels a < b, the magnitude-squared coherence |S_ab|^2 / (S_aa S_bb) and
// the phase of the cross-spectrum, arg S_ab = arg <conj(X_a) X_b> in rad,
// over the estimate's bins:
//
//   # coherence |S_ab|^2/(S_aa S_bb) and CSD phase arg S_ab = ..., rad
//   # <the estimate's provenance, a line each>
//   f_hz, coherence_a_b, phase_a_b, ...
//   0, 0.12, 0.5, ...
//
// Numbers to 10 significant digits. A single channel has no pair: its file
// holds frequencies only.
#pragma once

#include <string>

#include "deb/signal/spectral_estimate.h"

namespace deb {

std::string CoherenceCsvText(const CsdEstimate& csd);

}  // namespace deb
