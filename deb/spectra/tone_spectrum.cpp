#include "deb/spectra/tone_spectrum.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "deb/core/error.h"
#include "deb/core/limits.h"

namespace deb {

ToneSpectrum::ToneSpectrum(std::vector<SpectralLine> lines, int channels)
    : lines_(std::move(lines)), channels_(channels) {
  DEB_DEMAND(channels >= 1);
  if (lines_.empty()) throw InputError("a tonal source needs at least one tone");
  if (lines_.size() > limits::kMaxTones)
    throw InputError(std::to_string(lines_.size()) + " tones, more than the " + std::to_string(limits::kMaxTones) +
                     " one source may have");
  for (std::size_t i = 0; i < lines_.size(); ++i) {
    const SpectralLine& l = lines_[i];
    std::ostringstream where;
    where << "tone " << i + 1 << " (" << l.f_hz << " Hz): ";
    if (!(std::isfinite(l.f_hz) && l.f_hz > 0.0)) throw InputError(where.str() + "the frequency must be finite and > 0");
    if (l.rms.size() != channels)
      throw InputError(where.str() + "has " + std::to_string(l.rms.size()) + " amplitude(s) for " +
                       std::to_string(channels) + " channel(s)");
    if (!l.rms.allFinite()) throw InputError(where.str() + "an amplitude is not finite");
  }
  std::sort(lines_.begin(), lines_.end(), [](const SpectralLine& a, const SpectralLine& b) { return a.f_hz < b.f_hz; });
  for (std::size_t i = 1; i < lines_.size(); ++i)
    if (lines_[i].f_hz == lines_[i - 1].f_hz) {
      std::ostringstream os;
      os << "two tones at " << lines_[i].f_hz << " Hz: give one, with an amplitude (and phase) per channel";
      throw InputError(os.str());
    }
}

std::vector<double> ToneSpectrum::BreakpointsHz() const {
  std::vector<double> f;
  for (const SpectralLine& l : lines_) f.push_back(l.f_hz);
  return f;
}

std::string ToneSpectrum::Describe() const {
  std::ostringstream os;
  os << lines_.size() << (lines_.size() == 1 ? " tone" : " tones") << " at ";
  for (std::size_t i = 0; i < lines_.size() && i < 4; ++i) os << (i ? ", " : "") << lines_[i].f_hz;
  if (lines_.size() > 4) os << ", ...";
  os << " Hz";
  return os.str();
}

}  // namespace deb
