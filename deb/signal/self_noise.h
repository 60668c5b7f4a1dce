// Instrument self-noise from co-located recordings: sensors side by side see
// the same ground motion u; what they do not share is their own noise. The
// result is a noise PSD per sensor, usable as a budget source (a sensor noise
// spectrum) through ToMeasuredSpectrum.
//
// Model: x_a = H_a u + n_a with the n_a independent of u and of each other.
// Cross-spectra follow welch.h: S_ab = <conj(X_a) X_b>.
//
// Two sensors (Holcomb 1989, USGS OFR 89-214; Nizamoglu 2015, eqs. 4-6..4-9):
// assumes IDENTICAL sensors, H_a = H_b = 1 and equal noise levels. Then
// S_aa = S_u + N, |S_ab| = S_u, and with the coherence gamma^2 = |S_ab|^2 /
// (S_aa S_bb) the noise is
//     N_a = S_aa (1 - sqrt(gamma^2))    (thesis eq. 4-8; N_b likewise),
// i.e. N_a = S_aa - |S_ab| when S_aa = S_bb. A gain mismatch between the two
// sensors leaks into N (a 1 % gain error leaves about 1 % of S_u); the thesis
// notes the method fails below a geophone's natural frequency for this reason.
//
// Three sensors (Sleeman, van Wettum, Trampert 2006, BSSA 96(1), eq. 6): no
// assumption on the responses H_a or on equal noise; only independence:
//     N_aa = S_aa - S_ba S_ac / S_bc      for (a, b, c) each sensor in turn,
// since S_ba S_ac / S_bc = conj(H_b) H_a conj(H_a) H_c / (conj(H_b) H_c) S_u
// = |H_a|^2 S_u. The real part is taken (the imaginary part is estimation
// scatter).
//
// Both subtract nearly equal numbers where the common signal dominates, but
// the terms linear in the signal-noise cross-spectra cancel (expand S_ab =
// S_u + <U* n_b> + <n_a* U> + ...), so the scatter of N stays of relative
// order 1/sqrt(K) (K averages) until the noise is many orders below the
// signal. Estimates below zero (rounding, or noise too small to resolve) are
// set to 0 and counted in clamped_bins.
#pragma once

#include <string>
#include <vector>

#include "deb/signal/spectral_estimate.h"

namespace deb {

struct SelfNoiseEstimate {
  PsdEstimate noise;              // one column per sensor analysed
  std::string method;             // formula and assumptions, one line
  std::vector<int> clamped_bins;  // per sensor: bins where the estimate was < 0
};

// Sensors a, b (channel indices of csd). @throws InputError if an index is
// out of range or a == b.
SelfNoiseEstimate TwoSensorSelfNoise(const CsdEstimate& csd, int a, int b);

// Sensors a, b, c, distinct. @throws InputError as above.
SelfNoiseEstimate ThreeSensorSelfNoise(const CsdEstimate& csd, int a, int b, int c);

}  // namespace deb
