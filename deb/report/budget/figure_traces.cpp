#include "deb/report/budget/figure_traces.h"

#include <algorithm>
#include <iterator>
#include <memory>

#include "deb/budget/response_traces.h"
#include "deb/core/parallel.h"
#include "deb/report/figure/plot_points.h"

namespace deb::report {
namespace {

PathResponse Reduced(const PathResponse& r, const std::vector<double>& f) {
  if (!r.f_hz.empty() || f.size() < 3 || r.gain2.empty()) return r;
  std::vector<const std::vector<double>*> gains, phases;
  for (const auto& g : r.gain2) gains.push_back(&g);
  for (const auto& p : r.phase_rad) phases.push_back(&p);
  const std::vector<std::size_t> by_gain =
      PlotPoints(f, gains, f.front(), f.back(), PlotScale::kLog, kTraceTolerance / 2);
  const std::vector<std::size_t> by_phase =
      PlotPoints(f, phases, f.front(), f.back(), PlotScale::kLinear, kTraceTolerance / 2);
  std::vector<std::size_t> rows;
  std::set_union(by_gain.begin(), by_gain.end(), by_phase.begin(), by_phase.end(), std::back_inserter(rows));
  PathResponse out = r;
  out.f_hz.clear();
  for (std::size_t i : rows) out.f_hz.push_back(f[i]);
  const auto pick = [&](std::vector<std::vector<double>>& series) {
    for (auto& s : series) {
      std::vector<double> kept;
      kept.reserve(rows.size());
      for (std::size_t i : rows) kept.push_back(s[i]);
      s = std::move(kept);
    }
  };
  pick(out.gain2);
  pick(out.phase_rad);
  return out;
}

}  // namespace

BudgetResult WithFigureTraces(const BudgetResult& result, int threads) {
  BudgetResult out = result;
  if (!result.traces) return out;
  auto traces = std::make_shared<ResponseTraces>(*result.traces);
  const std::vector<double>& f = result.grid.f_hz();
  ParallelForEach(
      traces->paths.size(),
      [&](std::size_t c) {
        for (PathResponse& r : traces->paths[c]) r = Reduced(r, f);
      },
      threads);
  out.traces = std::move(traces);
  return out;
}

}  // namespace deb::report
