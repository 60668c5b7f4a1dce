// Times budgets of large modal paths, as a finite-element model hands them
// over: modal CSV tables (modes, input and output shapes), flat uncorrelated
// forces on every input, one output per output DOF. Per case it prints the
// grid size against the number of modes, the time to load, evaluate (all
// threads) and write summary.json and the CSVs, the cost per frequency
// against the p n m complex multiply-adds of a modal evaluation, the largest
// deviation of CPS (+ the estimated tails beyond the grid) from the exact
// variance, and the peak memory of the process.
//
// Usage: bench_modal [CASE ...] [--loop] [--keep DIR]
//   CASE: MODESxINPUTSxOUTPUTS, default 1000x20x20 and 5000x36x20.
//   --loop: the forces act on a feedback path instead: a diagonal 2x2 PID
//   (series form, 20 Hz crossover on the first channel) from outputs y1, y2
//   to inputs F1, F2 around the modal path, whose y1, y2 are collocated with
//   F1, F2 (the same shapes), so that the loop is stable.
//   Modes are log-uniform over 1-1000 Hz, every fifth a twin 0.3 % above the
//   one before, zeta log-uniform random in [1e-3, 3e-2]; shapes uniform
//   random in [-0.1, 0.1] (fixed seed). --keep DIR leaves DIR/CASE/b.yaml
//   and its tables for timing `deb run --no-plots` on them.
#include <sys/resource.h>

#include <Eigen/Dense>
#include <chrono>
#include <complex>
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

Eigen::MatrixXd RandomShapes(int dofs, int modes, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-0.1, 0.1);
  Eigen::MatrixXd phi(dofs, modes);
  for (int i = 0; i < dofs; ++i)
    for (int k = 0; k < modes; ++k) phi(i, k) = u(rng);
  return phi;
}

void WriteShapes(const fs::path& file, const char* prefix, const Eigen::MatrixXd& phi) {
  const Eigen::Index dofs = phi.rows(), modes = phi.cols();
  std::ofstream out(file);
  out << "dof";
  for (int k = 1; k <= modes; ++k) out << ",m" << k;
  out << "\n";
  char cell[32];
  for (Eigen::Index i = 0; i < dofs; ++i) {
    out << prefix << i + 1;
    for (Eigen::Index k = 0; k < modes; ++k) {
      std::snprintf(cell, sizeof cell, ",%.9g", phi(i, k));
      out << cell;
    }
    out << "\n";
  }
}

// The series-form PID of --loop as num/den in s, highest power first:
// gain (1 + w_i/s)(1 + s/w_d)/(1 + s/w_lp), f_i = f_c/5, f_d = f_c/3,
// f_lp = 3 f_c, with |K G| = 1 at f_c for the collocated plant G of channel 0.
std::string PidEntry(const Eigen::MatrixXd& phi, const std::vector<double>& f_hz, const std::vector<double>& zeta) {
  const double f_c = 20.0, wc = 2.0 * M_PI * f_c;
  std::complex<double> g(0.0);
  for (std::size_t k = 0; k < f_hz.size(); ++k) {
    const double wk = 2.0 * M_PI * f_hz[k];
    g += phi(0, static_cast<Eigen::Index>(k)) * phi(0, static_cast<Eigen::Index>(k)) /
         std::complex<double>(wk * wk - wc * wc, 2.0 * zeta[k] * wk * wc);
  }
  const double wi = wc / 5.0, wd = wc / 3.0, wlp = 3.0 * wc;
  const std::complex<double> s(0.0, wc);
  const double pid_at_fc = std::abs((1.0 + wi / s) * (1.0 + s / wd) / (1.0 + s / wlp));
  const double gain = 1.0 / (pid_at_fc * std::abs(g));
  char entry[200];
  std::snprintf(entry, sizeof entry, "{num: [%.12g, %.12g, %.12g], den: [%.12g, 1, 0]}", gain / wd,
                gain * (1.0 + wi / wd), gain * wi, 1.0 / wlp);
  return entry;
}

// The tables and the budget of one case in dir.
fs::path WriteCase(const Case& c, bool loop, const fs::path& dir) {
  fs::create_directories(dir);
  std::mt19937 rng(20261201);
  std::uniform_real_distribution<double> log_zeta(std::log(1e-3), std::log(3e-2));
  std::vector<double> f_hz, zeta;
  {
    std::ofstream out(dir / "modes.csv");
    out << "mode,f_hz,zeta\n";
    double previous = 0.0;
    for (int k = 0; k < c.modes; ++k) {
      const double f = k % 5 == 4 ? previous * 1.003 : std::pow(1000.0, k / (c.modes - 1.0));
      previous = f;
      f_hz.push_back(f);
      zeta.push_back(std::exp(log_zeta(rng)));
      char line[96];
      std::snprintf(line, sizeof line, "%d,%.12g,%.6g\n", k + 1, f, zeta.back());
      out << line;
    }
  }
  const Eigen::MatrixXd phi_in = RandomShapes(c.inputs, c.modes, rng);
  Eigen::MatrixXd phi_out = RandomShapes(c.outputs, c.modes, rng);
  if (loop) phi_out.topRows(2) = phi_in.topRows(2);  // y1, y2 collocated with F1, F2
  WriteShapes(dir / "phi_in.csv", "F", phi_in);
  WriteShapes(dir / "phi_out.csv", "y", phi_out);
  std::ofstream b(dir / "b.yaml");
  b << "name: modal_" << c.Name() << (loop ? "_loop" : "") << "\n"
    << "grid: {type: auto, min_hz: 0.001, max_hz: 100000}\n"
    << "sources:\n  - name: forces\n    unit: N\n    channels: [";
  for (int i = 1; i <= c.inputs; ++i) b << (i > 1 ? ", " : "") << "F" << i;
  b << "]\n    spectrum: {type: flat, level: 1}\n"
    << "paths:\n  - {name: frame, type: modal, modes: modes.csv, input_shapes: phi_in.csv, "
       "output_shapes: phi_out.csv, input_unit: N, output_unit: m}\n";
  if (loop) {
    auto row = [](int width, int one) {
      std::string r = "[";
      for (int j = 0; j < width; ++j) r += std::string(j ? ", " : "") + (j == one ? "1" : "0");
      return r + "]";
    };
    b << "  - {name: sensors, type: gain, gain: [" << row(c.outputs, 0) << ", " << row(c.outputs, 1)
      << "], input_unit: m, output_unit: m}\n";
    const std::string pid = PidEntry(phi_in, f_hz, zeta), zero = "{num: [0], den: [1]}";
    b << "  - {name: pid, type: transfer_function, matrix: [[" << pid << ", " << zero << "], [" << zero << ", " << pid
      << "]], input_unit: m, output_unit: N}\n";
    b << "  - {name: actuators, type: gain, gain: [";
    for (int i = 0; i < c.inputs; ++i) b << (i ? ", " : "") << "[" << (i == 0) << ", " << (i == 1) << "]";
    b << "], input_unit: N, output_unit: N}\n"
      << "  - {name: controller, type: series, of: [sensors, pid, actuators]}\n"
      << "  - {name: loop, type: feedback, plant: frame, controller: controller}\n";
  }
  b << "contributors:\n  - {name: forces, source: forces, path: " << (loop ? "loop" : "frame")
    << ", exact: required}\n"
    << "outputs:\n";
  for (int i = 1; i <= c.outputs; ++i) b << "  - {name: y" << i << ", signal: y" << i << ", unit: nm}\n";
  return dir / "b.yaml";
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<Case> cases;
  fs::path keep;
  bool loop = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--keep" && i + 1 < argc) {
      keep = argv[++i];
      continue;
    }
    if (a == "--loop") {
      loop = true;
      continue;
    }
    Case c;
    if (std::sscanf(a.c_str(), "%dx%dx%d", &c.modes, &c.inputs, &c.outputs) != 3) {
      std::fprintf(stderr, "usage: bench_modal [MODESxINPUTSxOUTPUTS ...] [--loop] [--keep DIR]\n");
      return 2;
    }
    cases.push_back(c);
  }
  if (cases.empty()) cases = {{1000, 20, 20}, {5000, 36, 20}};
  const fs::path root = keep.empty() ? fs::temp_directory_path() / "deb_bench_modal" : keep;
  std::printf("%-13s %7s %8s %8s %8s %8s %8s %10s %11s %9s %8s\n", "case", "points", "pts/mode", "load s",
              "eval s", "write s", "total s", "us/freq", "Gmadd/s", "max err", "peak MB");
  for (const Case& c : cases) {
    const fs::path dir = root / (c.Name() + (loop ? "_loop" : ""));
    const fs::path budget_file = WriteCase(c, loop, dir);
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
