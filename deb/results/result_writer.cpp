#include "deb/results/result_writer.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "deb/core/file_name.h"
#include "deb/budget/allocation.h"
#include "deb/budget/failure_guidance.h"
#include "deb/budget/groups.h"
#include "deb/core/error.h"
#include "deb/core/number_text.h"
#include "deb/core/parallel.h"
#include "deb/units/unit.h"
#include "deb/version.h"

namespace deb {
namespace fs = std::filesystem;
namespace {

nlohmann::json NumberOrNull(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

// Rows of a matrix; a non-finite entry (a correlation with a zero variance) is null.
nlohmann::json MatrixJson(const Eigen::MatrixXd& m) {
  nlohmann::json rows = nlohmann::json::array();
  for (Eigen::Index i = 0; i < m.rows(); ++i) {
    nlohmann::json row = nlohmann::json::array();
    for (Eigen::Index k = 0; k < m.cols(); ++k) row.push_back(NumberOrNull(m(i, k)));
    rows.push_back(row);
  }
  return rows;
}

// The budget's `covariance:` (deb/budget/output_covariance.h).
nlohmann::json CovarianceJson(const CovarianceResult& cov) {
  nlohmann::json j;
  j["outputs"] = cov.outputs;
  j["units"] = cov.units;
  j["matrix"] = MatrixJson(cov.matrix);
  j["correlation"] = MatrixJson(cov.correlation);
  j["exact_matrix"] = cov.exact_matrix ? MatrixJson(*cov.exact_matrix) : nlohmann::json(nullptr);
  if (!cov.exact_matrix) j["exact_note"] = cov.exact_note;
  nlohmann::json contributors = nlohmann::json::array();
  for (const ContributorCovariance& c : cov.contributors)
    contributors.push_back({{"name", c.name}, {"matrix", MatrixJson(c.matrix)}});
  j["contributors"] = contributors;
  return j;
}

nlohmann::json Conventions() {
  return {
      {"frequency", "Hz"},
      {"psd", "one-sided: variance = integral of S(f) df over 0 < f < infinity; unit^2/Hz"},
      {"asd", "sqrt(PSD), unit/sqrt(Hz)"},
      {"cps", "cumulative power spectrum, integral of the PSD from the grid's lowest frequency up to f; "
              "rms = sqrt(cps at the highest frequency)"},
      {"two_sided_sources", "sources declared two-sided are converted once at load: S_one = 2 S_two"},
      {"h2_norm", "||H||_2^2 = (1/2pi) integral over all omega of tr(H H^H); white one-sided S0 gives "
                  "variance = S0 ||H||_2^2 / 2"},
      {"exact_variance", "Lyapunov A P + P A^T + B W B^T = 0, variance = C P C^T, W = S0/2; over 0 < f < infinity"},
      {"contributors", "mutually uncorrelated; variances add"},
  };
}

// Every feedback loop and its margins (deb/systems/loop_margins.h): gain
// margins as factors, phase margins in degrees, frequencies in Hz; a margin
// the loop does not have is null.
nlohmann::json LoopsJson(const std::vector<LoopResult>& loops) {
  nlohmann::json out = nlohmann::json::array();
  for (const LoopResult& l : loops) {
    nlohmann::json jl = {{"plant", l.plant}, {"controller", l.controller}, {"sign", l.sign}, {"paths", l.paths},
                         {"evaluated", l.evaluated}};
    for (const LoopForm& f : l.same_loop)  // only a loop built in several ways
      jl["same_loop_as"].push_back({{"plant", f.plant}, {"controller", f.controller}, {"sign", f.sign}});
    for (const MarginCheck& c : MarginChecks(l))  // only a loop with `margins:`
      jl["requirements"].push_back({{"margin", c.what},
                                    {"unit", c.unit},
                                    {"required", c.required},
                                    {"actual", std::isfinite(c.actual) ? nlohmann::json(c.actual) : nlohmann::json(nullptr)},
                                    {"pass", c.pass()}});
    if (!l.evaluated) {
      jl["note"] = l.note;
      out.push_back(jl);
      continue;
    }
    const LoopMargins& m = l.margins;
    const auto crossing = [](const auto& c, const char* key, double value) {
      return c ? nlohmann::json{{"f_hz", c->f_hz}, {key, value}} : nlohmann::json(nullptr);
    };
    jl["channels"] = m.channels;
    jl["modulus_margin"] = {{"f_hz", m.modulus_margin_f_hz}, {"value", m.modulus_margin}};
    if (m.channels == 1) {
      jl["phase_margin"] = crossing(m.phase_margin, "deg", m.phase_margin ? m.phase_margin->phase_margin_deg : 0.0);
      jl["gain_margin"] =
          crossing(m.upper_gain_margin, "factor", m.upper_gain_margin ? m.upper_gain_margin->gain_margin : 0.0);
      jl["lower_gain_margin"] =
          crossing(m.lower_gain_margin, "factor", m.lower_gain_margin ? m.lower_gain_margin->gain_margin : 0.0);
    }
    for (const LoopApproximation& a : l.approximations)
      jl["approximations"].push_back({{"block", a.block},
                                      {"approximation", a.approximation},
                                      {"f_hz", a.f_hz},
                                      {"phase_error_deg", a.phase_error_deg},
                                      {"gain_ratio", a.gain_ratio}});
    out.push_back(jl);
  }
  return out;
}

nlohmann::json Names(const OutputResult& o, const std::vector<std::size_t>& contributors) {
  nlohmann::json names = nlohmann::json::array();
  for (std::size_t c : contributors) names.push_back(o.contributors[c].name);
  return names;
}

nlohmann::json OptionalNumber(const std::optional<double>& v) { return v ? nlohmann::json(*v) : nlohmann::json(nullptr); }

// What to fix (failure_guidance.h), or null when every requirement is met.
// Every factor divides an RMS amplitude; a PSD's is its square.
nlohmann::json GuidanceJson(const OutputResult& o, const FrequencyGrid& grid) {
  const std::optional<FailureGuidance> g = GuideFailure(o, grid);
  if (!g) return nullptr;
  nlohmann::json j;
  if (const auto& r = g->overall) {
    j["fail_factor"] = r->fail_factor;
    j["uniform_factor"] = r->fail_factor;
    j["cps_crossing_hz"] = OptionalNumber(r->cps_crossing_hz);
    j["dominant"] = {{"name", o.contributors[r->dominant].name},
                     {"share", r->dominant_share},
                     {"band", r->dominant_band ? nlohmann::json({{"lo_hz", r->dominant_band->lo_hz},
                                                                 {"hi_hz", r->dominant_band->hi_hz}})
                                               : nlohmann::json(nullptr)}};
    j["remove"] = Names(o, r->remove);
    nlohmann::json reduce = nlohmann::json::array();
    for (const ContributorReduction& c : r->reduce)
      reduce.push_back({{"contributors", Names(o, c.contributors)}, {"rms_factor", OptionalNumber(c.rms_factor)}});
    j["reduce_each"] = reduce;
  } else {
    for (const char* key : {"fail_factor", "uniform_factor", "cps_crossing_hz", "dominant"}) j[key] = nullptr;
    j["remove"] = nlohmann::json::array();
    j["reduce_each"] = nlohmann::json::array();
  }
  nlohmann::json bands = nlohmann::json::array();
  for (const BandGuidance& b : g->bands)
    bands.push_back({{"lo_hz", b.requirement.lo_hz},
                     {"hi_hz", b.requirement.hi_hz},
                     {"rms_max", b.requirement.rms_max},
                     {"rms", b.rms},
                     {"fail_factor", b.fail_factor},
                     {"largest", o.contributors[b.largest].name},
                     {"largest_share", b.largest_share},
                     {"largest_rms_factor", OptionalNumber(b.largest_rms_factor)}});
  j["bands"] = bands;
  j["sentence"] = g->sentence;
  return j;
}

// A contributor's factor on its source's PSD that puts the output at its
// limit and, when the source feeds several contributors, the factor that
// scales them all.
void AllocationJson(nlohmann::json& jc, const OutputResult& o, std::size_t c) {
  const ContributorResult& cr = o.contributors[c];
  const Allocation a = AllocationFactor(o, c);
  jc["allocation_factor"] = a.factor ? nlohmann::json(*a.factor) : nlohmann::json(nullptr);
  jc["allocation_note"] = a.factor ? nlohmann::json(nullptr) : nlohmann::json(a.note);
  std::vector<std::size_t> group;
  nlohmann::json shared = nlohmann::json::array();
  for (std::size_t k = 0; k < o.contributors.size(); ++k)
    if (o.contributors[k].source == cr.source) {
      group.push_back(k);
      if (k != c) shared.push_back(o.contributors[k].name);
    }
  if (group.size() > 1) {
    const Allocation g = SourceAllocationFactor(o, group);
    jc["source_shared_with"] = shared;
    jc["source_allocation_factor"] = g.factor ? nlohmann::json(*g.factor) : nlohmann::json(nullptr);
    jc["source_allocation_note"] = g.factor ? nlohmann::json(nullptr) : nlohmann::json(g.note);
  }
}

// A contributor's variance split over its source's channels, and the cross terms.
nlohmann::json BreakdownJson(const ContributorResult& cr) {
  nlohmann::json parts = nlohmann::json::array();
  for (const ContributorResult::ChannelPart& p : cr.channels)
    parts.push_back({{"channel", p.channel},
                     {"rms", std::sqrt(std::max(p.variance, 0.0))},
                     {"variance", p.variance},
                     {"share_of_contributor", cr.variance > 0.0 ? p.variance / cr.variance : 0.0}});
  return {{"channels", parts}, {"cross_variance", cr.cross_variance}};
}

// The exact (Lyapunov) figures of a contributor, or null and why not.
void ExactJson(nlohmann::json& jc, const ContributorResult& cr) {
  if (cr.exact_variance) {
    jc["exact_rms"] = std::sqrt(*cr.exact_variance);
    jc["exact_variance"] = *cr.exact_variance;
    // Everything the grid figure misses: the tails beyond its ends and its
    // quadrature error (tail_variance_estimate is the tails alone).
    jc["exact_minus_grid_variance"] = *cr.exact_variance - cr.variance;
    jc["exact_note"] = nullptr;
  } else {
    jc["exact_rms"] = nullptr;
    jc["exact_variance"] = nullptr;
    jc["exact_minus_grid_variance"] = nullptr;
    jc["exact_note"] = cr.exact_note;
  }
  jc["tail_variance_estimate"] = NumberOrNull(cr.tail_variance_estimate);
}

nlohmann::json ContributorJson(const OutputResult& o, std::size_t c) {
  const ContributorResult& cr = o.contributors[c];
  nlohmann::json jc;
  jc["name"] = cr.name;
  jc["source"] = cr.source;
  jc["path"] = cr.path;
  if (!cr.inputs.empty()) jc["inputs"] = cr.inputs;
  if (!cr.group.empty()) jc["group"] = cr.group;
  if (!cr.channels.empty()) jc["breakdown"] = BreakdownJson(cr);
  if (!cr.tones.empty()) {
    nlohmann::json tones = nlohmann::json::array();
    for (const ContributorResult::Tone& t : cr.tones)
      tones.push_back({{"f_hz", t.f_hz}, {"rms", std::sqrt(t.variance)}, {"variance", t.variance}});
    jc["tones"] = tones;
  }
  jc["rms"] = std::sqrt(cr.variance);
  jc["variance"] = cr.variance;
  jc["share"] = o.variance > 0.0 ? cr.variance / o.variance : 0.0;
  ExactJson(jc, cr);
  nlohmann::json modes = nlohmann::json::array();
  for (const ModeShare& m : cr.top_modes)
    modes.push_back(
        {{"mode", m.mode}, {"f_hz", m.f_hz}, {"zeta", m.zeta}, {"variance", m.variance}, {"share", m.share}});
  jc["top_modes"] = modes;
  jc["top_modes_of"] =
      cr.top_modes_of == ModeSplit::kNone ? nlohmann::json(nullptr) : nlohmann::json(ToString(cr.top_modes_of));
  if (o.rms_max) AllocationJson(jc, o, c);
  return jc;
}

// The output's requirement (or null) and its band requirements.
void RequirementsJson(nlohmann::json& jo, const OutputResult& o) {
  if (o.rms_max) jo["requirement"] = {{"rms_max", *o.rms_max}, {"pass", o.pass()}, {"margin", *o.rms_max - o.rms()}};
  else jo["requirement"] = nullptr;
  nlohmann::json band_requirements = nlohmann::json::array();
  for (const BandRequirementResult& b : o.band_requirements)
    band_requirements.push_back({{"lo_hz", b.requirement.lo_hz},
                                 {"hi_hz", b.requirement.hi_hz},
                                 {"rms_max", b.requirement.rms_max},
                                 {"rms", b.rms()},
                                 {"pass", b.pass()},
                                 {"margin", b.requirement.rms_max - b.rms()}});
  jo["band_requirements"] = band_requirements;
}

nlohmann::json BandsJson(const OutputResult& o) {
  nlohmann::json bands = nlohmann::json::array();
  for (const BandResult& b : o.bands) {
    nlohmann::json jb = {{"lo_hz", b.band.lo_hz}, {"hi_hz", b.band.hi_hz}, {"rms", std::sqrt(b.variance)},
                         {"variance", b.variance}};
    nlohmann::json bc = nlohmann::json::array();
    for (std::size_t c = 0; c < o.contributors.size(); ++c)
      bc.push_back({{"name", o.contributors[c].name},
                    {"rms", std::sqrt(b.contributor_variance[c])},
                    {"variance", b.contributor_variance[c]}});
    jb["contributors"] = bc;
    bands.push_back(jb);
  }
  return bands;
}

// A measured reference against the budget, overall and per band; a band
// reaching beyond the measurement has null measured figures.
nlohmann::json ReferenceJson(const OutputResult& o, const ReferenceResult& ref) {
  const double budget_covered = ref.budget_variance;
  nlohmann::json rb = nlohmann::json::array();
  for (std::size_t b = 0; b < o.bands.size(); ++b) {
    nlohmann::json jb = {{"lo_hz", o.bands[b].band.lo_hz}, {"hi_hz", o.bands[b].band.hi_hz},
                         {"budget_rms", std::sqrt(o.bands[b].variance)}};
    if (const auto& v = ref.band_variance[b]) {
      jb["measured_rms"] = std::sqrt(*v);
      jb["ratio"] = o.bands[b].variance > 0.0 ? nlohmann::json(std::sqrt(*v / o.bands[b].variance))
                                              : nlohmann::json(nullptr);
      jb["unexplained_rms"] = std::sqrt(std::max(*v - o.bands[b].variance, 0.0));
    } else {
      jb["measured_rms"] = nullptr;
      jb["ratio"] = nullptr;
      jb["unexplained_rms"] = nullptr;
    }
    rb.push_back(jb);
  }
  return {{"name", ref.name},
          {"covered_hz", {ref.covered_lo_hz, ref.covered_hi_hz}},
          {"measured_rms", std::sqrt(ref.variance)},
          {"budget_rms", std::sqrt(budget_covered)},
          {"ratio", budget_covered > 0.0 ? nlohmann::json(std::sqrt(ref.variance / budget_covered))
                                         : nlohmann::json(nullptr)},
          {"unexplained_rms", std::sqrt(std::max(ref.variance - budget_covered, 0.0))},
          {"bands", rb}};
}

nlohmann::json GroupsJson(const OutputResult& o, const std::vector<GroupResult>& groups) {
  nlohmann::json jg = nlohmann::json::array();
  for (const GroupResult& g : groups) {
    nlohmann::json members = nlohmann::json::array();
    for (std::size_t c : g.contributors) members.push_back(o.contributors[c].name);
    nlohmann::json subgroups = g.subgroups;
    nlohmann::json gb = nlohmann::json::array();
    for (std::size_t b = 0; b < o.bands.size(); ++b)
      gb.push_back({{"lo_hz", o.bands[b].band.lo_hz}, {"hi_hz", o.bands[b].band.hi_hz},
                    {"rms", std::sqrt(g.band_variance[b])}, {"variance", g.band_variance[b]}});
    jg.push_back({{"name", g.name}, {"path", g.path}, {"depth", g.depth}, {"variance", g.variance},
                  {"rms", std::sqrt(g.variance)}, {"share", g.share}, {"members", members},
                  {"subgroups", subgroups}, {"bands", gb}});
  }
  return jg;
}

nlohmann::json OutputJson(const OutputResult& o, const FrequencyGrid& grid) {
  nlohmann::json jo;
  jo["name"] = o.name;
  jo["signal"] = o.signal;
  jo["unit"] = o.unit;
  jo["rms"] = o.rms();
  jo["variance"] = o.variance;
  if (o.metric)  // rms is then sqrt(E[MA^2]) or sqrt(E[MSD^2]) over the window
    jo["metric"] = {{"type", ToString(o.metric->type)}, {"window_s", o.metric->window_s}};
  else
    jo["metric"] = nullptr;
  RequirementsJson(jo, o);
  jo["guidance"] = GuidanceJson(o, grid);
  nlohmann::json contributors = nlohmann::json::array();
  for (std::size_t c = 0; c < o.contributors.size(); ++c) contributors.push_back(ContributorJson(o, c));
  jo["contributors"] = contributors;
  jo["bands"] = BandsJson(o);
  if (!o.references.empty()) {
    nlohmann::json refs = nlohmann::json::array();
    for (const ReferenceResult& ref : o.references) refs.push_back(ReferenceJson(o, ref));
    jo["references"] = refs;
  }
  if (const std::vector<GroupResult> groups = ComputeGroups(o); !groups.empty()) jo["groups"] = GroupsJson(o, groups);
  return jo;
}

nlohmann::json ParametersJson(const std::vector<ParameterOutline>& parameters) {
  nlohmann::json params = nlohmann::json::array();
  for (const ParameterOutline& p : parameters)
    params.push_back({{"name", p.name}, {"value", p.value}, {"unit", p.unit}, {"expression", p.expression},
                      {"derived", p.derived}, {"description", p.description}});
  return params;
}

}  // namespace

std::string SummaryJson(const BudgetResult& result, const RunInfo& info) {
  nlohmann::json j;
  j["budget"] = result.outline.name;
  j["description"] = result.outline.description;
  j["budget_file"] = info.budget_file;
  j["budget_sha256"] = info.budget_sha256;  // "" when unknown: a budget built in code
  j["deb_version"] = DEB_VERSION;
  j["conventions"] = Conventions();
  j["grid"] = {{"type", ToString(result.outline.grid_kind)},
               {"points", result.grid.size()},
               {"min_hz", result.grid.min_hz()},
               {"max_hz", result.grid.max_hz()}};
  j["seconds"] = info.seconds ? nlohmann::json(*info.seconds) : nlohmann::json(nullptr);
  bool all_pass = true;
  nlohmann::json outputs = nlohmann::json::array();
  for (const OutputResult& o : result.outputs) {
    outputs.push_back(OutputJson(o, result.grid));
    all_pass &= o.AllPass();
  }
  j["outputs"] = outputs;
  j["pass"] = all_pass;
  j["warnings"] = result.warnings;
  if (!result.loops.empty()) j["loops"] = LoopsJson(result.loops);
  if (result.covariance) j["covariance"] = CovarianceJson(*result.covariance);
  if (!result.outline.parameters.empty()) j["parameters"] = ParametersJson(result.outline.parameters);
  return j.dump(2) + "\n";
}

std::string OutputCsvName(const std::string& output_name) { return FileNameWord(output_name) + ".csv"; }

std::string OutputCsv(const BudgetResult& result, const OutputResult& o) {
  std::ostringstream os;
  os.precision(10);
  os << "# deb " << DEB_VERSION << ", budget " << result.outline.name << ", output " << o.name << " (signal "
     << o.signal << ")\n"
     << "# psd_*: one-sided PSD in " << PsdUnitLabel(o.unit) << "; cps_*: cumulative from " << result.grid.min_hz()
     << " Hz in (" << o.unit << ")^2; reverse_cps_total: integral from f to " << result.grid.max_hz() << " Hz\n";
  os << "frequency_hz";
  for (const auto& c : o.contributors) os << ",psd_" << c.name;
  os << ",psd_total";
  for (const auto& c : o.contributors) os << ",cps_" << c.name;
  os << ",cps_total,reverse_cps_total\n";
  const std::vector<double> reverse = ReverseCps(o.total_cps);
  const auto& f = result.grid.f_hz();
  // Each number as the shortest text that reads back to the same double: the
  // data are exact, and shortest-form std::to_chars is about 3x faster than
  // a fixed precision (the table has grid points x (2 contributors + 3)
  // numbers, easily 10^5..10^6 of them).
  std::string text = os.str();
  const auto put = [&](double v, char sep) {
    text += sep;
    AppendNumberText(text, v);
  };
  for (std::size_t k = 0; k < f.size(); ++k) {
    AppendNumberText(text, f[k]);
    for (const auto& c : o.contributors) put(c.psd[k], ',');
    put(o.total_psd[k], ',');
    for (const auto& c : o.contributors) put(c.cps[k], ',');
    put(o.total_cps[k], ',');
    put(reverse[k], ',');
    text += '\n';
  }
  return text;
}

void WriteResultFiles(const BudgetResult& result, const RunInfo& info, const std::string& dir) {
  WriteTextFile((fs::path(dir) / "summary.json").string(), SummaryJson(result, info));
}

void WriteResultDirectory(const BudgetResult& result, const RunInfo& info, const std::string& out_dir, const ReplaceOptions& options) {
  ReplaceDirectory(out_dir, [&](const std::string& dir) { WriteResultFiles(result, info, dir); }, options);
}

}  // namespace deb
