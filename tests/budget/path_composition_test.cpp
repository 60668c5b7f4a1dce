#include "deb/budget/path_composition.h"

#include <doctest/doctest.h>

#include <complex>
#include <memory>

#include "deb/core/error.h"
#include "deb/systems/transfer_function.h"

namespace deb {
namespace {

using Complex = std::complex<double>;
constexpr double kTwoPi = 2.0 * M_PI;

// A SISO path num/den from `in` to `out` units.
Path Siso(const std::string& name, const TransferFunction& tf, const std::string& in, const std::string& out) {
  Path p;
  p.name = name;
  p.system = ToStateSpace(tf);
  p.input_names = {name + "_in"};
  p.output_names = {name + "_out"};
  p.input_units = {in};
  p.output_units = {out};
  return p;
}

Complex At(const Path& p, double f_hz) { return p.Model().At(f_hz)(0, 0); }
Complex At(const TransferFunction& tf, double f_hz) { return tf.Evaluate(Complex(0.0, kTwoPi * f_hz)); }

// G = 1/(s + 2) from N to um, K = 3/(s + 5) from nm to N.
const TransferFunction kG({1.0}, {1.0, 2.0}), kK({3.0}, {1.0, 5.0});
const std::vector<double> kF = {0.0, 0.1, 1.0, 7.0};

TEST_CASE("a series of paths multiplies their transfers with the unit scale at the junction") {
  const Path g = Siso("g", kG, "N", "um"), k = Siso("k", kK, "nm", "N");
  const Path s = SeriesOfPaths({{&g, "of[0]"}, {&k, "of[1]"}});
  CHECK(s.input_units == std::vector<std::string>{"N"});
  CHECK(s.output_units == std::vector<std::string>{"N"});
  CHECK(s.input_names == std::vector<std::string>{"g_in"});
  CHECK(s.output_names == std::vector<std::string>{"k_out"});
  CHECK(s.measured == nullptr);
  for (double f : kF) CHECK(std::abs(At(s, f) - 1000.0 * At(kK, f) * At(kG, f)) <= 1e-12 * std::abs(At(s, f)));
}

TEST_CASE("a parallel connection adds the transfers, scaled into the first path's units") {
  const Path a = Siso("a", kG, "N", "um"), b = Siso("b", kK, "kN", "nm");
  const Path p = ParallelOfPaths({{&a, ""}, {&b, ""}});
  CHECK(p.output_units == std::vector<std::string>{"um"});
  // N -> kN is 1e-3 at b's input, nm -> um 1e-3 at its output.
  for (double f : kF) CHECK(std::abs(At(p, f) - (At(kG, f) + 1e-6 * At(kK, f))) <= 1e-12 * std::abs(At(p, f)));
}

TEST_CASE("a feedback loop responds as G/(1 + G K) with the controller scaled into the plant's units") {
  const Path g = Siso("g", kG, "N", "um"), k = Siso("k", kK, "nm", "N");
  const Path loop = FeedbackOfPaths({&g, "plant"}, {&k, "controller"});
  CHECK(loop.input_units == std::vector<std::string>{"N"});
  CHECK(loop.output_units == std::vector<std::string>{"um"});
  for (double f : kF) {
    const Complex gk = At(kG, f) * 1000.0 * At(kK, f), expected = At(kG, f) / (1.0 + gk);
    CHECK(std::abs(At(loop, f) - expected) <= 1e-12 * std::abs(expected));
  }
  const Path positive = FeedbackOfPaths({&g, "plant"}, {&k, "controller"}, +1);
  const Complex gk = At(kG, 1.0) * 1000.0 * At(kK, 1.0);
  CHECK(std::abs(At(positive, 1.0) - At(kG, 1.0) / (1.0 - gk)) <= 1e-12 * std::abs(At(positive, 1.0)));
}

TEST_CASE("a part with measured data makes the composition a diagram evaluated per frequency") {
  const Path g = Siso("g", kG, "N", "um");
  Path m = Siso("m", TransferFunction({1.0}, {1.0}), "um", "um");
  m.measured = std::make_shared<const FrequencyModel>(MeasuredResponse(
      {0.5, 2.0}, {Eigen::MatrixXcd::Constant(1, 1, 4.0), Eigen::MatrixXcd::Constant(1, 1, 4.0)}));
  const Path s = SeriesOfPaths({{&g, "a"}, {&m, "b"}});
  REQUIRE(s.measured != nullptr);
  CHECK(s.system.states() == 0);
  CHECK(std::abs(At(s, 1.0) - 4.0 * At(kG, 1.0)) <= 1e-12 * std::abs(At(s, 1.0)));
}

TEST_CASE("composition errors name the part's key path, the values and the rule") {
  const Path g = Siso("g", kG, "N", "um"), v = Siso("v", kK, "um/s", "N");
  const Path two = Siso("two", kK, "um", "N");
  Path wide = two;
  wide.system = StateSpace::Gain(Eigen::MatrixXd::Ones(1, 2));
  wide.input_names = {"a", "b"};
  wide.input_units = {"um", "um"};
  try {
    SeriesOfPaths({{&g, "paths[2].of[0]"}, {&v, "paths[2].of[1]"}});
    FAIL("a junction from um to um/s must be refused");
  } catch (const InputError& e) {
    CHECK(e.key_path() == "paths[2].of[1]");
    CHECK(e.message() ==
          "series: channel 1 carries 'um' into 'um/s', which differ by a time derivative; insert the derivative "
          "explicitly");
  }
  try {
    SeriesOfPaths({{&g, "of[0]"}, {&wide, "of[1]"}});
    FAIL("a size mismatch must be refused");
  } catch (const InputError& e) {
    CHECK(e.key_path() == "of[1]");
    CHECK(e.message() == "path 'two' has 2 input(s) but follows 1 output(s)");
  }
  CHECK_THROWS_WITH_AS(ParallelOfPaths({{&g, "of[0]"}}), "list at least two paths", InputError);
  CHECK_THROWS_WITH_AS(ParallelOfPaths({{&g, "of[0]"}, {&wide, "of[1]"}}),
                       "of[1]: parallel paths must have the same numbers of inputs and outputs", InputError);
  CHECK_THROWS_WITH_AS(FeedbackOfPaths({&g, "plant"}, {&wide, "controller"}),
                       "controller: controller 'two' must have 1 input(s) and 1 output(s) to close a loop around 'g'",
                       InputError);
  CHECK_THROWS_WITH_AS(FeedbackOfPaths({&g, "plant"}, {&two, "controller"}, 0),
                       "sign must be -1 (negative feedback) or +1, got 0", InputError);
}

}  // namespace
TEST_CASE("selecting inputs keeps those columns of H, in the order named, for rational, modal and measured paths") {
  // A 2-output, 3-input state space; the selection [u3, u1] is H(:, [2, 0]) at every frequency.
  Eigen::MatrixXd a(2, 2), b(2, 3), c(2, 2), d(2, 3);
  a << -1, 2, -3, -4;
  b << 1, 0, 2, 0, 1, -1;
  c << 1, 1, 0, 2;
  d << 0, 0.5, 0, 0, 0, 0.25;
  Path p;
  p.name = "plant";
  p.system = StateSpace(a, b, c, d);
  p.input_names = {"u1", "u2", "u3"};
  p.input_units = {"N", "V", "nm"};
  p.output_names = {"y1", "y2"};
  p.output_units = {"um", "um"};
  const Path sel = SelectPathInputs(p, {"u3", "u1"});
  CHECK(sel.input_names == std::vector<std::string>{"u3", "u1"});
  CHECK(sel.input_units == std::vector<std::string>{"nm", "N"});
  CHECK(sel.system.states() == 2);
  for (double f : kF) {
    const Eigen::MatrixXcd h = p.Model().At(f), hs = sel.Model().At(f);
    REQUIRE(hs.cols() == 2);
    CHECK((hs.col(0) - h.col(2)).norm() <= 1e-15 * (1 + h.norm()));
    CHECK((hs.col(1) - h.col(0)).norm() <= 1e-15 * (1 + h.norm()));
  }
  // Measured: the same columns of the data.
  Path m = p;
  Eigen::MatrixXcd h0(2, 3), h1(2, 3);
  h0 << 1, 2, 3, 4, 5, 6;
  h1 << Complex(1, 1), 2, Complex(0, 3), 4, Complex(5, -1), 6;
  m.measured = std::make_shared<const FrequencyModel>(MeasuredResponse({0.5, 2.0}, {h0, h1}));
  m.system = StateSpace::Gain(Eigen::MatrixXd::Zero(2, 3));
  const Path ms = SelectPathInputs(m, {"u2"});
  REQUIRE(ms.measured != nullptr);
  CHECK((ms.measured->At(2.0).col(0) - h1.col(1)).norm() == 0.0);
  CHECK(ms.system.inputs() == 1);
  // Modal: the rows of the input shapes, and H is the modal sum over those inputs only.
  auto modal = std::make_shared<ModalModel>();
  modal->f_hz = {3.0, 11.0};
  modal->zeta = {0.02, 0.01};
  modal->phi_in = (Eigen::MatrixXd(3, 2) << 1, 0.5, -0.2, 2, 0.7, -1).finished();
  modal->phi_out = (Eigen::MatrixXd(2, 2) << 1, 1, 0.3, -0.4).finished();
  modal->input_names = {"u1", "u2", "u3"};
  modal->output_names = {"y1", "y2"};
  Path q = p;
  q.modal = modal;
  q.system = StateSpace::Gain(Eigen::MatrixXd::Zero(2, 3));
  const Path qs = SelectPathInputs(q, {"u2"});
  REQUIRE(qs.modal != nullptr);
  CHECK(qs.modal->phi_in.rows() == 1);
  CHECK(qs.modal->phi_in(0, 1) == 2.0);
  for (double f : {0.5, 3.0, 20.0}) {
    const Eigen::MatrixXcd h = q.Model().At(f), hs = qs.Model().At(f);
    CHECK((hs.col(0) - h.col(1)).norm() <= 1e-13 * h.norm());
  }
  // Unknown, repeated or no names are refused with the path's inputs.
  try {
    SelectPathInputs(p, {"u4"});
    FAIL("no error");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("path 'plant' has no input 'u4' (did you mean 'u1'?") != std::string::npos);
    CHECK(std::string(e.what()).find("(its inputs: u1, u2, u3)") != std::string::npos);
  }
  CHECK_THROWS_AS(SelectPathInputs(p, {"u1", "u1"}), InputError);
  CHECK_THROWS_AS(SelectPathInputs(p, {}), InputError);
}

}  // namespace deb
