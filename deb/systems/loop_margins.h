// Stability margins of a feedback loop from its loop gain L(j 2 pi f), the
// figures a control engineer reads off a Bode or Nyquist plot. With the
// loop closed as H = (I - sign G K)^-1 G, the loop gain is L = -sign G K,
// the sensitivity S = (I + L)^-1 and the complementary sensitivity
// T = L (I + L)^-1 = I - S.
//
// For a loop with one channel (L scalar):
//   - gain crossover: |L| = 1; phase margin PM = arg(-L) in degrees, in
//     (-180, 180] (60 means the phase of L is -120 deg there);
//   - phase crossover: L on the negative real axis; gain margin GM = 1/|L|
//     there: the factor on the loop gain that puts L on -1. GM > 1 is an
//     upper margin (more gain destabilises), GM < 1 a lower one (a
//     conditionally stable loop: less gain destabilises);
//   - modulus margin MM = min |1 + L| = 1/max|S|: the distance of the
//     Nyquist curve from -1.
// With several channels the modulus margin generalises to min over f of the
// smallest singular value of I + L (= 1/max ||S||_2); crossovers and the
// classical margins are defined per channel and are not computed.
//
// The margins are found on a frequency grid: a crossing is detected as a
// change of sign between neighbouring grid frequencies and then located by
// bisection in log f on L itself (to 1e-12 relative in f); the modulus
// margin's minimum is refined by golden-section search in log f between the
// neighbours of the grid's smallest value. A crossing pair that falls
// between two neighbouring grid frequencies is not seen: the grid must
// resolve the loop's resonances (deb's automatic grid refines around poles).
#pragma once

#include <Eigen/Dense>
#include <complex>
#include <functional>
#include <optional>
#include <vector>

namespace deb {

struct GainCrossover {
  double f_hz = 0.0;
  double phase_margin_deg = 0.0;  // arg(-L), in (-180, 180]
};

struct PhaseCrossover {
  double f_hz = 0.0;
  double gain_margin = 0.0;  // 1/|L| (a factor, not dB)
};

struct LoopMargins {
  int channels = 1;
  std::vector<GainCrossover> gain_crossovers;    // ascending f (one channel only)
  std::vector<PhaseCrossover> phase_crossovers;  // ascending f (one channel only)
  std::optional<GainCrossover> phase_margin;       // the crossover with the smallest phase margin
  std::optional<PhaseCrossover> upper_gain_margin;  // the smallest gain margin > 1
  std::optional<PhaseCrossover> lower_gain_margin;  // the largest gain margin < 1
  double modulus_margin = 0.0;                      // min |1 + L| (several channels: min sigma_min(I + L))
  double modulus_margin_f_hz = 0.0;
};

// L(j 2 pi f_hz): channels x channels, square. Called concurrently for
// distinct frequencies (ComputeLoopMargins evaluates the grid on all threads).
using LoopGainAt = std::function<Eigen::MatrixXcd(double f_hz)>;

// The margins of the loop over the grid `f_hz` (ascending, > 0, at least 2
// points). DEB_DEMANDs a valid grid and a square, non-empty, finite L.
// `on_grid`, if given, holds L at every f_hz already (evaluated in blocks of
// frequencies by the caller); loop_gain then serves only the refinements
// between grid points.
LoopMargins ComputeLoopMargins(const LoopGainAt& loop_gain, const std::vector<double>& f_hz,
                               std::vector<Eigen::MatrixXcd> on_grid = {});

// 20 log10(x): a gain margin in dB.
double ToDecibel(double factor);

}  // namespace deb
