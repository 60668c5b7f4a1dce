// Times the whole `deb run` pipeline minus plotting — load and validate the
// YAML budget (building any physical model), evaluate on one thread and on
// all threads, write summary.json and the CSVs — for the shipped budgets;
// and the result store (result.h5) each run writes, and reading it back as
// `deb report` does.
// Usage: bench_budgets [BUDGET.yaml ...]   (default: every budget the issue
// tracks for speed: the thesis case study at h = 210 and 0 mm, and the
// quickstart default).
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "deb/budget/engine.h"
#include "deb/load/budget_yaml.h"
#include "deb/formats/hdf5_file.h"
#include "deb/results/result_store.h"
#include "deb/results/result_writer.h"

namespace {

double Seconds(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> budgets;
  for (int i = 1; i < argc; ++i) budgets.push_back(argv[i]);
  if (budgets.empty()) {
    for (const char* b : {"nizamoglu2015_h210", "nizamoglu2015_h0", "avis_case_study", "single_axis_isolator"})
      budgets.push_back(std::string(DEB_SOURCE_DIR) + "/budgets/" + b + ".yaml");
  }
  const auto out = std::filesystem::temp_directory_path() / "deb_bench_budgets";
  std::printf("%-24s %8s %9s %11s %11s %9s %9s %9s %9s %9s\n", "budget", "points", "load ms", "eval 1t ms",
              "eval all ms", "write ms", "total 1t", "store ms", "read ms", "store MB");
  for (const auto& file : budgets) {
    constexpr int kRepeats = 5;
    double best_load = 1e9, best_eval1 = 1e9, best_evaln = 1e9, best_write = 1e9, best_store = 1e9, best_read = 1e9;
    double store_mb = 0.0;
    std::size_t points = 0;
    std::string name;
    for (int r = 0; r < kRepeats; ++r) {
      auto t0 = std::chrono::steady_clock::now();
      const deb::Budget budget = deb::LoadBudgetFile(file);
      best_load = std::min(best_load, Seconds(t0));
      deb::EngineOptions one;
      one.threads = 1;
      t0 = std::chrono::steady_clock::now();
      const deb::BudgetResult result = deb::Evaluate(budget, one);
      best_eval1 = std::min(best_eval1, Seconds(t0));
      t0 = std::chrono::steady_clock::now();
      deb::Evaluate(budget, {});
      best_evaln = std::min(best_evaln, Seconds(t0));
      t0 = std::chrono::steady_clock::now();
      deb::RunInfo info;
      info.budget_file = file;
      info.seconds = 0.0;
      deb::WriteResultDirectory(result, info, out.string());
      best_write = std::min(best_write, Seconds(t0));
      const std::string store = (out / deb::kResultStoreFile).string();
      t0 = std::chrono::steady_clock::now();
      deb::WriteResultStore(result, info, store);
      best_store = std::min(best_store, Seconds(t0));
      t0 = std::chrono::steady_clock::now();
      deb::ReadResultStore(store);
      best_read = std::min(best_read, Seconds(t0));
      store_mb = static_cast<double>(std::filesystem::file_size(store)) / 1e6;
      points = result.grid.size();
      name = budget.name;
    }
    std::printf("%-24s %8zu %9.2f %11.2f %11.2f %9.2f %9.2f %9.2f %9.2f %9.2f\n", name.c_str(), points,
                1e3 * best_load, 1e3 * best_eval1, 1e3 * best_evaln, 1e3 * best_write,
                1e3 * (best_load + best_eval1 + best_write), 1e3 * best_store, 1e3 * best_read, store_mb);
  }
  std::filesystem::remove_all(out);
  std::printf("(best of 5; 'total 1t' = load + one-thread evaluation + summary/CSV writing, without plots; "
              "'store' writes result.h5, 'read' reads it back)\n");
  return 0;
}
