// Times `deb optimise` on the thesis case study (nizamoglu2015_h210.yaml):
// the skyhook gain Kv in [5, 300] and the isolators' height h in [-300, 400]
// mm chosen to minimise the z velocity's RMS, by each method, against a
// brute-force grid of G x G designs over the same box (its best point, and
// the grid's spacing as the resolution the optimum must agree to).
// Usage: bench_optimise [G]   (default 200)
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "deb/budget/engine.h"
#include "deb/core/parallel.h"
#include "deb/load/optimise_yaml.h"

namespace {

double Seconds(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
  const int g = argc > 1 ? std::atoi(argv[1]) : 200;
  const auto dir = std::filesystem::temp_directory_path() / "deb_bench_optimise";
  std::filesystem::create_directories(dir);
  const std::string file = (dir / "thesis_opt.yaml").string();
  std::ofstream(file) << "extends: '" << DEB_SOURCE_DIR << "/budgets/nizamoglu2015_h210.yaml'\n"
                      << "name: thesis_opt\nparameters:\n  Kv: {value: 50, min: 5, max: 300}\n"
                      << "  h: {value: 210 mm, min: -300 mm, max: 400 mm}\n";
  const deb::OptimiseBudget budget = deb::LoadOptimiseFile(file, {"Kv", "h"});
  deb::OptimiseObjective objective;
  objective.terms = {{"z_velocity", 1.0}};
  for (deb::OptimiseMethod m : {deb::OptimiseMethod::kBobyqa, deb::OptimiseMethod::kCobyla,
                                deb::OptimiseMethod::kSlsqp, deb::OptimiseMethod::kMma}) {
    deb::OptimiseOptions o;
    o.method = m;
    const auto t0 = std::chrono::steady_clock::now();
    const deb::OptimiseResult r = deb::RunOptimise(budget.variables, objective, o, budget.loader);
    const auto& best = r.starts[r.best];
    std::printf("%-7s %4d evaluations %6.2f s: Kv %.4f, h %.2f mm, RMS %.6f um/s (%s)\n",
                deb::ToString(m).c_str(), r.evaluations, Seconds(t0), best.values[0], best.values[1] * 1e3,
                best.objective, best.stop.c_str());
  }
  // The brute-force grid.
  const auto& v = budget.variables;
  std::vector<double> rms(static_cast<std::size_t>(g) * g);
  const auto t0 = std::chrono::steady_clock::now();
  deb::ParallelForEach(rms.size(), [&](std::size_t k) {
    const double kv = v[0].min + (v[0].max - v[0].min) * static_cast<double>(k / g) / (g - 1);
    const double h = v[1].min + (v[1].max - v[1].min) * static_cast<double>(k % g) / (g - 1);
    rms[k] = deb::Evaluate(budget.loader({kv, h}), deb::EngineOptions::VariancesOnly()).outputs[0].rms();
  });
  std::size_t best = 0;
  for (std::size_t k = 1; k < rms.size(); ++k)
    if (rms[k] < rms[best]) best = k;
  std::printf("grid %dx%d (%zu budgets, %.1f s): Kv %.4f, h %.2f mm, RMS %.6f um/s; spacing %.4f, %.3f mm\n", g, g,
              rms.size(), Seconds(t0), v[0].min + (v[0].max - v[0].min) * static_cast<double>(best / g) / (g - 1),
              1e3 * (v[1].min + (v[1].max - v[1].min) * static_cast<double>(best % g) / (g - 1)), rms[best],
              (v[0].max - v[0].min) / (g - 1), 1e3 * (v[1].max - v[1].min) / (g - 1));
  std::filesystem::remove_all(dir);
  return 0;
}
