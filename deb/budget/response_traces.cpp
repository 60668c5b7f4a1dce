#include "deb/budget/response_traces.h"

#include <algorithm>
#include <cmath>

#include "deb/core/error.h"

namespace deb {
namespace {

const FeedbackLoop* FindLoop(const Budget& budget, const LoopResult& r) {
  for (const Path& p : budget.paths)
    for (const FeedbackLoop& l : p.loops)
      if (l.plant == r.plant && l.controller == r.controller && l.sign == r.sign) return &l;
  return nullptr;
}

std::optional<std::pair<double, double>> PolesWithin(const PathAnalysis& path, const FrequencyGrid& grid) {
  if (path.path().HasMeasuredData() || path.modes().empty()) return std::nullopt;
  double first = HUGE_VAL, last = 0.0;
  for (const Mode& m : path.modes()) {
    if (!(m.f_n_hz >= grid.min_hz() && m.f_n_hz <= grid.max_hz())) continue;  // integrators have f_n = 0
    first = std::min(first, m.f_n_hz);
    last = std::max(last, m.f_n_hz);
  }
  if (!(last > 0.0)) return std::nullopt;
  return std::make_pair(first, last);
}

}  // namespace

ResponseTraces ComputeResponseTraces(const Budget& budget, const BudgetResult& result,
                                     std::vector<std::vector<PathResponse>> recorded) {
  ResponseTraces t;
  const std::size_t n = budget.contributors.size();
  DEB_DEMAND(recorded.size() == n);
  t.paths = std::move(recorded);
  t.poles_hz.resize(n);
  for (std::size_t c = 0; c < n; ++c)
    t.poles_hz[c] = PolesWithin(*result.paths.at(ContributorPathKey(budget.contributors[c])), result.grid);
  for (const LoopResult& r : result.loops) {
    LoopTrace trace;
    const FeedbackLoop* loop = FindLoop(budget, r);
    if (loop && r.evaluated && r.margins.channels == 1) {
      const auto g = loop->plant_model->DefinedRangeHz(), k = loop->controller_model->DefinedRangeHz();
      for (double x : result.grid.f_hz())
        if ((!g || g->Contains(x, x)) && (!k || k->Contains(x, x))) trace.f_hz.push_back(x);
      if (trace.f_hz.size() < 2) trace.f_hz.clear();
      for (double f : trace.f_hz) trace.loop_gain.push_back(loop->LoopGainAt(f)(0, 0));
    }
    t.loops.push_back(std::move(trace));
  }
  return t;
}

}  // namespace deb
