// Frequency-response benchmark: the inner loop of every budget. Times
// FrequencyResponse on a random stable system (default 12 states, 6 outputs,
// 10 inputs, 100 000 log-spaced frequencies) in three uses:
//   reduce  - the one-off reduction of A (constructor),
//   forEach - H per frequency, reduced at once to diag(H H^H) and integrated
//             cumulatively (what the budget engine does with a white source),
//   store   - all H matrices kept (Evaluate),
// for the modal and the Schur form, on one thread and on all threads, next
// to a dense LU solve per frequency as the naive baseline.
//
// usage: bench_response [states outputs inputs frequencies]
#include <chrono>
#include <cmath>
#include <complex>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <random>
#include <vector>

#include "deb/core/parallel.h"
#include "deb/systems/frequency_response.h"
#include "bench/random_modes.h"

namespace {

using Clock = std::chrono::steady_clock;
using deb::FrequencyResponse;
using deb::StateSpace;

double MsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// CPU time of the whole process [ms]: on a loaded machine the wall time of a
// one-thread run overstates its cost, the CPU time does not.
double CpuMs() { return 1e3 * static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

struct Timing {
  double wall_ms, cpu_ms;
};

// Stable, lightly damped modes between 0.5 Hz and 500 Hz (zeta 1e-4 .. 0.3)
// plus one real pole if the state count is odd, mixed by a random similarity.
StateSpace RandomSystem(int n, int p, int m, std::mt19937& rng) {
  deb::bench::RandomModes random_modes(rng);
  const Eigen::MatrixXd blocks = random_modes.ModalBlocks(n, 1e-4, 3000.0);
  const auto random = [&](int r, int c) { return random_modes.Matrix(r, c); };
  const Eigen::MatrixXd s = Eigen::MatrixXd::Identity(n, n) + 0.3 * random(n, n);
  return StateSpace(s * blocks * s.inverse(), random(n, m), random(p, n),
                    Eigen::MatrixXd::Zero(p, m));
}

// Output PSDs for unit white inputs, S_y,ii = sum_j |H_ij|^2, then a
// cumulative trapezoid per output; returns the total to keep the work alive.
double EngineLikePass(const FrequencyResponse& h, const std::vector<double>& f, int threads) {
  const int p = h.outputs();
  std::vector<double> psd(f.size() * p);
  h.ForEach(
      f,
      [&](std::size_t k, const Eigen::MatrixXcd& hk) {
        for (int i = 0; i < p; ++i) psd[k * p + i] = hk.row(i).squaredNorm();
      },
      threads);
  double total = 0.0;
  for (int i = 0; i < p; ++i) {
    double cps = 0.0;
    for (std::size_t k = 1; k < f.size(); ++k)
      cps += 0.5 * (psd[k * p + i] + psd[(k - 1) * p + i]) * (f[k] - f[k - 1]);
    total += cps;
  }
  return total;
}

// Best of `repeats` runs (wall and CPU time taken separately).
template <typename F>
Timing Best(int repeats, F&& run) {
  Timing best{1e300, 1e300};
  for (int r = 0; r < repeats; ++r) {
    const double cpu = CpuMs();
    const auto start = Clock::now();
    run();
    best.wall_ms = std::min(best.wall_ms, MsSince(start));
    best.cpu_ms = std::min(best.cpu_ms, CpuMs() - cpu);
  }
  return best;
}

void PrintRow(const char* form, const char* use, int threads, Timing t, int count,
              double check) {
  std::printf("%-8s %-9s %7d %10.3f %10.3f %10.1f %14.6e\n", form, use, threads, t.wall_ms,
              t.cpu_ms, 1e6 * t.wall_ms / count, check);
}

}  // namespace

int main(int argc, char** argv) {
  const int n = argc > 1 ? std::atoi(argv[1]) : 12;
  const int p = argc > 2 ? std::atoi(argv[2]) : 6;
  const int m = argc > 3 ? std::atoi(argv[3]) : 10;
  const int count = argc > 4 ? std::atoi(argv[4]) : 100000;
  if (n < 1 || p < 1 || m < 1 || count < 2) {
    std::fprintf(stderr, "usage: bench_response [states outputs inputs frequencies]\n");
    return 2;
  }
  std::mt19937 rng(42);
  const StateSpace sys = RandomSystem(n, p, m, rng);
  std::vector<double> f(count);
  for (int k = 0; k < count; ++k) f[k] = 0.01 * std::pow(1e5, k / (count - 1.0));
  const int all = deb::DefaultThreadCount();
  const int repeats = 5;

  std::printf("system: %d states, %d outputs, %d inputs; %d frequencies 0.01-1000 Hz; "
              "%d threads available\n", n, p, m, count, all);
  std::printf("%-8s %-9s %7s %10s %10s %10s %14s\n", "form", "use", "threads", "wall ms",
              "cpu ms", "ns/freq", "check");
  for (const auto method : {FrequencyResponse::Method::kAuto, FrequencyResponse::Method::kSchur}) {
    FrequencyResponse h(sys, method);
    const Timing reduce = Best(repeats, [&] { h = FrequencyResponse(sys, method); });
    const char* form = h.method() == FrequencyResponse::Method::kModal ? "modal" : "schur";
    std::printf("%-8s %-9s %7d %10.3f %10.3f %10s %14s   cond(V) = %.3g\n", form, "reduce", 1,
                reduce.wall_ms, reduce.cpu_ms, "-", "-", h.condition());
    for (const int threads : {1, all}) {
      double check = 0.0;
      const Timing t = Best(repeats, [&] { check = EngineLikePass(h, f, threads); });
      PrintRow(form, "forEach", threads, t, count, check);
    }
    for (const int threads : {1, all}) {
      std::vector<Eigen::MatrixXcd> stored;
      const Timing t = Best(repeats, [&] { stored = h.Evaluate(f, threads); });
      PrintRow(form, "store", threads, t, count, std::abs(stored[count / 2](0, 0)));
    }
  }

  // Naive baseline: dense LU of (j w I - A) at every frequency, one thread.
  const Eigen::MatrixXcd a = sys.A().cast<std::complex<double>>();
  const Eigen::MatrixXcd b = sys.B().cast<std::complex<double>>();
  const Eigen::MatrixXcd c = sys.C().cast<std::complex<double>>();
  double check = 0.0;
  const Timing t = Best(1, [&] {
    for (double fk : f) {
      const std::complex<double> s(0.0, 2.0 * M_PI * fk);
      const Eigen::MatrixXcd x =
          (s * Eigen::MatrixXcd::Identity(n, n) - a).partialPivLu().solve(b);
      check += (c * x).squaredNorm();
    }
  });
  PrintRow("denseLU", "sum|H|^2", 1, t, count, check);
  return 0;
}
