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
//
// bench_dense --fe MODES [INPUTS OUTPUTS [FREQUENCIES]] [--exact]: a finite-
// element model as engineers hand it over: MODES modes (0.5-500 Hz log-
// uniform, zeta 1e-3..0.1, random mass-normalised shapes at INPUTS and
// OUTPUTS DOFs, default 20 x 20) realised in physical coordinates
// x = [q_1, q_1', ...] and rotated by a random orthogonal Q (the same H and
// variances). Prints the reduction (which form, cond), H at FREQUENCIES
// points (default 10201, log 0.1-1000 Hz, on all threads) with its worst
// error against the modal model's own H at every resonance, and with
// --exact the output variances (Lyapunov) against the modal closed form.
// --keep DIR writes DIR/plant.mat (A, B, C, D of the rotated model) and
// DIR/b.yaml (unit white forces on every input, exact variance required),
// for timing `deb run DIR/b.yaml --no-plots`.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "deb/core/error.h"
#include "deb/systems/frequency_response.h"
#include "deb/formats/mat_file.h"
#include "deb/systems/lyapunov.h"
#include "deb/systems/modal_model.h"
#include "deb/systems/modal_response.h"
#include "deb/core/parallel.h"
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

const char* FormName(deb::FrequencyResponse::Method m) {
  switch (m) {
    case deb::FrequencyResponse::Method::kModal: return "modal";
    case deb::FrequencyResponse::Method::kSchur: return "block-diagonal";
    case deb::FrequencyResponse::Method::kHessenberg: return "Hessenberg";
    default: return "?";
  }
}

std::vector<std::string> Numbered(const std::string& stem, int count) {
  std::vector<std::string> names;
  for (int i = 1; i <= count; ++i) names.push_back(stem + std::to_string(i));
  return names;
}

// DIR/plant.mat and DIR/b.yaml for `deb run` (see the usage above).
void KeepBudget(const std::string& dir, const StateSpace& sys, int modes) {
  std::filesystem::create_directories(dir);
  deb::formats::WriteMatFile(dir + "/plant.mat",
                        {{"A", deb::formats::MatValue::Matrix(sys.A())},
                         {"B", deb::formats::MatValue::Matrix(sys.B())},
                         {"C", deb::formats::MatValue::Matrix(sys.C())},
                         {"D", deb::formats::MatValue::Matrix(sys.D())},
                         {"input_names", deb::formats::MatValue::Names(Numbered("F", sys.inputs()))},
                         {"output_names", deb::formats::MatValue::Names(Numbered("y", sys.outputs()))}},
                        "a rotated finite-element model (bench_dense --fe)");
  std::ofstream b(dir + "/b.yaml");
  b << "name: dense_" << modes << "_modes\n"
    << "grid: {type: auto, min_hz: 0.001, max_hz: 100000}\n"
    << "sources:\n  - name: forces\n    unit: N\n    channels: [";
  for (int i = 1; i <= sys.inputs(); ++i) b << (i > 1 ? ", " : "") << "F" << i;
  b << "]\n    spectrum: {type: flat, level: 1, quantity: psd}\n"
    << "paths:\n  - {name: frame, type: state_space, file: plant.mat, input_unit: N, output_unit: m}\n"
    << "contributors:\n  - {name: forces, source: forces, path: frame, exact: required}\n"
    << "outputs:\n";
  for (int i = 1; i <= sys.outputs(); ++i) b << "  - {name: y" << i << ", signal: y" << i << ", unit: nm}\n";
}

int FiniteElementBench(int modes, int inputs, int outputs, int points, bool exact, const std::string& keep) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> normal(0.0, 1.0);
  deb::ModalModel model;
  for (int k = 0; k < modes; ++k) {
    model.f_hz.push_back(0.5 * std::pow(1000.0, unit(rng)));
    model.zeta.push_back(1e-3 * std::pow(100.0, unit(rng)));
  }
  model.phi_in.resize(inputs, modes);
  model.phi_out.resize(outputs, modes);
  for (int k = 0; k < modes; ++k) {
    for (int i = 0; i < inputs; ++i) model.phi_in(i, k) = normal(rng);
    for (int i = 0; i < outputs; ++i) model.phi_out(i, k) = normal(rng);
  }
  for (int i = 0; i < inputs; ++i) model.input_names.push_back("in" + std::to_string(i));
  for (int i = 0; i < outputs; ++i) model.output_names.push_back("out" + std::to_string(i));
  const StateSpace physical = deb::ModalStateSpace(model);
  const int n = physical.states();
  Eigen::MatrixXd g(n, n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) g(i, j) = normal(rng);
  const Eigen::MatrixXd q = Eigen::HouseholderQR<Eigen::MatrixXd>(g).householderQ();
  const StateSpace sys(q * physical.A() * q.transpose(), q * physical.B(), physical.C() * q.transpose(), physical.D());
  std::vector<int> rows(outputs);
  for (int i = 0; i < outputs; ++i) rows[i] = i;
  const deb::ModalResponse reference(model, rows);
  if (!keep.empty()) KeepBudget(keep, sys, modes);

  std::printf("finite-element model: %d modes (%d states) x %d inputs x %d outputs, rotated; %d threads\n", modes, n,
              inputs, outputs, deb::DefaultThreadCount());
  std::optional<deb::FrequencyResponse> h;
  Seconds t = Time([&] { h.emplace(sys); });
  std::printf("  reduction             %9.3f s wall %9.3f s cpu  form %s, cond %.3g, largest group %d\n", t.wall,
              t.cpu, FormName(h->method()), h->condition(), h->largest_block());
  std::vector<double> f(points);
  for (int i = 0; i < points; ++i) f[i] = 0.1 * std::pow(1e4, i / (points - 1.0));
  std::vector<double> psd(points);
  t = Time([&] {
    h->ForEach(f, [&](std::size_t k, const Eigen::MatrixXcd& hk) { psd[k] = hk.squaredNorm(); });
  });
  std::printf("  H at %6d points     %9.3f s wall %9.3f s cpu  (%.2f us per point and core)\n", points, t.wall, t.cpu,
              1e6 * t.cpu / points);
  double worst = 0.0;
  for (int k = 0; k < modes; ++k) {
    const double fd = model.f_hz[k] * std::sqrt(1.0 - model.zeta[k] * model.zeta[k]);
    for (const double x : {1.0 - model.zeta[k], 1.0, 1.0 + model.zeta[k]}) {
      const Eigen::MatrixXcd want = reference.At(fd * x);
      worst = std::max(worst, (h->At(fd * x) - want).norm() / want.norm());
    }
  }
  std::printf("  H at every resonance: worst relative error %.3g against the modal model\n", worst);
  if (!exact) return 0;
  const Eigen::MatrixXd w = Eigen::MatrixXd::Identity(inputs, inputs);
  Eigen::MatrixXd y;
  try {
    t = Time([&] { y = deb::OutputCovariance(sys, w); });
  } catch (const deb::InputError& e) {
    std::printf("  exact variance refused: %s\n", e.what());
    return 0;
  }
  const deb::ModalCovariance closed = deb::ModalOutputCovariance(model, rows, w);
  double err = 0.0;
  for (int i = 0; i < outputs; ++i) err = std::max(err, std::abs(y(i, i) - closed.variance(i)) / closed.variance(i));
  std::printf("  exact variance        %9.3f s wall %9.3f s cpu  worst relative error %.3g against the modal closed form\n",
              t.wall, t.cpu, err);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc >= 3 && std::strcmp(argv[1], "--fe") == 0) {
    std::vector<int> numbers;
    bool exact = false;
    std::string keep;
    for (int i = 2; i < argc; ++i) {
      if (std::strcmp(argv[i], "--keep") == 0 && i + 1 < argc) {
        keep = argv[++i];
      } else if (std::strcmp(argv[i], "--exact") == 0) {
        exact = true;
      } else {
        numbers.push_back(std::atoi(argv[i]));
        if (numbers.back() < 1) {
          std::fprintf(stderr, "usage: bench_dense --fe MODES [INPUTS OUTPUTS [FREQUENCIES]] [--exact] [--keep DIR]\n");
          return 2;
        }
      }
    }
    numbers.resize(4, 0);
    return FiniteElementBench(numbers[0], numbers[1] ? numbers[1] : 20, numbers[2] ? numbers[2] : 20,
                              numbers[3] ? numbers[3] : 10201, exact, keep);
  }
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
