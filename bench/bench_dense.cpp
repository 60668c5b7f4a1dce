// Dense state-space benchmark: the one-off linear algebra on A that precedes
// every evaluation. For a stable model of n states whose A is dense (lightly
// damped pairs, zeta 1e-3 .. 0.1 at 0.5 .. 500 Hz, rotated by a random
// orthogonal similarity), one output and three inputs, it prints the seconds
// (wall and CPU) for
//   poles      - StateSpace::Poles (eigenvalues of A),
//   response   - the FrequencyResponse constructor (modal reduction),
//   covariance - OutputCovariance under unit white inputs (Lyapunov),
// and with --eigen also Eigen's own dense solvers on the same A for
// comparison: EigenSolver without and with eigenvectors, and ComplexSchur.
// The check column is the output variance (the same with every solver).
//
// usage: bench_dense [--eigen] [states ...]   (default 200 500 1000 2000)
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <random>
#include <vector>

#include "deb/core/error.h"
#include "deb/systems/frequency_response.h"
#include "deb/systems/lyapunov.h"
#include "bench/random_modes.h"

namespace {

using Clock = std::chrono::steady_clock;
using deb::StateSpace;

struct Seconds {
  double wall, cpu;
};

// One run: the operations are single-threaded, so CPU time is the cost and
// wall time shows how loaded the machine was.
template <typename F>
Seconds Time(F&& run) {
  const std::clock_t cpu = std::clock();
  const auto start = Clock::now();
  run();
  return {std::chrono::duration<double>(Clock::now() - start).count(),
          static_cast<double>(std::clock() - cpu) / CLOCKS_PER_SEC};
}

StateSpace DenseModel(int n, std::mt19937& rng) {
  deb::bench::RandomModes random_modes(rng);
  const Eigen::MatrixXd blocks = random_modes.ModalBlocks(n, 1e-3, 100.0);
  const auto random = [&](int r, int c) { return random_modes.Matrix(r, c); };
  const Eigen::MatrixXd q = Eigen::HouseholderQR<Eigen::MatrixXd>(random(n, n)).householderQ();
  return StateSpace(q * blocks * q.transpose(), random(n, 3), random(1, n),
                    Eigen::MatrixXd::Zero(1, 3));
}

void PrintRow(int n, const char* what, Seconds s, double check) {
  std::printf("%6d  %-22s %9.3f %9.3f %16.9e\n", n, what, s.wall, s.cpu, check);
}

}  // namespace

int main(int argc, char** argv) {
  bool eigen = false;
  std::vector<int> sizes;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--eigen") == 0) {
      eigen = true;
      continue;
    }
    const int n = std::atoi(argv[i]);
    if (n < 1) {
      std::fprintf(stderr, "usage: bench_dense [--eigen] [states ...]\n");
      return 2;
    }
    sizes.push_back(n);
  }
  if (sizes.empty()) sizes = {200, 500, 1000, 2000};
  std::printf("%6s  %-22s %9s %9s %16s\n", "states", "operation", "wall s", "cpu s", "check");
  for (const int n : sizes) {
    std::mt19937 rng(7);
    const StateSpace sys = DenseModel(n, rng);
    // Each time is taken before its check is read (argument order is unspecified).
    Eigen::VectorXcd poles;
    Seconds t = Time([&] { poles = sys.Poles(); });
    PrintRow(n, "poles", t, poles.real().maxCoeff());
    double condition = 0.0;
    t = Time([&] { condition = deb::FrequencyResponse(sys).condition(); });
    PrintRow(n, "response", t, condition);
    Eigen::MatrixXd y;
    try {
      t = Time([&] { y = deb::OutputCovariance(sys, Eigen::MatrixXd::Identity(3, 3)); });
      PrintRow(n, "covariance", t, y(0, 0));
    } catch (const deb::InputError& e) {
      std::printf("%6d  %-22s refused: %s\n", n, "covariance", e.what());
    }
    if (!eigen) continue;
    const Eigen::MatrixXd& a = sys.A();
    t = Time([&] { poles = Eigen::EigenSolver<Eigen::MatrixXd>(a, false).eigenvalues(); });
    PrintRow(n, "Eigen eigenvalues", t, poles.real().maxCoeff());
    t = Time([&] { poles = Eigen::EigenSolver<Eigen::MatrixXd>(a, true).eigenvalues(); });
    PrintRow(n, "Eigen eigenvectors", t, poles.real().maxCoeff());
    t = Time([&] { poles = Eigen::ComplexSchur<Eigen::MatrixXd>(a).matrixT().diagonal(); });
    PrintRow(n, "Eigen ComplexSchur", t, poles.real().maxCoeff());
  }
  return 0;
}
