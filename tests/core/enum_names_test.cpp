#include "deb/core/enum_names.h"

#include <doctest/doctest.h>

#include <set>
#include <string>

#include "deb/budget/budget.h"
#include "deb/budget/output_metric.h"
#include "deb/budget/sweep.h"
#include "deb/core/extrapolation.h"
#include "deb/models/isolation_model.h"
#include "deb/models/isolation_system.h"
#include "deb/report/figure/report_options.h"
#include "deb/signal/frf_estimate.h"
#include "deb/signal/spectral_estimate.h"
#include "deb/signal/time_series_file.h"
#include "deb/signal/window.h"
#include "deb/spectra/building_criteria.h"
#include "deb/spectra/measured_spectrum.h"
#include "deb/spectra/peterson_noise_model.h"
#include "deb/spectra/spectrum_csv.h"
#include "deb/spectra/third_octave.h"
#include "deb/spectra/vc_curve.h"
#include "deb/systems/modal_model.h"

// Only the headers' tables and inline functions are used here: test_core
// links deb_core alone.
namespace deb {
namespace {

std::string MessageOf(void (*f)()) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no InputError)";
}

enum class Colour { kRed, kGreen, kBlue };
constexpr EnumName<Colour> kColourNames[] = {
    {Colour::kRed, "red"}, {Colour::kGreen, "green"}, {Colour::kBlue, "blue"}, {Colour::kGreen, "verde", kAlias}};
constexpr EnumNames<Colour> NamesOf(Colour) { return kColourNames; }

}  // namespace

#define DEB_NAMED_ENUMS                                                                                        \
  Extrapolation, WindowKind, FrfEstimator, Detrend, Averaging, RawSampleFormat, ThirdOctaveSeries,             \
      PetersonModel, VcClass, CriteriaSet, SpectrumInterpolation, SpectrumQuantity, SpectrumSides, PlotFormat, \
      ModalQuantity, SweepMode, GridKind, ExactVariance, MetricType, BodyAxis, LocalAxis, IsolationModel::Loop, \
      IsolationModel::Outputs

TEST_CASE_TEMPLATE("every name of a converted enum parses to its value and each value writes its first name", T,
                   DEB_NAMED_ENUMS) {
  std::set<std::string> written;
  int entries = 0;
  for (const EnumName<T>& n : NameTableOf<T>()) {
    ++entries;
    CHECK(ParseEnum<T>(n.name, "setting") == n.value);
    if (!n.alias) {
      CHECK(ToString(n.value) == n.name);     // the first name of a value is the one written
      CHECK(written.insert(n.name).second);   // and no two values share it
    }
    CHECK(ParseEnum<T>(ToString(n.value), "setting") == n.value);
  }
  CHECK(entries >= 2);
  CHECK(written.size() >= 2);
}

TEST_CASE_TEMPLATE("an unknown name of a converted enum is refused with every allowed name listed", T,
                   DEB_NAMED_ENUMS) {
  std::string message;
  try {
    ParseEnum<T>("no-such-name", "setting");
  } catch (const InputError& e) {
    message = e.what();
    CHECK(e.key_path().empty());
  }
  CHECK(message.rfind("unknown setting 'no-such-name'; allowed: ", 0) == 0);
  for (const EnumName<T>& n : NameTableOf<T>()) CHECK(message.find(n.name) != std::string::npos);
}

TEST_CASE("the allowed names come from the table, aliases last in parentheses") {
  CHECK(AllowedNames<Colour>() == "red, green, blue (or verde)");
  CHECK(AllowedNames<Extrapolation>() == "error, zero, hold");
  CHECK(AllowedNames<WindowKind>() == "rectangular, hann, hamming, blackman_harris, flattop (or boxcar, hanning)");
  CHECK(AllowedNames<RawSampleFormat>() == "float32, float64 (or f32, f64)");
}

TEST_CASE("an alias parses to its value but the value writes its own name") {
  CHECK(ParseEnum<Colour>("verde", "colour") == Colour::kGreen);
  CHECK(ToString(Colour::kGreen) == "green");
  CHECK(ParseWindowKind("hanning") == WindowKind::kHann);
  CHECK(ToString(WindowKind::kHann) == "hann");
  CHECK(ParseDetrend("constant") == Detrend::kMean);
  CHECK(ToString(Detrend::kMean) == "mean");
}

TEST_CASE("names match exactly unless the table ignores letter case") {
  CHECK_THROWS_WITH_AS(ParseEnum<Colour>("Red", "colour"), "unknown colour 'Red'; allowed: red, green, blue (or verde)",
                       InputError);
  CHECK_THROWS_AS(ParseWindowKind("Hann"), InputError);
  CHECK(ParseVcClass("vc-d") == VcClass::kD);
  CHECK(ParsePetersonModel("NhNm") == PetersonModel::kHigh);
  CHECK(ToString(PetersonModel::kHigh) == "nhnm");
  // The message quotes the text as written, not as compared.
  CHECK(MessageOf([] { ParseVcClass("vc-h"); }) ==
        "unknown vibration criterion 'vc-h'; allowed: VC-A, VC-B, VC-C, VC-D, VC-E, VC-F, VC-G");
}

TEST_CASE("a key path given to the parser is carried by the error") {
  try {
    ParseEnum<Colour>("mauve", "colour", "sources[2].colour");
    FAIL("no InputError");
  } catch (const InputError& e) {
    CHECK(e.key_path() == "sources[2].colour");
    CHECK(e.message() == "unknown colour 'mauve'; allowed: red, green, blue (or verde)");
    CHECK(std::string(e.what()) == "sources[2].colour: unknown colour 'mauve'; allowed: red, green, blue (or verde)");
  }
}

TEST_CASE("the parsers of the layers name their setting in one wording") {
  CHECK(MessageOf([] { ParseExtrapolation("clamp"); }) == "unknown extrapolation 'clamp'; allowed: error, zero, hold");
  CHECK(MessageOf([] { ParseWindowKind("kaiser"); }) ==
        "unknown window 'kaiser'; allowed: rectangular, hann, hamming, blackman_harris, flattop (or boxcar, hanning)");
  CHECK(MessageOf([] { ParseRawSampleFormat("int16"); }) ==
        "unknown raw sample format 'int16'; allowed: float32, float64 (or f32, f64)");
  CHECK(MessageOf([] { ParseDetrend("quadratic"); }) ==
        "unknown detrend 'quadratic'; allowed: none, mean, linear (or constant)");
  CHECK(MessageOf([] { ParseAveraging("mode"); }) == "unknown averaging 'mode'; allowed: mean, median");
  CHECK(MessageOf([] { ParseSpectrumSides("three"); }) == "unknown spectrum sides 'three'; allowed: one, two");
  CHECK(MessageOf([] { ParseSweepMode("cartesian"); }) == "unknown sweep mode 'cartesian'; allowed: grid, zip");
  CHECK(MessageOf([] { ParseGridKind("octave"); }) ==
        "unknown grid type 'octave'; allowed: auto, log, linear, explicit");
  CHECK(MessageOf([] { ParseExactVariance("yes"); }) ==
        "unknown exact-variance mode 'yes'; allowed: auto, required, off");
  CHECK(MessageOf([] { ParseMetricType("mean"); }) ==
        "unknown metric type 'mean'; allowed: moving_average, moving_std");
  CHECK(MessageOf([] { ParseCriteriaSet("din"); }) == "unknown criteria set 'din'; allowed: vc, iso, all");
  CHECK(MessageOf([] { ParsePlotFormat("gif"); }) == "unknown plot format 'gif'; allowed: png, pdf, svg");
}

}  // namespace deb
