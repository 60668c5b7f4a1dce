#include "deb/systems/frequency_model.h"

#include <doctest/doctest.h>

#include <random>

#include "deb/systems/interconnect.h"
#include "test_util.h"

namespace deb {
namespace {

using testing::Contains;
using testing::MessageOf;
using testing::RelativeError;

// The response of `sys` tabulated at f_hz: a "measurement" with no error.
MeasuredResponse Tabulate(const StateSpace& sys, const std::vector<double>& f_hz) {
  std::vector<Eigen::MatrixXcd> h;
  for (double f : f_hz) h.push_back(testing::DenseResponse(sys, f));
  return MeasuredResponse(f_hz, h);
}

TEST_CASE("series, parallel and feedback of measured blocks equal interconnect.h at the data points") {
  std::mt19937 rng(11);
  const StateSpace g = testing::RandomSystem({{-3.0}, {{20.0, 0.05}, {60.0, 0.2}}}, 2, 2, rng);
  const StateSpace k = testing::RandomSystem({{-40.0}, {{90.0, 0.3}}}, 2, 2, rng, /*with_d=*/true);
  const std::vector<double> f = testing::LogSpace(0.1, 100.0, 61);
  const FrequencyModel gm(Tabulate(g, f)), km(k);  // one measured block, one rational

  const StateSpace series = Series(g, k), parallel = Parallel(g, k), loop = Feedback(g, k, -1), pos = Feedback(g, k, 1);
  const FrequencyModel series_m = FrequencyModel::Series(gm, km), parallel_m = FrequencyModel::Parallel(gm, km),
                       loop_m = FrequencyModel::Feedback(gm, km, -1), pos_m = FrequencyModel::Feedback(gm, km, 1);
  double worst = 0.0;
  for (double fk : f) {
    worst = std::max(worst, RelativeError(series_m.At(fk), testing::DenseResponse(series, fk)));
    worst = std::max(worst, RelativeError(parallel_m.At(fk), testing::DenseResponse(parallel, fk)));
    worst = std::max(worst, RelativeError(loop_m.At(fk), testing::DenseResponse(loop, fk)));
    worst = std::max(worst, RelativeError(pos_m.At(fk), testing::DenseResponse(pos, fk)));
  }
  MESSAGE("largest relative difference: " << worst);
  CHECK(worst < 1e-10);
  CHECK(loop_m.HasLoopAroundData());
  CHECK_FALSE(series_m.HasLoopAroundData());
  CHECK(series_m.RationalParts().size() == 1);
  CHECK(series_m.DataFrequencies() == f);
}

TEST_CASE("ForEach visits every frequency with the response of At") {
  const std::vector<double> f = {1.0, 2.0, 4.0, 8.0};
  std::vector<Eigen::MatrixXcd> h;
  for (double fk : f) h.push_back(Eigen::MatrixXcd::Constant(2, 1, std::complex<double>(fk, -fk)));
  const FrequencyModel m = FrequencyModel(MeasuredResponse(f, h)).SelectOutputs({1});
  const std::vector<double> at = {1.0, 3.0, 8.0};
  std::vector<std::complex<double>> seen(at.size());
  m.ForEach(at, [&](std::size_t k, const Eigen::MatrixXcd& hk) { seen[k] = hk(0, 0); }, 2);
  for (std::size_t k = 0; k < at.size(); ++k) CHECK(seen[k] == m.At(at[k])(0, 0));
  CHECK(seen[0] == std::complex<double>(1.0, -1.0));
}

TEST_CASE("a loop that is singular at a frequency is an error there, and sizes must fit") {
  const std::vector<double> f = {1.0, 10.0};
  const FrequencyModel one(MeasuredResponse(f, {Eigen::MatrixXcd::Ones(1, 1), Eigen::MatrixXcd::Ones(1, 1)}));
  const FrequencyModel unity(StateSpace::Gain(Eigen::MatrixXd::Ones(1, 1)));
  const FrequencyModel loop = FrequencyModel::Feedback(one, unity, +1);  // 1 - G K = 0
  CHECK(Contains(MessageOf([&] { loop.At(3.0); }), "singular at 3 Hz"));
  const FrequencyModel wide(StateSpace::Gain(Eigen::MatrixXd::Ones(2, 2)));
  CHECK(Contains(MessageOf([&] { FrequencyModel::Series(one, wide); }), "2 input(s)"));
  CHECK(Contains(MessageOf([&] { FrequencyModel::Parallel(one, wide); }), "same numbers"));
  CHECK(Contains(MessageOf([&] { FrequencyModel::Feedback(one, unity, 2); }), "sign must be"));
}

}  // namespace
}  // namespace deb
