// Welch's method: the one-sided PSD, CSD and coherence of a multi-channel
// recording from averaged, windowed, overlapping segments (P.D. Welch, IEEE
// Trans. Audio Electroacoust. AU-15(2), 1967).
//
// Scaling (derived, not borrowed): segment x_n, n = 0..L-1, detrended and
// windowed by w_n, X_k = sum_n w_n x_n e^{-j 2 pi k n / L}. For white noise of
// variance s^2, E|X_k|^2 = s^2 S2 (S2 = sum w_n^2), and its one-sided density
// is 2 s^2 / fs, so
//     P_k = c_k |X_k|^2 / (fs S2),  c_k = 2 for 0 < k < L/2,
//     c_k = 1 at k = 0 and (L even) k = L/2,
// whose negative-frequency twins do not exist. Summed over the bins times
// fs/L, P returns sum_n (w_n x_n)^2 / S2, the window-weighted mean square
// (Parseval) - the density convention of scipy.signal.welch and of MATLAB's
// pwelch. Cross-spectra use the same scale with
//     S_ij(f_k) = c_k conj(X_i,k) X_j,k / (fs S2),
// the conjugate on the FIRST channel (scipy.signal.csd(x, y) order): if
// channel j lags channel i by tau, the phase of S_ij is -2 pi f tau.
//
// Averaging: mean over the K segments, or median divided by the expected
// median of K unit-mean exponential (chi-square-2) variables. The k-th order
// statistic of K has mean H_K - H_{K-k} (H harmonic numbers), so the median is
// biased by b(K) = H_K' - H_{(K'-1)/2} = sum_{n=1}^{K'} (-1)^(n+1) / n, K' the
// largest odd number <= K (for even K, the average of the two middle values
// has exactly the mean of the odd case K - 1).
// For cross-spectra the real and imaginary parts are medianed separately with
// the same correction, exact only for auto-spectra.
//
// Statistics: each bin is chi-square with nu degrees of freedom, nu = 2K /
// (1 + 2 sum_{m=1}^{K-1} (1 - m/K) rho(m D)^2), rho(s) = sum_n w_n w_{n+s} / S2,
// D = L - overlap (Welch 1967; Percival & Walden 1993, eq. 292b); for median
// averaging nu is multiplied by (ln 2)^2, the median's asymptotic efficiency
// for exponential data.
#pragma once

#include <string>

#include "deb/signal/spectral_estimate.h"
#include "deb/signal/time_series.h"

namespace deb {

struct WelchOptions {
  // The shortest segment: 8 bins above 0 Hz. Shorter segments give a
  // "spectrum" of a few bins that no band analysis or budget can use.
  static constexpr int kMinSegmentLength = 16;

  WindowKind window = WindowKind::kHann;
  // Samples per segment, >= kMinSegmentLength; 0 picks the largest power of
  // two that still gives at least 8 segments with the chosen overlap.
  int segment_length = 0;
  double overlap = 0.5;  // fraction of a segment shared with the next, [0, 1)
  Detrend detrend = Detrend::kMean;
  Averaging averaging = Averaging::kMean;
  double confidence = 0.95;  // level of the chi-square bounds, (0, 1)
  int threads = 0;           // 0: DefaultThreadCount()

  // False, with the field, its value and the rule in *error, if a field is
  // out of range (segment_length neither 0 nor >= kMinSegmentLength,
  // overlap outside [0, 1), confidence outside (0, 1)).
  bool IsValid(std::string* error) const;
};

// Segment length the options give for n samples.
// @throws InputError if the options are invalid or n is too short for one
//   segment ("too few samples").
int SegmentLengthFor(Eigen::Index samples, const WelchOptions& options);

// nu for K segments of window w shifted by `step` samples (see above).
double WelchDegreesOfFreedom(const std::vector<double>& window, int step, int segments, Averaging averaging);

// @throws InputError if the options are invalid or the series is shorter
//   than one segment.
PsdEstimate WelchPsd(const TimeSeries& series, const WelchOptions& options);
CsdEstimate WelchCsd(const TimeSeries& series, const WelchOptions& options);

}  // namespace deb
