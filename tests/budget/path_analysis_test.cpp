// Loops and chains around a modal path (a finite-element plant with a
// controller or a sensor model): H is evaluated from the parts, the modal
// form and the small controller closed at each frequency (path.h), while
// poles, stability and the exact variance come from the realisation. Each
// is checked against the dense realisation solved by other means: H by the
// backward-stable Hessenberg solve, the variance by the Bartels-Stewart
// solve of the whole Lyapunov equation.
#include "deb/budget/path_analysis.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <memory>
#include <random>
#include <vector>

#include "deb/budget/path_composition.h"
#include "deb/core/limits.h"
#include "deb/systems/frequency_response.h"
#include "deb/systems/interconnect.h"
#include "deb/systems/lyapunov.h"

namespace deb {
namespace {

constexpr double kTwoPi = 2.0 * M_PI;

// `modes` modes log-uniform in 1-500 Hz, zeta log-uniform in 2e-3..3e-2,
// three force inputs and three displacement outputs, the first two outputs
// collocated with the first two inputs (the same shapes): a loop closed
// through them by a PD controller is stable.
Path ModalPlant(int modes, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0), shape(-1.0, 1.0);
  auto m = std::make_shared<ModalModel>();
  for (int k = 0; k < modes; ++k) {
    m->f_hz.push_back(std::pow(500.0, unit(rng)));
    m->zeta.push_back(2e-3 * std::pow(15.0, unit(rng)));
  }
  m->phi_in.resize(3, modes);
  m->phi_out.resize(3, modes);
  for (int k = 0; k < modes; ++k)
    for (int i = 0; i < 3; ++i) {
      m->phi_in(i, k) = shape(rng);
      m->phi_out(i, k) = i < 2 ? m->phi_in(i, k) : shape(rng);
    }
  m->input_names = {"f1", "f2", "f3"};
  m->output_names = {"x1", "x2", "x3"};
  Path p;
  p.name = "plant";
  p.modal = m;
  p.system = StateSpace::Gain(Eigen::MatrixXd::Zero(3, 3));
  p.input_names = m->input_names;
  p.output_names = m->output_names;
  p.input_units = {"N", "N", "N"};
  p.output_units = {"m", "m", "m"};
  return p;
}

// Diagonal lead kp (1 + s/w_z)/(1 + s/w_p) on channels 1 and 2, nothing on
// channel 3, from um (converted from the plant's m at the junction) to N,
// f_z = 5 Hz, f_p = 80 Hz, with |K G_11| = 1 at 20 Hz.
Path Controller(const ModalModel& plant) {
  const double wz = kTwoPi * 5.0, wp = kTwoPi * 80.0, wc = kTwoPi * 20.0;
  std::complex<double> g = 0.0;  // G_11(j wc) in m/N
  for (int k = 0; k < plant.modes(); ++k) {
    const double wk = kTwoPi * plant.f_hz[k];
    g += plant.phi_in(0, k) * plant.phi_out(0, k) / std::complex<double>(wk * wk - wc * wc, 2.0 * plant.zeta[k] * wk * wc);
  }
  const std::complex<double> s(0.0, wc);
  const double kp = 1.0 / (std::abs(g) * 1e6 * std::abs((1.0 + s / wz) / (1.0 + s / wp)));  // N/um
  // (1 + s/wz)/(1 + s/wp) = wp/wz + (1 - wp/wz) wp/(s + wp): one state.
  Eigen::MatrixXd a = -wp * Eigen::MatrixXd::Identity(2, 2), b = Eigen::MatrixXd::Zero(2, 3),
                  c = Eigen::MatrixXd::Zero(3, 2), d = Eigen::MatrixXd::Zero(3, 3);
  for (int i = 0; i < 2; ++i) {
    b(i, i) = 1.0;
    c(i, i) = kp * (1.0 - wp / wz) * wp;
    d(i, i) = kp * wp / wz;
  }
  Path k;
  k.name = "controller";
  k.system = StateSpace(a, b, c, d);
  k.input_names = {"e1", "e2", "e3"};
  k.output_names = {"u1", "u2", "u3"};
  k.input_units = {"um", "um", "um"};
  k.output_units = {"N", "N", "N"};
  return k;
}

// The largest relative difference (Frobenius) of H from the diagram and from
// the dense realisation's Hessenberg solve, at and around the damped
// frequency of every pole of the realisation and at a log sweep.
double WorstAgainstRealisation(const Path& p) {
  const FrequencyResponse dense(p.system, FrequencyResponse::Method::kHessenberg);
  std::vector<double> f;
  for (Eigen::Index k = 0; k < dense.poles().size(); ++k) {
    const std::complex<double> pole = dense.poles()(k);
    if (pole.imag() <= 0.0) continue;
    const double zeta = -pole.real() / std::abs(pole);
    for (const double x : {1.0 - zeta, 1.0, 1.0 + zeta}) f.push_back(x * pole.imag() / kTwoPi);
  }
  for (int i = 0; i <= 60; ++i) f.push_back(0.1 * std::pow(1e4, i / 60.0));
  double worst = 0.0;
  for (const double x : f) {
    const Eigen::MatrixXcd want = dense.At(x), got = p.Model().At(x);
    worst = std::max(worst, (got - want).norm() / want.norm());
  }
  return worst;
}

TEST_CASE("a loop closed around a modal path is evaluated from its parts and matches its dense realisation") {
  const Path plant = ModalPlant(60, 7u);
  const Path controller = Controller(*plant.modal);
  const Path loop = FeedbackOfPaths({&plant, "plant"}, {&controller, "controller"});
  REQUIRE(loop.measured != nullptr);  // the diagram
  CHECK(!loop.HasMeasuredData());
  CHECK(loop.SystemApproximates());
  CHECK(loop.system.states() == 2 * 60 + 2);  // the realisation
  CHECK(loop.measured->ModalParts().size() == 1);
  const double worst = WorstAgainstRealisation(loop);
  MESSAGE("loop around 60 modes: H from the parts within " << worst << " of the realisation's Hessenberg solve");
  CHECK(worst <= 1e-9);

  // The loop's own model is the modal plant, not a realisation of it.
  REQUIRE(loop.loops.size() == 1);
  CHECK(loop.loops[0].plant_model->ModalParts().size() == 1);
  CHECK(loop.loops[0].plant_model->RationalParts().empty());

  // A chain with a modal part: plant, then a first-order sensor.
  Path sensor;
  sensor.name = "sensor";
  sensor.system = StateSpace((Eigen::MatrixXd(1, 1) << -kTwoPi * 300.0).finished(),
                             (Eigen::MatrixXd(1, 3) << 1.0, 0.0, 0.0).finished(),
                             (Eigen::MatrixXd(1, 1) << kTwoPi * 300.0).finished(), Eigen::MatrixXd::Zero(1, 3));
  sensor.input_names = {"x1", "x2", "x3"};
  sensor.output_names = {"reading"};
  sensor.input_units = {"m", "m", "m"};
  sensor.output_units = {"nm"};
  const Path chain = SeriesOfPaths({{&plant, "of[0]"}, {&sensor, "of[1]"}});
  REQUIRE(chain.measured != nullptr);
  CHECK(chain.system.states() == 2 * 60 + 1);
  CHECK(WorstAgainstRealisation(chain) <= 1e-9);
}

TEST_CASE("a loop around a modal path: poles, stability and exact variance from its coupled blocks") {
  const Path plant = ModalPlant(120, 11u);
  const Path controller = Controller(*plant.modal);
  const Path loop = FeedbackOfPaths({&plant, "plant"}, {&controller, "controller"});
  const PathAnalysis analysis(loop, {0, 1, 2});
  // 120 mode blocks and the controller's one, coupled through its sensed
  // and actuated channels: no dense reduction (coupled_spectrum.h).
  const std::string form =
      "its parts at each frequency (the modal form of 120 mode(s)); poles of its 242 states from 121 block(s) coupled "
      "at rank 4 (no dense reduction), exact variance in closed form on their eigenvectors (eigenvalue condition up to ";
  CHECK(analysis.ResponseForm().substr(0, form.size()) == form);
  CHECK(analysis.StateSpacePoles().size() == 242);  // for deb check's stability line
  CHECK(analysis.unstable_poles().empty());
  CHECK(analysis.marginal_poles().empty());
  CHECK(analysis.modes().size() >= 120);  // every pair once, the controller's real poles
  // Every pole of the realisation (Eigen's own eigenvalue solver) is among
  // the analysis' modes.
  const Eigen::VectorXcd eig = Eigen::EigenSolver<Eigen::MatrixXd>(loop.system.A()).eigenvalues();
  int pairs = 0;
  double worst_pole = 0.0;
  for (Eigen::Index k = 0; k < eig.size(); ++k) {
    if (eig(k).imag() <= 0.0) continue;
    ++pairs;
    double nearest = HUGE_VAL;
    for (const Mode& m : analysis.modes()) nearest = std::min(nearest, std::abs(m.pole_rad_s - eig(k)));
    worst_pole = std::max(worst_pole, nearest / std::abs(eig(k)));
  }
  CHECK(pairs >= 119);
  CHECK(worst_pole <= 1e-9);

  // H on a grid, on all threads, equals the realisation's.
  std::vector<double> f;
  for (int i = 0; i <= 400; ++i) f.push_back(0.5 * std::pow(2000.0, i / 400.0));
  const FrequencyResponse dense(loop.system, FrequencyResponse::Method::kHessenberg);
  std::vector<double> error(f.size());
  analysis.ForEachResponse(f, [&](std::size_t k, const Eigen::MatrixXcd& h) {
    const Eigen::MatrixXcd want = dense.At(f[k]);
    error[k] = (h - want).norm() / want.norm();
  });
  CHECK(*std::max_element(error.begin(), error.end()) <= 1e-9);

  // The exact variance of each row under white forces: against the whole
  // Bartels-Stewart solve of the same realisation.
  const Eigen::MatrixXd w = Eigen::Vector3d(1.0, 0.5, 2.0).asDiagonal();
  const StateSpace& s = loop.system;
  const Eigen::MatrixXd reference = s.C() * SolveLyapunov(s.A(), s.B() * w * s.B().transpose()) * s.C().transpose();
  double worst = 0.0;
  for (int row = 0; row < 3; ++row)
    worst = std::max(worst, std::abs(analysis.Exact(row, w, nullptr).variance - reference(row, row)) / reference(row, row));
  MESSAGE("loop around 120 modes (" << s.states() << " states): exact variances within " << worst
                                    << " of the whole Bartels-Stewart solve");
  CHECK(worst <= 1e-9);
  // The rows' whole covariance (deb's output covariance), off the diagonal too.
  const Eigen::MatrixXd cov = analysis.ExactCovariance({0, 1, 2}, {nullptr, nullptr, nullptr}, w);
  CHECK((cov - reference).norm() <= 1e-9 * reference.norm());
}

TEST_CASE("a chain of a modal path and measured data takes its poles from the modes") {
  const Path plant = ModalPlant(8, 3u);
  Path frf;
  frf.name = "amplifier";
  frf.measured = std::make_shared<const FrequencyModel>(
      MeasuredResponse({0.1, 1e4}, {Eigen::MatrixXcd::Identity(3, 3) * 2.0, Eigen::MatrixXcd::Identity(3, 3) * 2.0}));
  frf.system = StateSpace::Gain(Eigen::MatrixXd::Zero(3, 3));
  frf.input_names = {"a1", "a2", "a3"};
  frf.output_names = {"b1", "b2", "b3"};
  frf.input_units = {"N", "N", "N"};
  frf.output_units = {"N", "N", "N"};
  const Path chain = SeriesOfPaths({{&frf, "of[0]"}, {&plant, "of[1]"}});
  REQUIRE(chain.HasMeasuredData());
  const PathAnalysis analysis(chain, {0});
  REQUIRE(analysis.modes().size() == 8);
  for (std::size_t k = 0; k < 8; ++k) {
    double nearest = HUGE_VAL;
    for (const double f : plant.modal->f_hz) nearest = std::min(nearest, std::abs(analysis.modes()[k].f_n_hz / f - 1.0));
    CHECK(nearest <= 1e-12);
  }
  // H: 2 (the data, flat) times the modal plant.
  const Eigen::MatrixXcd h = chain.Model().At(3.0), g = plant.Model().At(3.0);
  CHECK((h - 2.0 * g).norm() <= 1e-14 * g.norm());
}

TEST_CASE("a loop of more than 2000 states is kept as its parts: no dense realisation, its figures from coupled blocks") {
  const Path plant = ModalPlant(1001, 5u);
  const Path controller = Controller(*plant.modal);
  const Path loop = FeedbackOfPaths({&plant, "plant"}, {&controller, "controller"});
  REQUIRE(loop.KeptAsParts());
  CHECK(!loop.SystemApproximates());
  CHECK(loop.system.states() == 0);  // only its size
  CHECK(loop.system.inputs() == 3);
  CHECK(loop.States() == 2 * 1001 + 2);
  const PathAnalysis analysis(loop, {0, 1, 2});
  CHECK(analysis.ResponseForm().find("poles of its 2004 states from 1002 block(s) coupled at rank 4 (no dense "
                                     "realisation: more than 2000 states)") != std::string::npos);
  CHECK(analysis.StateSpacePoles().size() == 2004);
  CHECK(analysis.unstable_poles().empty());
  CHECK(analysis.marginal_poles().empty());

  // Against the same loop realised by hand (the junction's m -> um is a
  // gain of 1e6 at the controller's input) and the whole Bartels-Stewart
  // solve: the dense work deb no longer does. A fourth output is x1 through
  // a first-order weighting 100/(s + 100), for the weighted variance.
  const StateSpace& k = controller.system;
  const StateSpace dense = Feedback(ModalStateSpace(*plant.modal), StateSpace(k.A(), 1e6 * k.B(), k.C(), 1e6 * k.D()));
  REQUIRE(dense.states() == 2004);
  const StateSpace weighting((Eigen::MatrixXd(1, 1) << -100.0).finished(), Eigen::MatrixXd::Ones(1, 1),
                             (Eigen::MatrixXd(1, 1) << 100.0).finished(), Eigen::MatrixXd::Zero(1, 1));
  Eigen::MatrixXd fb = Eigen::MatrixXd::Zero(1, 3), fc = Eigen::MatrixXd::Zero(4, 1), fd = Eigen::MatrixXd::Zero(4, 3);
  fb(0, 0) = 1.0;
  fc(3, 0) = 100.0;
  fd.topRows(3).setIdentity();
  const StateSpace weighted = Series(dense, StateSpace(weighting.A(), fb, fc, fd));
  const Eigen::MatrixXd w = Eigen::Vector3d(1.0, 0.5, 2.0).asDiagonal();
  const Eigen::MatrixXd reference = weighted.C() *
                                    SolveLyapunov(weighted.A(), weighted.B() * w * weighted.B().transpose()) *
                                    weighted.C().transpose();
  double worst = 0.0;
  for (int row = 0; row < 3; ++row)
    worst = std::max(worst, std::abs(analysis.Exact(row, w, nullptr).variance - reference(row, row)) / reference(row, row));
  MESSAGE("loop around 1001 modes kept as parts: exact variances within " << worst << " of the whole Bartels-Stewart solve");
  CHECK(worst <= 1e-9);

  // A combined output's variance is the weighted covariance: its cross
  // terms are exact.
  const Path combined = AddCombinedOutput(loop, "x1_minus_x2", {{"x1", 1.0, "1"}, {"x2", -1.0, "1"}});
  REQUIRE(combined.KeptAsParts());
  const PathAnalysis difference(combined, {3});
  const double want = reference(0, 0) + reference(1, 1) - 2.0 * reference(0, 1);
  CHECK(std::abs(difference.Exact(3, w, nullptr).variance - want) <= 1e-9 * want);
  // One input of it: still kept as parts.
  const Path one = SelectPathInputs(loop, {"f3"});
  REQUIRE(one.KeptAsParts());
  CHECK(one.system.inputs() == 1);

  // An output weighting joins the coupled form in series.
  const double weighted_variance = analysis.Exact(0, w, &weighting).variance;
  MESSAGE("its weighted variance within " << std::abs(weighted_variance / reference(3, 3) - 1.0));
  CHECK(std::abs(weighted_variance - reference(3, 3)) <= 1e-9 * reference(3, 3));
}

// The variance of output `row` of a modal path (displacement) through the
// weighting z' = -a z + y, y_w = a z (a / (s + a)), by blocks of the
// series' Lyapunov equation, whose A = [A_x 0; c^T -a] is block lower
// triangular: the modal states' covariance P_kl from each pair of 2 x 2
// mode blocks, A_k P_kl + P_kl A_l^T + B_k W B_l^T = 0 (a 4 x 4 Kronecker
// solve per pair); the coupling to z, (A_k - a I) p_k = -sum_l P_kl c_l;
// and var y_w = a^2 P_zz = a sum_k c_k^T p_k. O(n^2), no 2n-state solve and
// no code of the coupled form.
double WeightedModalVariance(const ModalModel& m, int row, const Eigen::MatrixXd& w, double a) {
  const auto n = static_cast<std::size_t>(m.modes());
  std::vector<Eigen::Matrix2d> blk(n);
  std::vector<Eigen::Vector2d> c(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double wk = kTwoPi * m.f_hz[k];
    blk[k] << 0.0, 1.0, -wk * wk, -2.0 * m.zeta[k] * wk;
    c[k] << m.phi_out(row, static_cast<Eigen::Index>(k)), 0.0;
  }
  double variance = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    Eigen::Vector2d pc = Eigen::Vector2d::Zero();  // sum_l P_kl c_l
    for (std::size_t l = 0; l < n; ++l) {
      // vec(A_k P + P A_l^T) = (I (x) A_k + A_l (x) I) vec(P), column-major;
      // B_k W B_l^T = [0 0; 0 q] with B_k = [0; phi_in(:,k)^T].
      Eigen::Matrix4d op = Eigen::Matrix4d::Zero();
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j)
          for (int r = 0; r < 2; ++r) {
            op(i + 2 * j, r + 2 * j) += blk[k](i, r);
            op(i + 2 * j, i + 2 * r) += blk[l](j, r);
          }
      const double q = m.phi_in.col(static_cast<Eigen::Index>(k)).dot(w * m.phi_in.col(static_cast<Eigen::Index>(l)));
      const Eigen::Vector4d p = op.partialPivLu().solve(Eigen::Vector4d(0.0, 0.0, 0.0, -q));
      pc += Eigen::Map<const Eigen::Matrix2d>(p.data()) * c[l];
    }
    const Eigen::Vector2d pk = (blk[k] - a * Eigen::Matrix2d::Identity()).partialPivLu().solve(-pc);
    variance += a * c[k].dot(pk);
  }
  return variance;
}

TEST_CASE("a weighted output of a modal path of more than 2000 states: the modes as coupled blocks, the weighting in series") {
  const Path plant = ModalPlant(1001, 9u);
  REQUIRE(plant.States() == 2002);
  const PathAnalysis analysis(plant, {0, 2});
  const StateSpace weighting((Eigen::MatrixXd(1, 1) << -100.0).finished(), Eigen::MatrixXd::Ones(1, 1),
                             (Eigen::MatrixXd(1, 1) << 100.0).finished(), Eigen::MatrixXd::Zero(1, 1));
  const Eigen::MatrixXd w = Eigen::Vector3d(1.0, 0.5, 2.0).asDiagonal();
  for (const int row : {0, 2}) {
    CAPTURE(row);
    const double want = WeightedModalVariance(*plant.modal, row, w, 100.0);
    const double got = analysis.Exact(row, w, &weighting).variance;
    MESSAGE("row " << row << ": weighted variance within " << std::abs(got / want - 1.0)
                   << " of the blockwise Lyapunov solve");
    CHECK(std::abs(got - want) <= 1e-9 * want);
  }
  // A weighting that is a gain of 3: nine times the unweighted closed form.
  const StateSpace three = StateSpace::Gain(Eigen::MatrixXd::Constant(1, 1, 3.0));
  const double plain = analysis.Exact(0, w, nullptr).variance;
  CHECK(std::abs(analysis.Exact(0, w, &three).variance - 9.0 * plain) <= 1e-12 * 9.0 * plain);
}

TEST_CASE("a loop kept as parts that its parts cannot solve, or too large to keep, is refused with the reason") {
  const Path plant = ModalPlant(1001, 5u);
  // A controller of 40 states: one block of more than kMaxCoupledBlock.
  Path wide = Controller(*plant.modal);
  Eigen::MatrixXd a = -kTwoPi * 80.0 * Eigen::MatrixXd::Identity(40, 40), b = Eigen::MatrixXd::Zero(40, 3),
                  c = Eigen::MatrixXd::Zero(3, 40);
  for (int i = 0; i < 40; ++i) {
    b(i, i % 2) = 1.0;
    c(i % 2, i) = 1e-3;
  }
  wide.system = StateSpace(a, b, c, Eigen::MatrixXd::Zero(3, 3));
  const Path loop = FeedbackOfPaths({&plant, "plant"}, {&wide, "controller"});
  REQUIRE(loop.KeptAsParts());
  CHECK_THROWS_WITH_AS(PathAnalysis(loop, {0}),
                       doctest::Contains("its 2042 states are more than the 2000 deb realises densely, and its parts "
                                         "do not hold as coupled blocks ("),
                       InputError);

  // Two modal paths of 3001 modes side by side: 12 004 states, more than
  // limits::kMaxCoupledStates (a loop around the largest modal path, 5000
  // modes, fits).
  const Path one = ModalPlant(3001, 1u), other = ModalPlant(3001, 2u);
  CHECK_THROWS_WITH_AS(ParallelOfPaths({{&one, "of[0]"}, {&other, "of[1]"}}),
                       "the combination has 12004 states (2 per mode), more than the 12000 deb keeps as coupled parts",
                       InputError);
}

}  // namespace
}  // namespace deb
