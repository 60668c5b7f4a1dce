// Internal: not part of the public API.
// The transfer of one contributor to one output as the engine applies it:
//   h_k(f) = c_out(f) · w(f) · H_row,k(j 2 pi f) · c_in,k(f)
// with c_in,k the conversion from the source's unit to the path's input unit
// k, H_row the path row of the output's signal, w the output's weighting and
// c_out the conversion from the (weighted) signal's unit to the output's unit.
// For a source with uncorrelated channels the contributor's PSD on the output
// is sum_k |h_k|^2 S_kk; with correlated channels cross terms add to that.
// The engine calls the conversion helpers below, so reports that show path
// magnitudes use exactly the factors behind the budget's numbers.
#pragma once

#include <complex>
#include <cstddef>
#include <string>
#include <vector>

#include "deb/budget/budget.h"
#include "deb/budget/path_analysis.h"
#include "deb/budget/result.h"
#include "deb/units/unit.h"

namespace deb {

// Source unit -> path input unit, one per input channel.
// @throws InputError (from ConvertUnit) if a pair does not convert.
std::vector<UnitConversion> InputConversions(const Source& source, const Path& path);

// The two-sided intensity W = F S0 F / 2 that the path's inputs see from a
// white source of one-sided level S0 (Spectrum::WhiteLevel), F = diag of the
// input conversions' scales: the W of the Lyapunov equation (docs/method.md,
// conventions 2-3). DEB_DEMANDs a white source.
Eigen::MatrixXd WhiteInputIntensity(const Source& source, const std::vector<UnitConversion>& in_conv);

// Unit of path row `row` after the output's weighting (the product with the
// weighting's unit), and its conversion to the output's unit.
std::string WeightedSignalUnit(const Path& path, int row, const Output& output);
UnitConversion OutputConversion(const Path& path, int row, const Output& output);

// |w(j 2 pi f)|^2 of the output's weighting times its metric's PSD factor
// (OutputMetric::PsdFactor) at every f; empty without either.
// @throws InputError if f coincides with a pole of the weighting.
std::vector<double> WeightingGain2(const Output& output, const std::vector<double>& f_hz, int threads = 0);

struct PathResponse {
  // The frequencies of the response: f_hz, or `grid` where f_hz is empty.
  const std::vector<double>& Frequencies(const std::vector<double>& grid_hz) const {
    return f_hz.empty() ? grid_hz : f_hz;
  }

  std::string contributor;
  std::string output;
  std::vector<std::string> channels;  // the source's channel names
  std::string unit;                   // "output unit / source unit", for labels
  // The frequencies f_i of gain2 and phase_rad; empty: the result's grid
  // (as the engine computes them; a report keeps fewer, FiguresTraces).
  std::vector<double> f_hz;
  // gain2[k][i] = |h_k(f_i)|^2, output unit^2 per source unit^2.
  std::vector<std::vector<double>> gain2;
  // phase_rad[k][i] = arg h_k(f_i) in (-pi, pi], the weighting's phase
  // included (a moving-average metric only scales the PSD).
  std::vector<std::vector<double>> phase_rad;
};

// Fills a contributor's PathResponses (one per output, budget order) from
// the evaluated rows of its path's H at each frequency, wherever H is
// evaluated: the engine's propagation records them in the same pass
// (Evaluate), ComputePathResponses in a pass of its own.
class PathResponseRecorder {
 public:
  // DEB_DEMANDs a valid contributor of a validated budget whose every
  // output's signal `analysis` evaluates. f_hz is kept by reference: it must
  // outlive the recorder.
  // @throws InputError as the engine does for units and weightings.
  PathResponseRecorder(const Budget& budget, const PathAnalysis& analysis, std::size_t contributor,
                       const std::vector<double>& f_hz, int threads = 0);
  // Frequency i from H_rows(j 2 pi f_hz[i]) (PathAnalysis::ForEachResponse);
  // concurrent calls with distinct i are safe.
  void Record(std::size_t i, const Eigen::MatrixXcd& h_rows);
  // The responses, once every frequency is recorded.
  std::vector<PathResponse> Take() { return std::move(r_); }

 private:
  const std::vector<double>& f_hz_;
  std::vector<UnitConversion> in_conv_, out_conv_;
  std::vector<int> position_;
  std::vector<std::vector<double>> w2_;
  std::vector<std::vector<std::complex<double>>> w_;  // the weighting's response, for the phase
  std::vector<PathResponse> r_;
};

// |h_k(f)|^2 for contributor `contributor` (index into budget.contributors)
// and output `output` (index into budget.outputs) at every f, from the path's
// analysis in `result` (Evaluate of the same budget).
// DEB_DEMANDs valid indices of a validated budget.
// @throws InputError as the engine does for units and poles on the grid.
PathResponse ComputePathResponse(const Budget& budget, const BudgetResult& result, std::size_t contributor,
                                 std::size_t output, const std::vector<double>& f_hz, int threads = 0);
// The same for every output at once, in the order of budget.outputs: one
// evaluation of the path.
std::vector<PathResponse> ComputePathResponses(const Budget& budget, const BudgetResult& result,
                                               std::size_t contributor, const std::vector<double>& f_hz,
                                               int threads = 0);

}  // namespace deb
