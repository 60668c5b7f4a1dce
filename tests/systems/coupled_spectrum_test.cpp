// A PID loop closed around a modal plant, kept as mode blocks and a low-rank
// coupling (coupled_realisation.h), against the dense realisation of the
// same loop (interconnect.h): its eigenvalues (LAPACK) and its Lyapunov
// variance (lyapunov.h), two independent computations.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdlib>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "deb/core/math_constants.h"
#include "deb/systems/coupled_spectrum.h"
#include "deb/systems/frequency_model.h"
#include "deb/systems/interconnect.h"
#include "deb/systems/lyapunov.h"
#include "deb/systems/modal_model.h"
#include "test_util.h"

namespace deb {
namespace {

using cd = std::complex<double>;

// `modes` modes log-uniform in 1-1000 Hz, every fifth 0.3 % above the one
// before, zeta log-uniform in 1e-3..3e-2; random shapes at `inputs` inputs
// and `outputs` outputs, outputs 0 and 1 collocated with inputs 0 and 1.
std::shared_ptr<ModalModel> Plant(int modes, int inputs, int outputs, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  auto m = std::make_shared<ModalModel>();
  for (int k = 0; k < modes; ++k) {
    m->f_hz.push_back(k % 5 == 4 ? m->f_hz.back() * 1.003 : std::pow(1000.0, k / (modes - 1.0)));
    m->zeta.push_back(1e-3 * std::pow(30.0, unit(rng)));
  }
  m->phi_in = testing::RandomMatrix(inputs, modes, rng);
  m->phi_out = testing::RandomMatrix(outputs, modes, rng);
  m->phi_out.topRows(2) = m->phi_in.topRows(2);
  for (int i = 0; i < inputs; ++i) m->input_names.push_back("f" + std::to_string(i));
  for (int i = 0; i < outputs; ++i) m->output_names.push_back("y" + std::to_string(i));
  return m;
}

// K = actuators * diag(PID, PID) * sensors on channels 0 and 1: the series
// PID g (1 + wi/s)(1 + s/wd)/(1 + s/wlp), wi = wc/5, wd = wc/3, wlp = 3 wc,
// with |K G_00| = 1 at 20 Hz.
StateSpace Controller(const ModalModel& plant) {
  const double wc = kTwoPi * 20.0, wi = wc / 5.0, wd = wc / 3.0, wlp = 3.0 * wc;
  cd g00 = 0.0;
  for (int k = 0; k < plant.modes(); ++k) {
    const double wk = kTwoPi * plant.f_hz[k];
    g00 += plant.phi_in(0, k) * plant.phi_in(0, k) / cd(wk * wk - wc * wc, 2.0 * plant.zeta[k] * wk * wc);
  }
  const cd s(0.0, wc);
  const double g = 1.0 / (std::abs((1.0 + wi / s) * (1.0 + s / wd) / (1.0 + s / wlp)) * std::abs(g00));
  // g wlp ((1/wd) s^2 + (1 + wi/wd) s + wi) / (s^2 + wlp s)
  const double n2 = g * wlp / wd, n1 = g * wlp * (1.0 + wi / wd), n0 = g * wlp * wi;
  Eigen::MatrixXd a(2, 2), b(2, 1), c(1, 2), d(1, 1);
  a << 0, 1, 0, -wlp;
  b << 0, 1;
  c << n0, n1 - n2 * wlp;
  d << n2;
  const StateSpace pid(a, b, c, d);
  const StateSpace two = Append(pid, pid);
  const int m = static_cast<int>(plant.phi_in.rows()), p = static_cast<int>(plant.phi_out.rows());
  Eigen::MatrixXd sensors = Eigen::MatrixXd::Zero(2, p), actuators = Eigen::MatrixXd::Zero(m, 2);
  sensors(0, 0) = sensors(1, 1) = 1.0;
  actuators(0, 0) = actuators(1, 1) = 1.0;
  return Series(Series(StateSpace::Gain(sensors), two), StateSpace::Gain(actuators));
}

// The largest distance of a pole of `found` from its nearest one in `ref`,
// relative to that pole's size (both are the same set of n poles).
double PoleDistance(const Eigen::VectorXcd& found, const Eigen::VectorXcd& ref) {
  double worst = 0.0;
  for (Eigen::Index i = 0; i < found.size(); ++i) {
    double best = INFINITY;
    for (Eigen::Index j = 0; j < ref.size(); ++j) best = std::min(best, std::abs(found(i) - ref(j)));
    worst = std::max(worst, best / std::max(1.0, std::abs(found(i))));
  }
  return worst;
}

struct Loop {
  std::shared_ptr<ModalModel> plant;
  StateSpace dense = StateSpace::Gain(Eigen::MatrixXd::Zero(1, 1));
  FrequencyModel diagram = FrequencyModel(StateSpace::Gain(Eigen::MatrixXd::Zero(1, 1)));
};

Loop MakeLoop(int modes, unsigned seed) {
  Loop l;
  l.plant = Plant(modes, 4, 3, seed);
  const StateSpace k = Controller(*l.plant);
  l.dense = Feedback(ModalStateSpace(*l.plant), k, -1);
  l.diagram = FrequencyModel::Feedback(FrequencyModel(std::shared_ptr<const ModalModel>(l.plant)), FrequencyModel(k), -1);
  return l;
}

// The loop solved in coupled form, against its balanced dense realisation:
// every pole within 1e-9 both ways, and each output's variance under white
// inputs within 1e-9 of the dense Lyapunov solve and within its own
// estimate (beside the dense solve's own error).
CoupledSpectrum CheckAgainstDense(const Loop& l) {
  std::string why;
  const std::optional<CoupledRealisation> coupled = l.diagram.Coupled(&why);
  INFO(why);
  REQUIRE(coupled);
  CHECK(coupled->states() == l.dense.states());
  CoupledSolve solved = SolveCoupled(*coupled);
  INFO(solved.why_not);
  REQUIRE(solved.spectrum);
  const CoupledSpectrum& sp = *solved.spectrum;
  // LAPACK on the balanced dense loop (unbalanced, the modal blocks'
  // w^2 = 4e7 cost it 6 digits of the slow poles).
  const Eigen::VectorXcd ref = l.dense.Balanced().Poles();
  REQUIRE(ref.real().maxCoeff() < 0.0);
  CHECK(sp.poles.size() == ref.size());
  CHECK(PoleDistance(sp.poles, ref) < 1e-9);
  CHECK(PoleDistance(ref, sp.poles) < 1e-9);
  const Eigen::MatrixXd w = 0.5 * Eigen::MatrixXd::Identity(4, 4);
  const Eigen::MatrixXd dense_cov = OutputCovariance(l.dense, w);
  const CoupledCovariance cov = CoupledOutputCovariance(sp, {0, 1, 2}, w);
  for (int i = 0; i < 3; ++i) {
    CAPTURE(i);
    const double err = std::abs(cov.covariance(i, i) / dense_cov(i, i) - 1.0);
    CHECK(err < 1e-9);
    CHECK(cov.relative_error(i) < kCoupledVarianceTolerance);
    CHECK(err <= cov.relative_error(i) + 5e-11);
    MESSAGE(sp.poles.size() << " poles, row " << i << ": error " << err << ", estimate " << cov.relative_error(i)
                            << ", eigenvalue condition " << sp.eigenvalue_condition << ", sweeps " << sp.sweeps);
  }
  // Off the diagonal too.
  CHECK((cov.covariance - dense_cov).norm() < 1e-9 * dense_cov.norm());
  return std::move(*solved.spectrum);
}

TEST_CASE("coupled realisation: a PID loop around modes is the dense loop, poles and exact variance to 1e-9") {
  // Seeds whose loops are stable (the dense poles say so).
  for (const std::pair<int, unsigned>& c : {std::pair<int, unsigned>{40, 2}, {150, 1}, {300, 3}}) {
    const int modes = c.first;
    CAPTURE(modes);
    const CoupledSpectrum sp = CheckAgainstDense(MakeLoop(modes, c.second));
    CHECK(sp.rank == 4);  // two actuated and two sensed channels
  }
}

TEST_CASE("coupled realisation: the covariance, formed by slabs of rows, is the same on one thread or four") {
  // 604 poles: five slabs of 128 rows, summed in order whatever the threads.
  const Loop l = MakeLoop(300, 3);
  std::string why;
  const std::optional<CoupledRealisation> coupled = l.diagram.Coupled(&why);
  REQUIRE(coupled);
  const CoupledSolve solved = SolveCoupled(*coupled);
  REQUIRE(solved.spectrum);
  const Eigen::MatrixXd w = 0.5 * Eigen::MatrixXd::Identity(4, 4);
  const char* before = std::getenv("DEB_THREADS");
  const std::string kept = before ? before : "";
  const auto on = [&](const char* threads) {
    ::setenv("DEB_THREADS", threads, 1);
    return CoupledOutputCovariance(*solved.spectrum, {0, 1, 2}, w);
  };
  const CoupledCovariance one = on("1"), four = on("4");
  if (before)
    ::setenv("DEB_THREADS", kept.c_str(), 1);
  else
    ::unsetenv("DEB_THREADS");
  CHECK(one.covariance == four.covariance);
  CHECK(one.relative_error == four.relative_error);
}

// The loop of MakeLoop with mode `k`'s shapes at the loop's channels (inputs
// and outputs 0 and 1) set to zero: at the inputs (`driven` false), at the
// outputs (`seen` false), or both.
Loop LoopMissingMode(int modes, unsigned seed, int k, bool driven, bool seen) {
  Loop l;
  l.plant = Plant(modes, 4, 3, seed);
  if (!driven) l.plant->phi_in.block(0, k, 2, 1).setZero();
  if (!seen) l.plant->phi_out.block(0, k, 2, 1).setZero();
  const StateSpace c = Controller(*l.plant);
  l.dense = Feedback(ModalStateSpace(*l.plant), c, -1);
  l.diagram = FrequencyModel::Feedback(FrequencyModel(std::shared_ptr<const ModalModel>(l.plant)), FrequencyModel(c), -1);
  return l;
}

TEST_CASE("coupled realisation: a mode the loop neither drives nor sees keeps its pole, and the variance holds") {
  const Loop l = LoopMissingMode(40, 2, 7, false, false);
  const CoupledSpectrum sp = CheckAgainstDense(l);
  const std::complex<double> own = ModalPole(l.plant->f_hz[7], l.plant->zeta[7]);
  CHECK(PoleDistance(Eigen::VectorXcd::Constant(1, own), sp.poles) < 1e-14);
}

// MakeLoop's loop with its first mode a rigid-body mode (f = 0).
Loop RigidLoop(int modes, unsigned seed) {
  Loop l;
  l.plant = Plant(modes, 4, 3, seed);
  l.plant->f_hz[0] = 0.0;
  const StateSpace c = Controller(*l.plant);
  l.dense = Feedback(ModalStateSpace(*l.plant), c, -1);
  l.diagram = FrequencyModel::Feedback(FrequencyModel(std::shared_ptr<const ModalModel>(l.plant)), FrequencyModel(c), -1);
  return l;
}

TEST_CASE("coupled realisation: a rigid-body mode in the loop joins the coupling, poles and variance to 1e-9") {
  for (const unsigned seed : {6u, 17u}) {  // seeds whose loops are stable
    CAPTURE(seed);
    // The loop's 4, and the double integrator's [0 1; 0 0].
    CHECK(CheckAgainstDense(RigidLoop(40, seed)).rank == 5);
  }
}

TEST_CASE("coupled realisation: modes the loop reaches on one side only; what it cannot keep as blocks") {
  SUBCASE("a mode driven but not seen, or seen but not driven: its own pole stays, its eigenvectors solved") {
    for (const bool driven : {true, false}) {
      CAPTURE(driven);
      CheckAgainstDense(LoopMissingMode(40, 2, 7, driven, !driven));
    }
  }
  SUBCASE("modes repeated exactly (a symmetric structure)") {
    Loop l;
    l.plant = Plant(60, 4, 3, 6);
    for (int k = 1; k < 60; k += 10) {
      l.plant->f_hz[static_cast<std::size_t>(k)] = l.plant->f_hz[static_cast<std::size_t>(k - 1)];
      l.plant->zeta[static_cast<std::size_t>(k)] = l.plant->zeta[static_cast<std::size_t>(k - 1)];
    }
    const StateSpace c = Controller(*l.plant);
    l.dense = Feedback(ModalStateSpace(*l.plant), c, -1);
    l.diagram =
        FrequencyModel::Feedback(FrequencyModel(std::shared_ptr<const ModalModel>(l.plant)), FrequencyModel(c), -1);
    CheckAgainstDense(l);  // the loop's two actuators and sensors move both of each pair
  }
  SUBCASE("a part too large for one block") {
    const Loop l = MakeLoop(40, 2);
    std::mt19937 rng(5);
    testing::ModalSpec spec;
    for (int k = 0; k < 20; ++k) spec.pairs.push_back({100.0 + 10.0 * k, 0.05});
    const StateSpace big = testing::RandomSystem(spec, 4, 3, rng, false);
    const FrequencyModel diagram =
        FrequencyModel::Feedback(FrequencyModel(std::shared_ptr<const ModalModel>(l.plant)), FrequencyModel(big), -1);
    std::string why;
    CHECK_FALSE(diagram.Coupled(&why));
    CHECK(testing::Contains(why, "40 states"));
  }
}

}  // namespace
}  // namespace deb
