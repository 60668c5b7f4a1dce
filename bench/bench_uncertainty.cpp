// Times `deb uncertainty` without its report: the study of a budget with
// uncertain parameters (default: the thesis case study with tolerances,
// budgets/nizamoglu2015_tolerances.yaml) at N samples on 1 thread and on all,
// and what one sample costs, split into loading its budget (YAML, parameters,
// models) and evaluating it.
// Usage: bench_uncertainty [BUDGET.yaml [SAMPLES]]   (default 2000 samples)
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "deb/budget/engine.h"
#include "deb/core/parallel.h"
#include "deb/load/uncertainty_yaml.h"

namespace {

double Seconds(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
  const std::string file =
      argc > 1 ? argv[1] : std::string(DEB_SOURCE_DIR) + "/budgets/nizamoglu2015_tolerances.yaml";
  const std::size_t samples = argc > 2 ? std::strtoul(argv[2], nullptr, 10) : 2000;
  const deb::UncertaintyBudget budget = deb::LoadUncertaintyFile(file);
  std::vector<double> nominal;
  for (const deb::UncertainParameter& p : budget.spec.parameters) nominal.push_back(p.nominal);

  // One sample's parts, best of 20.
  double load = 1e9, evaluate = 1e9;
  for (int r = 0; r < 20; ++r) {
    auto t0 = std::chrono::steady_clock::now();
    const deb::Budget b = budget.variant(nominal);
    load = std::min(load, Seconds(t0));
    t0 = std::chrono::steady_clock::now();
    deb::Evaluate(b, deb::EngineOptions::VariancesOnly());  // as the study evaluates a sample
    evaluate = std::min(evaluate, Seconds(t0));
  }
  std::printf("%s: %zu uncertain parameters\n", file.c_str(), budget.spec.parameters.size());
  std::printf("one sample: load %.2f ms, evaluate %.2f ms (1 thread)\n", 1e3 * load, 1e3 * evaluate);

  for (int threads : {1, deb::DefaultThreadCount()}) {
    deb::UncertaintyOptions o;
    o.samples = samples;
    o.threads = threads;
    const auto t0 = std::chrono::steady_clock::now();
    const deb::UncertaintyResult r = deb::RunUncertainty(budget.spec, o, budget.variant);
    const double s = Seconds(t0);
    std::printf("%zu samples (%zu budgets), %d thread(s): %.2f s wall, %.2f ms per budget; 1e4 samples: ~%.0f s\n",
                samples, r.evaluations, threads, s, 1e3 * s / static_cast<double>(r.evaluations),
                s * 1e4 / static_cast<double>(samples));
  }
  return 0;
}
