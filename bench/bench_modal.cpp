// Times budgets of large modal paths, as a finite-element model hands them
// over: modal CSV tables (modes, input and output shapes), flat uncorrelated
// forces on every input, one output per output DOF. Per case it prints the
// grid size against the number of modes, the time to load, evaluate (all
// threads) and write summary.json and the CSVs, the cost per frequency
// against the p n m complex multiply-adds of a modal evaluation, the largest
// deviation of CPS (+ the estimated tails beyond the grid) from the exact
// variance, and the peak memory of the process.
//
// Usage: bench_modal [CASE ...] [--keep DIR]
//   CASE: MODESxINPUTSxOUTPUTS, default 1000x20x20 and 5000x36x20.
//   Modes are log-uniform over 1-1000 Hz, every fifth a twin 0.3 % above the
//   one before, zeta log-uniform random in [1e-3, 3e-2]; shapes uniform
//   random in [-0.1, 0.1] (fixed seed). --keep DIR leaves DIR/CASE/b.yaml
//   and its tables for timing `deb run --no-plots` on them.
#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "deb/budget/engine.h"
#include "deb/load/budget_yaml.h"
#include "deb/results/result_writer.h"

namespace {

namespace fs = std::filesystem;

double Seconds(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

struct Case {
  int modes = 1000, inputs = 20, outputs = 20;
  std::string Name() const {
    return std::to_string(modes) + "x" + std::to_string(inputs) + "x" + std::to_string(outputs);
  }
};

void WriteShapes(const fs::path& file, const char* prefix, int dofs, int modes, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-0.1, 0.1);
  std::ofstream out(file);
  out << "dof";
  for (int k = 1; k <= modes; ++k) out << ",m" << k;
  out << "\n";
  char cell[32];
  for (int i = 1; i <= dofs; ++i) {
    out << prefix << i;
    for (int k = 0; k < modes; ++k) {
      std::snprintf(cell, sizeof cell, ",%.9g", u(rng));
      out << cell;
    }
    out << "\n";
  }
}

// The tables and the budget of one case in dir.
fs::path WriteCase(const Case& c, const fs::path& dir) {
  fs::create_directories(dir);
  std::mt19937 rng(20261201);
  std::uniform_real_distribution<double> log_zeta(std::log(1e-3), std::log(3e-2));
  {
    std::ofstream out(dir / "modes.csv");
    out << "mode,f_hz,zeta\n";
    double previous = 0.0;
    for (int k = 0; k < c.modes; ++k) {
      const double f = k % 5 == 4 ? previous * 1.003 : std::pow(1000.0, k / (c.modes - 1.0));
      previous = f;
      char line[96];
      std::snprintf(line, sizeof line, "%d,%.12g,%.6g\n", k + 1, f, std::exp(log_zeta(rng)));
      out << line;
    }
  }
  WriteShapes(dir / "phi_in.csv", "F", c.inputs, c.modes, rng);
  WriteShapes(dir / "phi_out.csv", "y", c.outputs, c.modes, rng);
  std::ofstream b(dir / "b.yaml");
  b << "name: modal_" << c.Name() << "\n"
    << "grid: {type: auto, min_hz: 0.001, max_hz: 100000}\n"
    << "sources:\n  - name: forces\n    unit: N\n    channels: [";
  for (int i = 1; i <= c.inputs; ++i) b << (i > 1 ? ", " : "") << "F" << i;
  b << "]\n    spectrum: {type: flat, level: 1}\n"
    << "paths:\n  - {name: frame, type: modal, modes: modes.csv, input_shapes: phi_in.csv, "
       "output_shapes: phi_out.csv, input_unit: N, output_unit: m}\n"
    << "contributors:\n  - {name: forces, source: forces, path: frame, exact: required}\n"
    << "outputs:\n";
  for (int i = 1; i <= c.outputs; ++i) b << "  - {name: y" << i << ", signal: y" << i << ", unit: nm}\n";
  return dir / "b.yaml";
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<Case> cases;
  fs::path keep;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--keep" && i + 1 < argc) {
      keep = argv[++i];
      continue;
    }
    Case c;
    if (std::sscanf(a.c_str(), "%dx%dx%d", &c.modes, &c.inputs, &c.outputs) != 3) {
      std::fprintf(stderr, "usage: bench_modal [MODESxINPUTSxOUTPUTS ...] [--keep DIR]\n");
      return 2;
    }
    cases.push_back(c);
  }
  if (cases.empty()) cases = {{1000, 20, 20}, {5000, 36, 20}};
  const fs::path root = keep.empty() ? fs::temp_directory_path() / "deb_bench_modal" : keep;
  std::printf("%-13s %7s %8s %8s %8s %8s %8s %10s %11s %9s %8s\n", "case", "points", "pts/mode", "load s",
              "eval s", "write s", "total s", "us/freq", "Gmadd/s", "max err", "peak MB");
  for (const Case& c : cases) {
    const fs::path dir = root / c.Name();
    const fs::path budget_file = WriteCase(c, dir);
    auto t0 = std::chrono::steady_clock::now();
    const deb::Budget budget = deb::LoadBudgetFile(budget_file.string());
    const double load = Seconds(t0);
    t0 = std::chrono::steady_clock::now();
    const deb::BudgetResult result = deb::Evaluate(budget, {});
    const double eval = Seconds(t0);
    t0 = std::chrono::steady_clock::now();
    fs::create_directories(dir / "out");
    deb::WriteResultFiles(result, {budget_file.string(), 0.0}, (dir / "out").string());
    const double write = Seconds(t0);
    double worst = 0.0;
    for (const deb::OutputResult& o : result.outputs)
      for (const deb::ContributorResult& cr : o.contributors)
        if (cr.exact_variance)
          worst = std::max(worst, std::abs(std::sqrt(cr.variance + cr.tail_variance_estimate) /
                                               std::sqrt(*cr.exact_variance) - 1.0));
    const double points = static_cast<double>(result.grid.size());
    const double madds = points * c.modes * c.inputs * c.outputs;  // complex x real, per modal evaluation
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    std::printf("%-13s %7.0f %8.1f %8.3f %8.3f %8.3f %8.3f %10.1f %11.2f %9.1e %8.0f\n", c.Name().c_str(), points,
                points / c.modes, load, eval, write, load + eval + write, 1e6 * eval / points, 1e-9 * madds / eval,
                worst, usage.ru_maxrss / 1024.0);
    if (keep.empty()) fs::remove_all(dir);
  }
  std::printf("(eval: grid, propagation on all threads, exact variance; us/freq and Gmadd/s: evaluation time per\n"
              " grid frequency, and p n m complex-by-real multiply-adds per second of it; max err: largest\n"
              " |RMS(CPS + tails) / RMS(exact) - 1| over the outputs; peak MB: the process so far)\n");
  return 0;
}
