// deb/results/result_store.h: a result written to result.h5 and read back is the
// same result. Four shipped budgets together use every part of the schema
// (groups, a measured reference, band requirements and metrics: the wafer
// stage; channel breakdown, a weighting and the output covariance: the
// thesis; tones: the measured stage; modal paths and their top modes: the
// metrology frame). The strongest check is that the result read back,
// written again, gives the same file byte for byte: a field the reader
// dropped or changed would change the file. The figures a report shows are
// also compared one by one, exactly (HDF5 keeps the doubles as written).
// A store a reader must refuse (not HDF5, another schema, a newer version,
// a PSD of the wrong length, an index out of range) gives an InputError
// naming the file and the object.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <string>
#include <unistd.h>
#include <vector>

#include "deb/budget/engine.h"
#include "deb/budget/response_traces.h"
#include "deb/core/error.h"
#include "deb/load/budget_yaml.h"
#include "deb/formats/hdf5_file.h"
#include "deb/results/result_store.h"
#include "tests/support/contains.h"

namespace deb {
namespace {

namespace fs = std::filesystem;
using test::Contains;

class StoreDir {
 public:
  StoreDir() : dir_(fs::temp_directory_path() / ("deb_store_" + std::to_string(::getpid()))) {
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  ~StoreDir() { fs::remove_all(dir_); }
  std::string File(const std::string& name) const { return (dir_ / name).string(); }

 private:
  fs::path dir_;
};

std::string Bytes(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string Budget(const std::string& name) { return std::string(DEB_SOURCE_DIR) + "/budgets/" + name; }

struct Written {
  BudgetResult result;
  RunInfo info;
};

Written WriteStore(const std::string& budget_file, const std::string& store) {
  Written w{Evaluate(LoadBudgetFile(budget_file)), {}};
  w.info.budget_file = budget_file;
  w.info.budget_text = "name: the text of the budget file, kept as it was read\n";
  w.info.budget_sha256 = std::string(64, 'a');
  w.info.seconds = 0.25;
  WriteResultStore(w.result, w.info, store);
  return w;
}

std::string ErrorOf(const std::string& store) {
  try {
    ReadResultStore(store);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST_CASE("a result store read back and written again is the same file, for every shipped feature") {
  const StoreDir dir;
  for (const char* name : {"wafer_stage.yaml", "nizamoglu2015_h210.yaml", "measured_stage.yaml",
                           "metrology_frame.yaml"}) {
    CAPTURE(name);
    const std::string first = dir.File("first.h5"), second = dir.File("second.h5");
    const Written w = WriteStore(Budget(name), first);
    RunInfo info;
    const BudgetResult s = ReadResultStore(first, &info);
    WriteResultStore(s, info, second);
    const std::string a = Bytes(first), b = Bytes(second);
    CHECK(a.size() > 1000);
    const bool same_bytes = a == b;
    CHECK(same_bytes);

    // What the report reads, exactly.
    CHECK(info.budget_file == w.info.budget_file);
    CHECK(*info.budget_text == *w.info.budget_text);
    CHECK(info.budget_sha256 == w.info.budget_sha256);
    CHECK(*info.seconds == 0.25);
    CHECK(s.outline.name == w.result.outline.name);
    CHECK(s.outline.description == w.result.outline.description);
    CHECK(s.outline.grid_kind == w.result.outline.grid_kind);
    CHECK(s.outline.bands.size() == w.result.outline.bands.size());
    CHECK(s.outline.covariance == w.result.outline.covariance);
    REQUIRE(s.outline.sources.size() == w.result.outline.sources.size());
    for (std::size_t i = 0; i < s.outline.sources.size(); ++i) {
      CHECK(s.outline.sources[i].name == w.result.outline.sources[i].name);
      CHECK(s.outline.sources[i].unit == w.result.outline.sources[i].unit);
      CHECK(s.outline.sources[i].channels == w.result.outline.sources[i].channels);
    }
    REQUIRE(s.outline.contributors.size() == w.result.outline.contributors.size());
    for (std::size_t i = 0; i < s.outline.contributors.size(); ++i) {
      CHECK(s.outline.contributors[i].name == w.result.outline.contributors[i].name);
      CHECK(s.outline.contributors[i].exact == w.result.outline.contributors[i].exact);
      CHECK(s.outline.contributors[i].breakdown_channels == w.result.outline.contributors[i].breakdown_channels);
    }
    REQUIRE(s.outline.outputs.size() == w.result.outline.outputs.size());
    CHECK(s.grid.f_hz() == w.result.grid.f_hz());
    CHECK(s.grid.panel_starts() == w.result.grid.panel_starts());
    CHECK(s.warnings == w.result.warnings);
    REQUIRE(s.outputs.size() == w.result.outputs.size());
    for (std::size_t o = 0; o < w.result.outputs.size(); ++o) {
      const OutputResult &x = w.result.outputs[o], &y = s.outputs[o];
      CHECK(y.name == x.name);
      CHECK(y.unit == x.unit);
      CHECK(y.total_psd == x.total_psd);
      CHECK(y.total_cps == x.total_cps);
      CHECK(y.variance == x.variance);
      CHECK(y.rms_max == x.rms_max);
      CHECK(y.metric.has_value() == x.metric.has_value());
      CHECK(y.band_requirements.size() == x.band_requirements.size());
      CHECK(y.references.size() == x.references.size());
      CHECK(s.outline.outputs[o].weighting.has_value() == w.result.outline.outputs[o].weighting.has_value());
      CHECK(s.outline.outputs[o].combination.size() == w.result.outline.outputs[o].combination.size());
      REQUIRE(y.contributors.size() == x.contributors.size());
      for (std::size_t c = 0; c < x.contributors.size(); ++c) {
        const ContributorResult &cx = x.contributors[c], &cy = y.contributors[c];
        CHECK(cy.psd == cx.psd);
        CHECK(cy.cps == cx.cps);
        CHECK(cy.exact_variance == cx.exact_variance);
        CHECK(cy.tones.size() == cx.tones.size());
        CHECK(cy.channels.size() == cx.channels.size());
        CHECK(cy.top_modes.size() == cx.top_modes.size());
        CHECK(cy.group == cx.group);
        const PathResponse &px = w.result.traces->paths[c][o], &py = s.traces->paths[c][o];
        CHECK(py.gain2 == px.gain2);
        CHECK(py.phase_rad == px.phase_rad);
      }
    }
    REQUIRE(s.loops.size() == w.result.loops.size());
    for (std::size_t l = 0; l < s.loops.size(); ++l) {
      CHECK(s.loops[l].paths == w.result.loops[l].paths);
      REQUIRE(s.loops[l].same_loop.size() == w.result.loops[l].same_loop.size());
      for (std::size_t k = 0; k < s.loops[l].same_loop.size(); ++k) {
        CHECK(s.loops[l].same_loop[k].plant == w.result.loops[l].same_loop[k].plant);
        CHECK(s.loops[l].same_loop[k].controller == w.result.loops[l].same_loop[k].controller);
        CHECK(s.loops[l].same_loop[k].sign == w.result.loops[l].same_loop[k].sign);
      }
    }
    CHECK(s.traces->poles_hz == w.result.traces->poles_hz);
    REQUIRE(s.covariance.has_value() == w.result.covariance.has_value());
    if (w.result.covariance) {
      CHECK(s.covariance->matrix == w.result.covariance->matrix);
      CHECK(s.covariance->exact_matrix.has_value() == w.result.covariance->exact_matrix.has_value());
    }
  }
}

TEST_CASE("a store of schema version 1 (uncompressed, every response in full) is still read, and written as version 2") {
  // Written by deb 0.1.0 before version 2, from budgets/guide/feedback_loop.yaml.
  const std::string v1 = std::string(DEB_SOURCE_DIR) + "/tests/results/data/feedback_loop_v1.h5";
  CHECK(formats::Hdf5Reader(v1).Integer("schema_version") == 1);
  RunInfo info;
  const BudgetResult a = ReadResultStore(v1, &info);
  CHECK(info.budget_file == "budgets/guide/feedback_loop.yaml");
  REQUIRE(a.traces);
  REQUIRE_FALSE(a.outputs.empty());
  for (const auto& per_output : a.traces->paths)
    for (const PathResponse& p : per_output) {
      CHECK(p.f_hz.empty());  // on the grid
      for (const auto& g : p.gain2) CHECK(g.size() == a.grid.size());
    }
  // The CPS ends at the variance, which is the RMS squared.
  for (const OutputResult& o : a.outputs) CHECK(o.total_cps.back() == doctest::Approx(o.rms() * o.rms()).epsilon(1e-12));

  const StoreDir dir;
  const std::string v2 = dir.File("v2.h5");
  WriteResultStore(a, info, v2);
  CHECK(formats::Hdf5Reader(v2).Integer("schema_version") == 2);
  const BudgetResult b = ReadResultStore(v2);
  REQUIRE(b.outputs.size() == a.outputs.size());
  for (std::size_t o = 0; o < a.outputs.size(); ++o) {
    CHECK(b.outputs[o].rms() == a.outputs[o].rms());
    CHECK(b.outputs[o].total_psd == a.outputs[o].total_psd);
    CHECK(b.outputs[o].total_cps == a.outputs[o].total_cps);
    for (std::size_t c = 0; c < a.outputs[o].contributors.size(); ++c) {
      CHECK(b.outputs[o].contributors[c].psd == a.outputs[o].contributors[c].psd);
      CHECK(b.outputs[o].contributors[c].cps == a.outputs[o].contributors[c].cps);
    }
  }
  for (std::size_t c = 0; c < a.traces->paths.size(); ++c)
    for (std::size_t o = 0; o < a.traces->paths[c].size(); ++o) {
      CHECK(b.traces->paths[c][o].gain2 == a.traces->paths[c][o].gain2);
      CHECK(b.traces->paths[c][o].phase_rad == a.traces->paths[c][o].phase_rad);
    }
  REQUIRE(b.traces->loops.size() == a.traces->loops.size());
  for (std::size_t i = 0; i < a.traces->loops.size(); ++i)
    CHECK(b.traces->loops[i].loop_gain == a.traces->loops[i].loop_gain);
}

TEST_CASE("responses that contributors share are stored once, and compressed: the store is under half its raw size") {
  // wafer_stage: seven contributors drive force_to_position, so each output
  // has five distinct responses for eleven contributors.
  const StoreDir dir;
  const std::string file = dir.File("w.h5");
  const Written w = WriteStore(Budget("wafer_stage.yaml"), file);
  const formats::Hdf5Reader r(file);
  std::size_t shared = 0, raw = 0;
  const ResponseTraces& t = *w.result.traces;
  for (std::size_t c = 0; c < t.paths.size(); ++c)
    for (std::size_t o = 0; o < t.paths[c].size(); ++o) {
      const std::string at = "result/traces/paths/" + std::to_string(c) + "/" + std::to_string(o);
      if (r.Has(at + "/same_as_contributor")) {
        ++shared;
        CHECK_FALSE(r.Has(at + "/gain2"));
        const auto sc = static_cast<std::size_t>(r.Integer(at + "/same_as_contributor"));
        const auto so = static_cast<std::size_t>(r.Integer(at + "/same_as_output"));
        CHECK(w.result.outline.contributors[sc].path == w.result.outline.contributors[c].path);
        CHECK(so == o);
      }
      for (const auto& g : t.paths[c][o].gain2) raw += 2 * g.size() * sizeof(double);  // with the phase
    }
  CHECK(shared == 3 * 6);
  for (const OutputResult& o : w.result.outputs)
    for (const ContributorResult& c : o.contributors) raw += (c.psd.size() + c.cps.size()) * sizeof(double);
  MESSAGE("store " << Bytes(file).size() << " bytes for " << raw << " bytes of responses and spectra");
  CHECK(Bytes(file).size() * 2 < raw);
}

TEST_CASE("a budget's parameters are in its store, read back as written") {
  const StoreDir dir;
  const std::string budget = dir.File("p.yaml");
  std::ofstream(budget) << R"(name: p
parameters:
  m: 2100 kg
  k_iso: {value: 5.2e4 N/m, description: vertical stiffness per isolator}
  f_susp: sqrt(4*k_iso/m)/(2*pi)
grid: {type: log, min_hz: f_susp/100, max_hz: 2 kHz, points: 100}
sources:
  - {name: floor, unit: um/s, spectrum: {type: flat, quantity: asd, level: 0.1}}
paths:
  - {name: iso, type: second_order, f_hz: f_susp, zeta: 0.05, input_unit: um/s, output_unit: um/s, outputs: [v]}
contributors:
  - {name: floor, source: floor, path: iso}
outputs:
  - {name: v, signal: v, unit: um/s}
)";
  const std::string first = dir.File("first.h5"), second = dir.File("second.h5");
  const Written w = WriteStore(budget, first);
  RunInfo info;
  const BudgetResult s = ReadResultStore(first, &info);
  WriteResultStore(s, info, second);
  const bool same_bytes = Bytes(first) == Bytes(second);
  CHECK(same_bytes);
  REQUIRE(s.outline.parameters.size() == 3);
  CHECK(s.outline.parameters[0].name == "m");
  CHECK(s.outline.parameters[0].value == 2100.0);
  CHECK(s.outline.parameters[0].unit == "kg");
  CHECK_FALSE(s.outline.parameters[0].derived);
  CHECK(s.outline.parameters[1].description == "vertical stiffness per isolator");
  CHECK(s.outline.parameters[2].derived);
  CHECK(s.outline.parameters[2].expression == "sqrt(4*k_iso/m)/(2*pi)");
  CHECK(s.outline.parameters[2].unit == "s-1");
  CHECK(s.outline.parameters[2].value == w.result.outline.parameters[2].value);
  CHECK(std::abs(s.outline.parameters[2].value - std::sqrt(4 * 5.2e4 / 2100.0) / (2 * M_PI)) <= 1e-15);
}

TEST_CASE("the studies a budget holds (a sweep, tolerances) are in its store, so that a redrawn report says so") {
  const StoreDir dir;
  RunInfo info;
  WriteStore(std::string(DEB_SOURCE_DIR) + "/budgets/nizamoglu2015_sweep.yaml", dir.File("sweep.h5"));
  const BudgetResult swept = ReadResultStore(dir.File("sweep.h5"), &info);
  CHECK(swept.outline.has_sweep);
  CHECK(swept.outline.uncertain_parameters == 0);
  WriteStore(std::string(DEB_SOURCE_DIR) + "/budgets/nizamoglu2015_tolerances.yaml", dir.File("tolerances.h5"));
  const BudgetResult toleranced = ReadResultStore(dir.File("tolerances.h5"));
  CHECK_FALSE(toleranced.outline.has_sweep);
  CHECK(toleranced.outline.uncertain_parameters == 4);
  // A store written before they were kept reads as neither (feedback_loop has neither).
  const BudgetResult v1 = ReadResultStore(std::string(DEB_SOURCE_DIR) + "/tests/results/data/feedback_loop_v1.h5");
  CHECK_FALSE(v1.outline.has_sweep);
  CHECK(v1.outline.uncertain_parameters == 0);
}

TEST_CASE("a loop around a delay keeps its approximation's error at the crossover in the store") {
  const StoreDir dir;
  const std::string budget = dir.File("d.yaml");
  std::ofstream(budget) << R"(name: d
grid: {type: log, min_hz: 0.1, max_hz: 2000, points: 400}
sources:
  - {name: force, unit: N, spectrum: {type: flat, quantity: asd, level: 1}}
paths:
  - {name: plant, type: mass_spring_damper, m: 1 kg, k: 3948 N/m, d: 12.6 N s/m, input_unit: N, output_unit: um, outputs: [x]}
  - {name: pid, type: pid, gain: 0.1, f_i_hz: 5, f_d_hz: 20, f_lp_hz: 200, input_unit: um, output_unit: N}
  - {name: wait, type: delay, seconds: 200 us, pade_order: 3, input_unit: N, output_unit: N}
  - {name: late_pid, type: series, of: [pid, wait]}
  - {name: loop, type: feedback, plant: plant, controller: late_pid}
contributors:
  - {name: force, source: force, path: loop}
outputs:
  - {name: x, signal: x, unit: um}
)";
  const std::string first = dir.File("first.h5"), second = dir.File("second.h5");
  const Written w = WriteStore(budget, first);
  RunInfo info;
  const BudgetResult s = ReadResultStore(first, &info);
  WriteResultStore(s, info, second);
  const bool same_bytes = Bytes(first) == Bytes(second);
  CHECK(same_bytes);
  REQUIRE(w.result.loops.size() == 1);
  REQUIRE(s.loops.size() == 1);
  REQUIRE(w.result.loops[0].approximations.size() == 1);
  REQUIRE(s.loops[0].approximations.size() == 1);
  const LoopApproximation &a = w.result.loops[0].approximations[0], &b = s.loops[0].approximations[0];
  CHECK(b.block == "a delay of 200 us");
  CHECK(b.approximation == "Pade (3, 3)");
  CHECK(b.approximation == a.approximation);
  CHECK(b.f_hz == a.f_hz);
  CHECK(b.phase_error_deg == a.phase_error_deg);
  CHECK(b.gain_ratio == a.gain_ratio);
  CHECK(std::abs(b.phase_error_deg) > 0.0);  // order 3 at ~110 Hz: small, not zero
  CHECK(std::abs(b.phase_error_deg) < 1e-3);
}

TEST_CASE("the features each example stands for are in its store") {
  const StoreDir dir;
  const auto read = [&](const char* name) {
    WriteStore(Budget(name), dir.File("s.h5"));
    return ReadResultStore(dir.File("s.h5"));
  };
  const BudgetResult wafer = read("wafer_stage.yaml");
  bool grouped = false, referenced = false, metric = false, band_requirement = false;
  for (const OutputResult& o : wafer.outputs) {
    for (const ContributorResult& c : o.contributors) grouped |= !c.group.empty();
    referenced |= !o.references.empty();
    metric |= o.metric.has_value();
    band_requirement |= !o.band_requirements.empty();
  }
  CHECK(grouped);
  CHECK(referenced);
  CHECK(metric);
  CHECK(band_requirement);
  // One physical loop, built as PS, T and S: one loop naming its two other forms.
  REQUIRE(wafer.loops.size() == 1);
  CHECK(wafer.loops[0].same_loop.size() == 2);
  const BudgetResult thesis = read("nizamoglu2015_h210.yaml");
  CHECK(thesis.covariance.has_value());
  bool broken_down = false, weighted = false;
  for (const OutputResult& o : thesis.outputs)
    for (const ContributorResult& c : o.contributors) broken_down |= !c.channels.empty();
  for (const OutputOutline& o : thesis.outline.outputs) weighted |= o.weighting.has_value();
  CHECK(broken_down);
  CHECK(weighted);
  const BudgetResult measured = read("measured_stage.yaml");
  bool tones = false;
  for (const OutputResult& o : measured.outputs)
    for (const ContributorResult& c : o.contributors) tones |= !c.tones.empty();
  CHECK(tones);
  const BudgetResult frame = read("metrology_frame.yaml");
  bool modes = false;
  for (const OutputResult& o : frame.outputs)
    for (const ContributorResult& c : o.contributors) modes |= !c.top_modes.empty();
  CHECK(modes);
}

TEST_CASE("a store the reader must refuse gives an error naming the file and the object") {
  const StoreDir dir;
  SUBCASE("not an HDF5 file") {
    const std::string file = dir.File("text.h5");
    std::ofstream(file) << "schema: deb-result\n";
    CHECK(Contains(ErrorOf(file), file));
  }
  SUBCASE("another schema, or a newer version of this one") {
    const std::string other = dir.File("other.h5"), newer = dir.File("newer.h5");
    {
      formats::Hdf5Writer w(other);
      w.Text("schema", "someone-else");
      w.Integer("schema_version", 1);
      w.Close();
      formats::Hdf5Writer v(newer);
      v.Text("schema", kResultStoreSchema);
      v.Integer("schema_version", kResultStoreVersion + 1);
      v.Close();
    }
    CHECK(Contains(ErrorOf(other), "not a result store of deb"));
    const std::string e = ErrorOf(newer);
    CHECK(Contains(e, newer));
    CHECK(Contains(e, "schema version " + std::to_string(kResultStoreVersion + 1)));
  }
  SUBCASE("a PSD one value short of the grid") {
    Written w{Evaluate(LoadBudgetFile(Budget("single_axis_isolator.yaml"))), {}};
    w.result.outputs[1].contributors[0].psd.pop_back();
    const std::string file = dir.File("short.h5");
    WriteResultStore(w.result, w.info, file);
    const std::string e = ErrorOf(file);
    CHECK(Contains(e, file));
    CHECK(Contains(e, "'result/outputs/1/contributors/0/psd' has " + std::to_string(w.result.grid.size() - 1) +
                          " values, not " + std::to_string(w.result.grid.size())));
  }
  SUBCASE("a contributor of a source the store does not hold, an output index out of range") {
    Written w{Evaluate(LoadBudgetFile(Budget("nizamoglu2015_h210.yaml"))), {}};
    REQUIRE(w.result.covariance);
    const std::string renamed = dir.File("renamed.h5"), index = dir.File("index.h5");
    BudgetResult changed = w.result;
    changed.outline.sources[0].name = "renamed";
    WriteResultStore(changed, w.info, renamed);
    CHECK(Contains(ErrorOf(renamed), "'budget/contributors/0/source' names the source"));
    w.result.covariance->index[1] = 99;
    WriteResultStore(w.result, w.info, index);
    const std::string e = ErrorOf(index);
    CHECK(Contains(e, "'result/covariance/index' holds the index 99"));
  }
  SUBCASE("what a budget's rules forbid: a negative variance, a requirement of 0, two outputs of one name") {
    Written w{Evaluate(LoadBudgetFile(Budget("single_axis_isolator.yaml"))), {}};
    const auto refused = [&](const std::function<void(Written&)>& change, const std::string& says) {
      Written changed = w;
      change(changed);
      const std::string file = dir.File("changed.h5");
      WriteResultStore(changed.result, changed.info, file);
      const std::string e = ErrorOf(file);
      CHECK_MESSAGE(Contains(e, says), e);
    };
    refused([](Written& c) { c.result.outputs[0].variance = -1.0; },
            "'result/outputs/0/variance' holds -1, which must be >= 0");
    refused([](Written& c) { c.result.outputs[1].rms_max = 0.0; },
            "'result/outputs/1/rms_max' holds the requirement 0, which must be > 0");
    refused([](Written& c) { c.result.outputs[1].name = c.result.outputs[0].name; },
            "'result/outputs/1/name' holds the name");
    refused([](Written& c) { c.result.outputs[0].contributors[0].psd[3] = -1e-9; },
            "'result/outputs/0/contributors/0/psd' holds -1e-09 at element 3");
    refused([](Written& c) { c.result.outline.name = "a\x1b[31m"; }, "'budget/name' holds the name");
  }
  SUBCASE("a NaN where a figure must be finite") {
    Written w{Evaluate(LoadBudgetFile(Budget("single_axis_isolator.yaml"))), {}};
    w.result.outputs[0].variance = std::numeric_limits<double>::quiet_NaN();
    const std::string file = dir.File("nan.h5");
    WriteResultStore(w.result, w.info, file);
    const std::string e = ErrorOf(file);
    CHECK(Contains(e, "result/outputs/0/variance"));
  }
}

}  // namespace
}  // namespace deb
