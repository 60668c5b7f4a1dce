#include "deb/budget/response_traces.h"

#include <algorithm>
#include <cmath>

#include "deb/core/parallel.h"

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

ResponseTraces ComputeResponseTraces(const Budget& budget, const BudgetResult& result, int threads,
                                     std::vector<std::vector<PathResponse>> recorded) {
  ResponseTraces t;
  const std::size_t n = budget.contributors.size();
  t.paths.resize(n);
  t.poles_hz.resize(n);
  std::vector<std::size_t> missing;  // contributors whose paths were not recorded
  for (std::size_t c = 0; c < n; ++c) {
    t.poles_hz[c] = PolesWithin(*result.paths.at(ContributorPathKey(budget.contributors[c])), result.grid);
    if (c < recorded.size() && !recorded[c].empty()) t.paths[c] = std::move(recorded[c]);
    else missing.push_back(c);
  }
  // Contributors on the threads, each path evaluated on one; with fewer
  // contributors than threads, each path on all threads instead.
  const int workers = threads > 0 ? threads : DefaultThreadCount();
  const bool across = missing.size() >= static_cast<std::size_t>(workers);
  ParallelForEach(
      missing.size(),
      [&](std::size_t i) {
        t.paths[missing[i]] = ComputePathResponses(budget, result, missing[i], result.grid.f_hz(), across ? 1 : workers);
      },
      across ? workers : 1);
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
