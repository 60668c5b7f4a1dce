// Times deb::Evaluate (propagation S_y = H S_u H^H, CPS, bands, exact
// variance) for a 12-state, 10-input, 6-output path with lightly damped modes
// on a 100 000-point log grid: a diagonal white 10-channel source, the same
// source made coherent (full S_u), and both again band-limited, which makes
// the engine evaluate S_u at every frequency; last, the same path as a
// measured frequency response (type: frf) tabulated at 2000 frequencies,
// which the engine interpolates at every grid point. Prints the best of a few
// runs with one thread and with all threads. Target: < 100 ms on one core.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "deb/budget/engine.h"
#include "deb/core/parallel.h"
#include "deb/spectra/channel_set.h"
#include "deb/spectra/flat_spectrum.h"
#include "deb/systems/frequency_response.h"

namespace {

constexpr int kStates = 12, kInputs = 10, kOutputs = 6, kGridPoints = 100000;
int repeats = 5;  // first argument overrides
constexpr double kTwoPi = 6.283185307179586476925286766559;

Eigen::MatrixXd RandomMatrix(int rows, int cols, std::mt19937& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::MatrixXd m(rows, cols);
  for (int j = 0; j < cols; ++j)
    for (int i = 0; i < rows; ++i) m(i, j) = normal(rng);
  return m;
}

// Six modes, 2..500 Hz, zeta 0.002..0.05, in a random (well conditioned) basis.
deb::StateSpace LightlyDampedSystem(std::mt19937& rng) {
  const double f_n[kStates / 2] = {2.0, 7.5, 23.0, 61.0, 180.0, 500.0};
  const double zeta[kStates / 2] = {0.01, 0.002, 0.05, 0.005, 0.02, 0.01};
  Eigen::MatrixXd blocks = Eigen::MatrixXd::Zero(kStates, kStates);
  for (int i = 0; i < kStates / 2; ++i) {
    const double w = kTwoPi * f_n[i], re = -zeta[i] * w, im = w * std::sqrt(1 - zeta[i] * zeta[i]);
    blocks.block(2 * i, 2 * i, 2, 2) << re, im, -im, re;
  }
  const Eigen::MatrixXd t =
      Eigen::MatrixXd::Identity(kStates, kStates) + 0.2 * RandomMatrix(kStates, kStates, rng);
  return deb::StateSpace(t * blocks * t.inverse(), RandomMatrix(kStates, kInputs, rng),
                         RandomMatrix(kOutputs, kStates, rng), Eigen::MatrixXd::Zero(kOutputs, kInputs));
}

std::vector<std::string> Names(const std::string& stem, int count) {
  std::vector<std::string> names;
  for (int i = 0; i < count; ++i) names.push_back(stem + std::to_string(i));
  return names;
}

deb::Budget MakeBudget(std::shared_ptr<const deb::Spectrum> spectrum, std::mt19937& rng) {
  deb::Budget b;
  b.name = "propagation benchmark";
  b.grid.kind = deb::GridKind::kExplicit;
  b.grid.f_hz = deb::FrequencyGrid::Log(0.1, 1e4, kGridPoints).f_hz();

  deb::Source s;
  s.name = "noise";
  s.unit = "um/s";
  s.spectrum = std::move(spectrum);
  s.channel_names = Names("ch", kInputs);
  b.sources.push_back(s);

  deb::Path p;
  p.name = "plant";
  p.system = LightlyDampedSystem(rng);
  p.input_names = Names("u", kInputs);
  p.output_names = Names("y", kOutputs);
  p.input_units.assign(kInputs, "um/s");
  p.output_units.assign(kOutputs, "um/s");
  b.paths.push_back(p);

  b.contributors.push_back({"noise_plant", "noise", "plant", deb::ExactVariance::kAuto, {}, {}, false});
  for (int o = 0; o < kOutputs; ++o)
    b.outputs.push_back({"out" + std::to_string(o), p.output_names[o], "um/s", {}, {}, {}, {}, {}, {}});
  return b;
}

struct Timing {
  double wall_ms = 1e300;
  double cpu_ms = 1e300;  // process CPU time, all threads
};

// Best wall and CPU times of `repeats` runs. With one thread the CPU time is
// the time on one core even when other processes compete for it.
Timing Best(const deb::Budget& budget, int threads) {
  deb::EngineOptions options;
  options.threads = threads;
  Timing best;
  for (int r = 0; r < repeats; ++r) {
    const std::clock_t c0 = std::clock();
    const auto t0 = std::chrono::steady_clock::now();
    const deb::BudgetResult result = deb::Evaluate(budget, options);
    const auto t1 = std::chrono::steady_clock::now();
    const std::clock_t c1 = std::clock();
    if (result.outputs.size() != kOutputs) std::abort();
    best.wall_ms = std::min(best.wall_ms, std::chrono::duration<double, std::milli>(t1 - t0).count());
    best.cpu_ms = std::min(best.cpu_ms, 1e3 * static_cast<double>(c1 - c0) / CLOCKS_PER_SEC);
  }
  return best;
}

void Run(const char* label, const deb::Budget& budget) {
  const std::size_t points = budget.grid.f_hz.size();
  const std::size_t contributors = budget.contributors.size();
  std::printf("%s (best of %d)\n", label, repeats);
  std::printf("  path: %d states, %d inputs, %d outputs; %zu contributor(s); %zu grid points\n", kStates,
              kInputs, kOutputs, contributors, points);
  for (int threads : {1, deb::DefaultThreadCount()}) {
    const Timing t = Best(budget, threads);
    const double ns = t.wall_ms * 1e6 / static_cast<double>(points * contributors);
    std::printf("  %2d thread(s): wall %8.2f ms, cpu %8.2f ms, %6.1f ns per frequency per contributor\n",
                threads, t.wall_ms, t.cpu_ms, ns);
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc > 1) repeats = std::max(1, std::atoi(argv[1]));
  std::mt19937 rng(12345);
  std::vector<std::shared_ptr<const deb::Spectrum>> parts;
  for (int i = 0; i < kInputs; ++i) parts.push_back(std::make_shared<deb::FlatSpectrum>(0.5 + 0.1 * i));
  const auto diagonal = std::make_shared<deb::IndependentChannels>(parts);
  Run("diagonal white source (10 channels)", MakeBudget(diagonal, rng));

  // Coherence: a normalised Gram matrix, symmetric positive definite with unit diagonal.
  const Eigen::MatrixXd g = RandomMatrix(kInputs, kInputs + 2, rng);
  const Eigen::MatrixXd gram = g * g.transpose();
  const Eigen::VectorXd d = gram.diagonal().cwiseSqrt().cwiseInverse();
  Eigen::MatrixXd rho = d.asDiagonal() * gram * d.asDiagonal();
  rho.diagonal().setOnes();
  rng.seed(12345);  // the same path in every case
  Run("correlated white source (full S_u, constant)",
      MakeBudget(std::make_shared<deb::CorrelatedChannels>(diagonal, rho), rng));

  // Band-limited (not white): S_u is evaluated at every frequency.
  std::vector<std::shared_ptr<const deb::Spectrum>> limited;
  for (int i = 0; i < kInputs; ++i)
    limited.push_back(std::make_shared<deb::FlatSpectrum>(0.5 + 0.1 * i, 0.0, 2e4));
  const auto limited_diagonal = std::make_shared<deb::IndependentChannels>(limited);
  rng.seed(12345);
  Run("band-limited source (10 channels, evaluated per frequency)", MakeBudget(limited_diagonal, rng));
  rng.seed(12345);
  Run("correlated band-limited source (full S_u, evaluated per frequency)",
      MakeBudget(std::make_shared<deb::CorrelatedChannels>(limited_diagonal, rho), rng));

  // The same path as measured data: its response at 2000 log-spaced points.
  rng.seed(12345);
  deb::Budget measured = MakeBudget(diagonal, rng);
  deb::Path& path = measured.paths[0];
  const std::vector<double> table_hz = deb::FrequencyGrid::Log(0.1, 1e4, 2000).f_hz();
  const std::vector<Eigen::MatrixXcd> table = deb::FrequencyResponse(path.system).Evaluate(table_hz);
  path.measured = std::make_shared<const deb::FrequencyModel>(deb::MeasuredResponse(table_hz, table));
  path.system = deb::StateSpace::Gain(Eigen::MatrixXd::Zero(kOutputs, kInputs));
  Run("measured frequency response (2000 points, interpolated per frequency), diagonal white source", measured);
  return 0;
}
