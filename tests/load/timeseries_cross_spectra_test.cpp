// Multi-channel `type: timeseries` sources keep the Welch cross-spectral
// matrix (cross_spectra: full, the default), so coherent channels add in
// amplitude and delayed copies interfere; cross_spectra: none treats the
// channels as independent.
#include <doctest/doctest.h>

#include <cmath>
#include <complex>
#include <filesystem>
#include <fstream>
#include <random>
#include <unistd.h>

#include "deb/budget/engine.h"
#include "deb/core/error.h"
#include "deb/load/budget_yaml.h"
#include "tests/support/text_edit.h"

namespace deb {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A directory holding rec.csv: two columns a, b of unit-variance white noise
// (fixed seed), b = a, b independent of a, or b = a delayed by `delay` samples.
enum class Relation { kCopy, kIndependent, kDelayed };

class Recording {
 public:
  Recording(Relation relation, double rate_hz, int samples, int delay = 0, const std::string& unit = "um/s")
      : dir_(std::filesystem::temp_directory_path() /
             ("deb_ts_csd_" + std::to_string(::getpid()) + "_" + std::to_string(static_cast<int>(relation)))) {
    std::filesystem::create_directories(dir_);
    std::mt19937_64 rng(20240611);
    std::normal_distribution<double> normal(0.0, 1.0);
    std::vector<double> x(static_cast<std::size_t>(samples + delay));
    for (double& v : x) v = normal(rng);
    std::ofstream out(dir_ / "rec.csv");
    out.precision(17);
    out << "# rate_hz: " << rate_hz << "\n# unit: " << unit << "\na, b\n";
    for (int n = 0; n < samples; ++n) {
      const double a = x[static_cast<std::size_t>(n + delay)];
      double b = a;
      if (relation == Relation::kIndependent) b = normal(rng);
      if (relation == Relation::kDelayed) b = x[static_cast<std::size_t>(n)];  // b[n] = a[n - delay]
      out << a << ", " << b << "\n";
    }
  }
  ~Recording() { std::filesystem::remove_all(dir_); }
  std::string path() const { return dir_.string(); }

 private:
  std::filesystem::path dir_;
};

using test::Replace;

// One path, three rows: y_sum = a + b, y_a = a, y_diff = a - b.
const char* kSumBudget = R"(name: pair
grid: {type: log, min_hz: 1, max_hz: 100, points: 400}
sources:
  - name: rec
    unit: um/s
    spectrum:
      type: timeseries
      file: rec.csv
      segment_length: 1024
paths:
  - name: mix
    type: gain
    gain: [[1, 1], [1, 0], [1, -1]]
    input_unit: um/s
    output_unit: um/s
    outputs: [sum, a, diff]
contributors:
  - {name: rec, source: rec, path: mix}
outputs:
  - {name: sum, signal: sum, unit: um/s}
  - {name: a, signal: a, unit: um/s}
  - {name: diff, signal: diff, unit: um/s}
)";

struct Variances {
  double sum, a, diff;
};

Variances Evaluate(const std::string& text, const std::string& dir) {
  const BudgetResult r = Evaluate(LoadBudgetText(text, "b.yaml", dir));
  return {r.outputs[0].variance, r.outputs[1].variance, r.outputs[2].variance};
}

const std::string kNone = "segment_length: 1024\n      cross_spectra: none";

// Statistical tolerance of a variance ratio for independent channels: over
// B = 99 Hz of a T = 163.84 s record, a band power has relative variance
// 1/(B T) and a band cross-power 1/(2 B T) of the auto power, so
// var(1 + S_bb/S_aa + 2 Re S_ab/S_aa) ~ 2/(B T) + 4/(2 B T) = 4/(B T):
// sigma ~ 0.016 (Hann with 50 % overlap keeps nearly all of it). 5 sigma:
constexpr double kRatioTolerance = 0.08;

TEST_CASE("two fully coherent channels add in amplitude with cross-spectra (4x) and in power without (2x)") {
  const Recording rec(Relation::kCopy, 400.0, 1 << 16);
  const Variances full = Evaluate(kSumBudget, rec.path());
  MESSAGE("coherent, full: var(a) = " << full.a << ", var(a+b)/var(a) = " << full.sum / full.a
                                      << ", var(a-b)/var(a) = " << full.diff / full.a);
  // White, unit variance, one-sided 2/fs over 1-100 Hz: 0.495.
  CHECK(full.a == doctest::Approx(0.495).epsilon(0.05));
  CHECK(full.sum / full.a == doctest::Approx(4.0).epsilon(1e-9));
  CHECK(full.diff / full.a <= 1e-9);

  const Variances none = Evaluate(Replace(kSumBudget, "segment_length: 1024", kNone), rec.path());
  MESSAGE("coherent, none: var(a+b)/var(a) = " << none.sum / none.a << ", var(a-b)/var(a) = " << none.diff / none.a);
  CHECK(none.a == doctest::Approx(full.a).epsilon(1e-12));
  CHECK(none.sum / none.a == doctest::Approx(2.0).epsilon(1e-9));
  CHECK(none.diff / none.a == doctest::Approx(2.0).epsilon(1e-9));

  const Budget b = LoadBudgetText(kSumBudget, "b.yaml", rec.path());
  CHECK_FALSE(b.sources[0].spectrum->IsDiagonal());
  CHECK(b.sources[0].spectrum->Describe().find("cross-spectral 'Welch estimate (hann, 1024 samples") == 0);
  CHECK(LoadBudgetText(Replace(kSumBudget, "segment_length: 1024", kNone), "b.yaml", rec.path())
            .sources[0].spectrum->IsDiagonal());
}

TEST_CASE("two independent channels add in power with or without cross-spectra (2x within Welch statistics)") {
  const Recording rec(Relation::kIndependent, 400.0, 1 << 16);
  const Variances full = Evaluate(kSumBudget, rec.path());
  const Variances none = Evaluate(Replace(kSumBudget, "segment_length: 1024", kNone), rec.path());
  MESSAGE("independent, full: var(a+b)/var(a) = " << full.sum / full.a << ", var(a-b)/var(a) = " << full.diff / full.a
                                                  << "; none: " << none.sum / none.a);
  CHECK(std::abs(full.sum / full.a - 2.0) <= kRatioTolerance);
  CHECK(std::abs(full.diff / full.a - 2.0) <= kRatioTolerance);
  CHECK(std::abs(none.sum / none.a - 2.0) <= kRatioTolerance);
  // The cross term is all that separates a + b from a - b; without it they agree.
  CHECK(none.sum == doctest::Approx(none.diff).epsilon(1e-12));
  // Point by point (the CPS integrates power laws between grid points, so
  // integrals of sums differ from sums of integrals at 1e-4).
  const BudgetResult rf = Evaluate(LoadBudgetText(kSumBudget, "b.yaml", rec.path()));
  const BudgetResult rn = Evaluate(LoadBudgetText(Replace(kSumBudget, "segment_length: 1024", kNone), "b.yaml", rec.path()));
  for (std::size_t k = 0; k < rf.grid.size(); ++k)
    CHECK(rf.outputs[0].total_psd[k] + rf.outputs[2].total_psd[k] ==
          doctest::Approx(2.0 * rn.outputs[0].total_psd[k]).epsilon(1e-12));
}

// b lags a by 4 samples at 1 kHz (tau = 4 ms); explicit grid on Welch bins
// (fs / 1024 = 0.9765625 Hz): 31.25, 62.5, 125, 250 Hz. Rows: a; a - b;
// b - A a with A(s) = (1 - s T)/(1 + s T), T = tau / 2 (Pade delay).
const char* kDelayBudget = R"(name: delayed
grid: {type: explicit, f_hz: [31.25, 62.5, 125, 250]}
sources:
  - name: rec
    unit: um/s
    spectrum: {type: timeseries, file: rec.csv, segment_length: 1024}
paths:
  - name: mix
    type: transfer_function
    matrix:
      - [{num: [1], den: [1]}, {num: [0], den: [1]}]
      - [{num: [1], den: [1]}, {num: [-1], den: [1]}]
      - [{num: [0.002, -1], den: [0.002, 1]}, {num: [1], den: [1]}]
    input_unit: um/s
    output_unit: um/s
    outputs: [a, diff, align]
contributors:
  - {name: rec, source: rec, path: mix}
outputs:
  - {name: a, signal: a, unit: um/s}
  - {name: diff, signal: diff, unit: um/s}
  - {name: align, signal: align, unit: um/s}
)";

TEST_CASE("a delayed copy differenced gives |1 - e^{-j2 pi f tau}|^2 S_aa, and the phase of S_ab is +2 pi f tau") {
  const double tau = 0.004, t = tau / 2;
  // File in m/s, budget in um/s: the matrix is scaled as a whole.
  const Recording rec(Relation::kDelayed, 1000.0, 1 << 16, 4, "m/s");
  const Budget budget = LoadBudgetText(kDelayBudget, "b.yaml", rec.path());
  const BudgetResult r = Evaluate(budget);
  const std::vector<double> f_hz = {31.25, 62.5, 125.0, 250.0};
  for (std::size_t k = 0; k < f_hz.size(); ++k) {
    const double f = f_hz[k], w = 2.0 * kPi * f;
    CAPTURE(f);
    const double saa = r.outputs[0].total_psd[k];
    CHECK(saa == doctest::Approx(2e12 / 1000.0).epsilon(0.3));  // white 2 sigma^2/fs, (um/s)^2/Hz, one bin
    const double diff = r.outputs[1].total_psd[k] / saa;
    const double expected_diff = std::norm(1.0 - std::polar(1.0, -w * tau));  // 4 sin^2(pi f tau)
    const std::complex<double> a_of_s = (1.0 - std::complex<double>(0.0, w * t)) / (1.0 + std::complex<double>(0.0, w * t));
    const double align = r.outputs[2].total_psd[k] / saa;
    const double expected_align = std::norm(std::polar(1.0, -w * tau) - a_of_s);
    const double conjugated_align = std::norm(std::polar(1.0, w * tau) - a_of_s);  // the other orientation
    MESSAGE("f = " << f << " Hz: diff/S_aa = " << diff << " (expected " << expected_diff << "), align/S_aa = " << align
                   << " (expected " << expected_align << ", the conjugate orientation would give " << conjugated_align
                   << ")");
    // Welch bias of a delayed copy: a segment of b holds tau/segment = 0.4 %
    // of samples not in a's, mostly under the window's tails (measured
    // within 2.2e-3 of S_aa).
    CHECK(std::abs(diff - expected_diff) <= 5e-3);
    CHECK(std::abs(align - expected_align) <= 5e-3);
    // Where e^{j 2 pi f tau} is not real the two orientations differ by far more.
    if (std::abs(std::sin(w * tau)) > 0.5) CHECK(std::abs(align - conjugated_align) > 1.0);

    const Eigen::MatrixXcd s = budget.sources[0].spectrum->Csd(f);
    if (f < 100.0) CHECK(std::arg(s(0, 1)) == doctest::Approx(std::remainder(w * tau, 2 * kPi)).epsilon(1e-3));
    CHECK(std::abs(s(0, 1)) == doctest::Approx(s(0, 0).real()).epsilon(1e-3));
  }
}

std::string ErrorOf(const std::string& text, const std::string& dir) {
  return test::InputErrorOf([&] { LoadBudgetText(text, "b.yaml", dir); });
}

TEST_CASE("cross_spectra accepts full or none; median averaging and a correlation conflict with full cross-spectra") {
  const Recording rec(Relation::kIndependent, 400.0, 1 << 12);
  CHECK(ErrorOf(Replace(kSumBudget, "segment_length: 1024", "segment_length: 1024\n      cross_spectra: maybe"),
                rec.path()) ==
        "b.yaml:10:22: sources[0].spectrum.cross_spectra: unknown cross_spectra 'maybe'; allowed: full, none");
  CHECK(ErrorOf(Replace(kSumBudget, "segment_length: 1024", "segment_length: 1024\n      cross_spectra: full"),
                rec.path()) == "(no error)");

  const std::string median =
      ErrorOf(Replace(kSumBudget, "segment_length: 1024", "segment_length: 1024\n      averaging: median"), rec.path());
  CHECK(median.find("b.yaml:10:18: sources[0].spectrum.averaging: median averaging does not give a positive "
                    "semi-definite cross-spectral matrix") == 0);
  CHECK(median.find("cross_spectra: none") != std::string::npos);
  CHECK(ErrorOf(Replace(kSumBudget, "segment_length: 1024", kNone + "\n      averaging: median"), rec.path()) ==
        "(no error)");

  const std::string correlated =
      ErrorOf(Replace(kSumBudget, "      segment_length: 1024\n", "      segment_length: 1024\n    correlation: 0.5\n"),
              rec.path());
  CHECK(correlated.find("b.yaml:10:18: sources[0].correlation: the recording's cross-spectra already give") == 0);
  CHECK(ErrorOf(Replace(kSumBudget, "      segment_length: 1024\n",
                        "      segment_length: 1024\n      cross_spectra: none\n    correlation: 0.5\n"),
                rec.path()) == "(no error)");
}

}  // namespace
}  // namespace deb
