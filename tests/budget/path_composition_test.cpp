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
}  // namespace deb
