// Data windows for Welch spectral estimation, and the window sums that fix
// the density scaling and the equivalent noise bandwidth.
//
// Windows are the periodic ("DFT-even") forms used for spectral analysis:
// w_n = sum_m (-1)^m a_m cos(2 pi m n / N), n = 0 .. N-1 (a length-N+1
// symmetric window without its last sample), so that the cosine terms are
// exact DFT bins. Coefficients:
//  - rectangular: a = {1}.
//  - hann:  a = {0.5, 0.5}.
//  - hamming: a = {0.54, 0.46}.
//  - blackman_harris: minimum 4-term, a = {0.35875, 0.48829, 0.14128, 0.01168}
//    (F.J. Harris, "On the use of windows for harmonic analysis with the
//    discrete Fourier transform", Proc. IEEE 66(1), 1978).
//  - flattop: 5-term, a = {0.21557895, 0.41663158, 0.277263158, 0.083578947,
//    0.006947368} (G. D'Antona, A. Ferrero, "Digital Signal Processing for
//    Measurement Systems", Springer 2006; the flat-top of common analysis
//    packages): amplitude flat to about 0.01 dB across a bin.
#pragma once

#include <string>
#include <vector>

#include "deb/core/enum_names.h"

namespace deb {

enum class WindowKind { kRectangular, kHann, kHamming, kBlackmanHarris, kFlatTop };

inline constexpr EnumName<WindowKind> kWindowKindNames[] = {
    {WindowKind::kRectangular, "rectangular"}, {WindowKind::kHann, "hann"}, {WindowKind::kHamming, "hamming"},
    {WindowKind::kBlackmanHarris, "blackman_harris"}, {WindowKind::kFlatTop, "flattop"},
    {WindowKind::kRectangular, "boxcar", kAlias}, {WindowKind::kHann, "hanning", kAlias}};
constexpr EnumNames<WindowKind> NamesOf(WindowKind) { return kWindowKindNames; }

// @throws InputError naming the text and listing the allowed values.
inline WindowKind ParseWindowKind(const std::string& text) { return ParseEnum<WindowKind>(text, "window"); }

// The N samples of the window. @throws InputError if size < 1.
std::vector<double> MakeWindow(WindowKind kind, int size);

// Sums of a window that the estimators need.
struct WindowSums {
  double sum = 0.0;          // S1 = sum w_n (coherent gain x N)
  double sum_squares = 0.0;  // S2 = sum w_n^2 (power normalisation)
};
WindowSums SumsOf(const std::vector<double>& window);

// Equivalent noise bandwidth in bins, N S2 / S1^2 (1 for rectangular, 1.5 for
// Hann): the width of the rectangular filter that passes as much white-noise
// power as the window's spectral response. In Hz: bins x fs / N.
double EnbwBins(const std::vector<double>& window);

}  // namespace deb
