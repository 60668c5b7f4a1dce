#include "deb/results/result_store.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <Eigen/Dense>
#include <functional>
#include <limits>
#include <optional>
#include <set>
#include <utility>

#include "deb/budget/groups.h"
#include "deb/budget/response_traces.h"
#include "deb/core/error.h"
#include "deb/core/input_file.h"
#include "deb/core/limits.h"
#include "deb/core/number_text.h"
#include "deb/formats/hdf5_file.h"
#include "deb/version.h"

namespace deb {
using formats::AtMost;
using formats::Hdf5Reader;
using formats::Hdf5Writer;

namespace {

constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
// Entries of one list of a store (sources, contributors, outputs, loops,
// references): a read bound, far above any budget.
constexpr std::size_t kMaxEntries = 100'000;

std::string At(const std::string& prefix, std::size_t index) { return prefix + "/" + std::to_string(index); }

double OrNone(const std::optional<double>& v) { return v ? *v : kNone; }
std::optional<double> FromNone(double v) { return std::isnan(v) ? std::nullopt : std::optional<double>(v); }

std::vector<double> Indices(const std::vector<std::size_t>& v) { return {v.begin(), v.end()}; }

// The names of a list's entries, for its `names` dataset.
template <class T, class Name>
std::vector<std::string> Names(const std::vector<T>& entries, Name name) {
  std::vector<std::string> names;
  for (const T& e : entries) names.push_back(name(e));
  return names;
}
const auto kName = [](const auto& entry) { return entry.name; };

// ---------------------------------------------------------------- writing

std::vector<std::vector<double>> RowsOf(const Eigen::MatrixXd& m) {
  std::vector<std::vector<double>> rows(static_cast<std::size_t>(m.rows()));
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    for (Eigen::Index j = 0; j < m.cols(); ++j) rows[static_cast<std::size_t>(i)].push_back(m(i, j));
  return rows;
}

void WriteCovariance(Hdf5Writer& w, const std::string& at, const CovarianceResult& c) {
  w.Texts(at + "/outputs", c.outputs);
  w.Texts(at + "/units", c.units);
  w.Numbers(at + "/index", Indices(c.index));
  w.Rows(at + "/matrix", RowsOf(c.matrix));
  w.Rows(at + "/correlation", RowsOf(c.correlation));
  w.Rows(at + "/exact_matrix", c.exact_matrix ? RowsOf(*c.exact_matrix) : std::vector<std::vector<double>>{});
  w.Text(at + "/exact_note", c.exact_note);
  w.Texts(at + "/contributors/names", Names(c.contributors, kName));
  for (std::size_t i = 0; i < c.contributors.size(); ++i)
    w.Rows(At(at + "/contributors", i) + "/matrix", RowsOf(c.contributors[i].matrix));
}

void WriteContributor(Hdf5Writer& w, const std::string& at, const ContributorResult& c) {
  w.Text(at + "/name", c.name);
  w.Text(at + "/source", c.source);
  w.Text(at + "/path", c.path);
  w.Texts(at + "/inputs", c.inputs);
  w.Text(at + "/group", c.group);
  w.Numbers(at + "/psd", c.psd);
  w.Numbers(at + "/cps", c.cps);
  w.Number(at + "/variance", c.variance);
  w.Number(at + "/exact_variance", OrNone(c.exact_variance));
  w.Text(at + "/exact_note", c.exact_note);
  w.Number(at + "/tail_variance_estimate", c.tail_variance_estimate);
  std::vector<std::vector<double>> tones;
  for (const ContributorResult::Tone& t : c.tones) tones.push_back({t.f_hz, t.variance});
  w.Rows(at + "/tones", tones);
  std::vector<std::string> channels;
  std::vector<std::vector<double>> psd, cps;
  std::vector<double> variance;
  for (const ContributorResult::ChannelPart& p : c.channels) {
    channels.push_back(p.channel);
    psd.push_back(p.psd);
    cps.push_back(p.cps);
    variance.push_back(p.variance);
  }
  w.Texts(at + "/channels/names", channels);
  w.Rows(at + "/channels/psd", psd);
  w.Rows(at + "/channels/cps", cps);
  w.Numbers(at + "/channels/variance", variance);
  w.Number(at + "/channels/cross_variance", c.cross_variance);
  std::vector<std::vector<double>> modes;
  for (const ModeShare& m : c.top_modes) modes.push_back({double(m.mode), m.f_hz, m.zeta, m.variance, m.share});
  w.Rows(at + "/top_modes", modes);
  w.Text(at + "/top_modes_of", ToString(c.top_modes_of));
}

void WriteOutput(Hdf5Writer& w, const std::string& at, const OutputOutline& spec, const OutputResult& o) {
  w.Text(at + "/name", o.name);
  w.Text(at + "/signal", o.signal);
  w.Text(at + "/unit", o.unit);
  w.Number(at + "/variance", o.variance);
  w.Number(at + "/rms", o.rms());
  w.Number(at + "/rms_max", OrNone(o.rms_max));
  w.Text(at + "/metric/type", o.metric ? ToString(o.metric->type) : "");
  w.Number(at + "/metric/window_s", o.metric ? o.metric->window_s : kNone);
  w.Text(at + "/weighting/unit", spec.weighting ? spec.weighting->unit : "");
  w.Text(at + "/weighting/description", spec.weighting ? spec.weighting->description : "");
  w.Integer(at + "/weighting/present", spec.weighting ? 1 : 0);
  std::vector<std::string> term_signals, term_units;
  std::vector<double> term_weights;
  for (const SignalTerm& t : spec.combination) {
    term_signals.push_back(t.signal);
    term_weights.push_back(t.weight);
    term_units.push_back(t.unit);
  }
  w.Texts(at + "/combination/signals", term_signals);
  w.Numbers(at + "/combination/weights", term_weights);
  w.Texts(at + "/combination/units", term_units);
  w.Numbers(at + "/total_psd", o.total_psd);
  w.Numbers(at + "/total_cps", o.total_cps);
  std::vector<std::vector<double>> requirements;
  std::vector<double> requirement_variance;
  for (const BandRequirementResult& b : o.band_requirements) {
    requirements.push_back({b.requirement.lo_hz, b.requirement.hi_hz, b.requirement.rms_max});
    requirement_variance.push_back(b.variance);
  }
  w.Rows(at + "/band_requirements/limits", requirements);
  w.Numbers(at + "/band_requirements/variance", requirement_variance);
  std::vector<std::vector<double>> bands, band_contributors;
  std::vector<double> band_variance;
  for (const BandResult& b : o.bands) {
    bands.push_back({b.band.lo_hz, b.band.hi_hz});
    band_variance.push_back(b.variance);
    band_contributors.push_back(b.contributor_variance);
  }
  w.Rows(at + "/bands/edges_hz", bands);
  w.Numbers(at + "/bands/variance", band_variance);
  w.Rows(at + "/bands/contributor_variance", band_contributors);
  w.Texts(at + "/contributors/names", Names(o.contributors, kName));
  for (std::size_t c = 0; c < o.contributors.size(); ++c) WriteContributor(w, At(at + "/contributors", c), o.contributors[c]);
  w.Texts(at + "/references/names", Names(o.references, kName));
  for (std::size_t i = 0; i < o.references.size(); ++i) {
    const ReferenceResult& r = o.references[i];
    const std::string ra = At(at + "/references", i);
    w.Text(ra + "/name", r.name);
    w.Numbers(ra + "/psd", r.psd);
    w.Numbers(ra + "/cps", r.cps);
    w.Number(ra + "/variance", r.variance);
    w.Number(ra + "/budget_variance", r.budget_variance);
    w.Numbers(ra + "/covered_hz", {r.covered_lo_hz, r.covered_hi_hz});
    std::vector<double> per_band;
    for (const std::optional<double>& v : r.band_variance) per_band.push_back(OrNone(v));
    w.Numbers(ra + "/band_variance", per_band);
  }
  // Groups are derived from the contributors (ComputeGroups): stored for
  // readers, not read back.
  const std::vector<GroupResult> groups = ComputeGroups(o);
  w.Texts(at + "/groups/paths", Names(groups, [](const GroupResult& g) { return g.path; }));
  for (std::size_t i = 0; i < groups.size(); ++i) {
    const GroupResult& g = groups[i];
    const std::string ga = At(at + "/groups", i);
    w.Text(ga + "/path", g.path);
    w.Number(ga + "/variance", g.variance);
    w.Number(ga + "/rms", std::sqrt(std::max(g.variance, 0.0)));
    w.Number(ga + "/share", g.share);
    w.Numbers(ga + "/members", Indices(g.all_contributors));
    w.Numbers(ga + "/band_variance", g.band_variance);
  }
}

void WriteLoop(Hdf5Writer& w, const std::string& at, const LoopResult& r, const LoopTrace& trace) {
  w.Text(at + "/plant", r.plant);
  w.Text(at + "/controller", r.controller);
  w.Integer(at + "/sign", r.sign);
  w.Texts(at + "/paths", r.paths);
  w.Integer(at + "/evaluated", r.evaluated ? 1 : 0);
  w.Text(at + "/note", r.note);
  if (!r.same_loop.empty()) {  // only loops built in several ways
    std::vector<std::string> plants, controllers;
    std::vector<double> signs;
    for (const LoopForm& f : r.same_loop) {
      plants.push_back(f.plant);
      controllers.push_back(f.controller);
      signs.push_back(f.sign);
    }
    w.Texts(at + "/same_loop/plants", plants);
    w.Texts(at + "/same_loop/controllers", controllers);
    w.Numbers(at + "/same_loop/signs", signs);
  }
  if (!r.required.empty()) {  // only loops with `margins:`: gain dB, phase deg, modulus; NaN where not given
    const double nan = std::nan("");
    w.Numbers(at + "/required_margins", {r.required.gain_db.value_or(nan), r.required.phase_deg.value_or(nan),
                                         r.required.modulus.value_or(nan)});
  }
  const LoopMargins& m = r.margins;
  w.Integer(at + "/margins/channels", m.channels);
  std::vector<std::vector<double>> gain, phase;
  for (const GainCrossover& c : m.gain_crossovers) gain.push_back({c.f_hz, c.phase_margin_deg});
  for (const PhaseCrossover& c : m.phase_crossovers) phase.push_back({c.f_hz, c.gain_margin});
  w.Rows(at + "/margins/gain_crossovers", gain);
  w.Rows(at + "/margins/phase_crossovers", phase);
  w.Numbers(at + "/margins/phase_margin",
            m.phase_margin ? std::vector<double>{m.phase_margin->f_hz, m.phase_margin->phase_margin_deg}
                           : std::vector<double>{});
  for (const auto& [name, margin] : {std::make_pair("upper_gain_margin", &m.upper_gain_margin),
                                     std::make_pair("lower_gain_margin", &m.lower_gain_margin)})
    w.Numbers(at + "/margins/" + name,
              *margin ? std::vector<double>{(*margin)->f_hz, (*margin)->gain_margin} : std::vector<double>{});
  w.Numbers(at + "/margins/modulus_margin", {m.modulus_margin, m.modulus_margin_f_hz});
  if (!r.approximations.empty()) {  // only loops around delays or sampled blocks
    std::vector<std::string> blocks, how;
    std::vector<std::vector<double>> errors;
    for (const LoopApproximation& a : r.approximations) {
      blocks.push_back(a.block);
      how.push_back(a.approximation);
      errors.push_back({a.f_hz, a.phase_error_deg, a.gain_ratio});
    }
    w.Texts(at + "/approximations/blocks", blocks);
    w.Texts(at + "/approximations/approximations", how);
    w.Rows(at + "/approximations/errors", errors);
  }
  std::vector<double> re, im;
  for (const std::complex<double>& l : trace.loop_gain) {
    re.push_back(l.real());
    im.push_back(l.imag());
  }
  w.Numbers(at + "/trace/f_hz", trace.f_hz);
  w.Numbers(at + "/trace/loop_gain_re", re);
  w.Numbers(at + "/trace/loop_gain_im", im);
}

// ---------------------------------------------------------------- reading

// Bounds of what a store may declare, checked from each dataset's header
// before anything is allocated: the budget's own limits where there is one
// (deb/core/limits.h).
constexpr std::size_t kMaxTexts = kMaxEntries;  // warnings, combination terms, covariance outputs
constexpr std::size_t kMaxChannels = static_cast<std::size_t>(limits::kMaxChannels);
constexpr std::size_t kMaxModes = static_cast<std::size_t>(limits::kMaxModes);

// True for a C0 or C1 control character at text[i] (C1 in UTF-8: 0xC2
// 0x80-0x9F): a terminal acts on them (ESC [ ... sets colours, moves the
// cursor), so names printed on the console must hold none.
bool ControlAt(const std::string& text, std::size_t i) {
  const auto c = static_cast<unsigned char>(text[i]);
  return c < 0x20 || c == 0x7f ||
         (c == 0xC2 && i + 1 < text.size() && static_cast<unsigned char>(text[i + 1]) >= 0x80 &&
          static_cast<unsigned char>(text[i + 1]) <= 0x9F);
}

class Reading {
 public:
  explicit Reading(const std::string& file) : r_(file), file_(file) {}
  const Hdf5Reader& r() const { return r_; }
  [[noreturn]] void Fail(const std::string& object, const std::string& what) const {
    throw InputError(file_ + ": object '" + object + "' " + what);
  }
  // A vector of `n` numbers.
  std::vector<double> Numbers(const std::string& object, std::size_t n, bool allow_nan = false) const {
    std::vector<double> v = r_.Numbers(object, AtMost(n), allow_nan);
    if (v.size() != n)
      Fail(object, "has " + std::to_string(v.size()) + " values, not " + std::to_string(n));
    return v;
  }
  // Up to `most` numbers.
  std::vector<double> UpTo(const std::string& object, std::size_t most) const {
    return r_.Numbers(object, AtMost(most));
  }
  // Up to `most` rows of `columns` numbers each (a 0 x 0 matrix is no rows).
  std::vector<std::vector<double>> Rows(const std::string& object, std::size_t columns, std::size_t most,
                                        bool allow_nan = false) const {
    return r_.Rows(object, AtMost(most), columns, allow_nan);
  }
  // Exactly `rows` rows of `columns` numbers.
  std::vector<std::vector<double>> Exactly(const std::string& object, std::size_t rows, std::size_t columns,
                                           bool allow_nan) const {
    std::vector<std::vector<double>> v = r_.Rows(object, AtMost(rows), columns, allow_nan);
    if (v.size() != rows) Fail(object, "has " + std::to_string(v.size()) + " rows, not " + std::to_string(rows));
    return v;
  }
  // Text printed on the console and drawn in figures (names, units,
  // channels): no control characters.
  std::string Printable(const std::string& object) const { return Checked(object, r_.Text(object)); }
  std::vector<std::string> Printables(const std::string& object, std::size_t most) const {
    std::vector<std::string> texts = r_.Texts(object, AtMost(most));
    for (const std::string& t : texts) Checked(object, t);
    return texts;
  }
  // A name by the rule a budget's names follow (budget_yaml.cpp,
  // Budget::Validate): letters, digits, '_', '-' and '.', not "." or "..";
  // it names files of the report.
  std::string Name(const std::string& object) const {
    const std::string name = r_.Text(object);
    if (name.empty()) Fail(object, "holds an empty name; every name must be given");
    for (char ch : name)
      if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '-' || ch == '.'))
        Fail(object, "holds the name '" + Excerpt(name) +
                         "', which may contain only letters, digits, '_', '-' and '.' (as in a budget)");
    if (name == "." || name == "..") Fail(object, "holds the name '" + name + "', which names no file");
    return name;
  }
  // The entries listed in `names_object` (at most `bound`).
  std::size_t Count(const std::string& names_object, std::size_t bound) const {
    return r_.Texts(names_object, AtMost(bound)).size();
  }
  // A figure a result never has negative (a variance, a PSD, a CPS).
  double NonNegative(const std::string& object, bool allow_nan = false) const {
    const double v = r_.Number(object, allow_nan);
    if (v < 0.0) Fail(object, "holds " + NumberText(v) + ", which must be >= 0");
    return v;
  }
  std::vector<double> NonNegative(const std::string& object, std::vector<double> v) const {
    for (std::size_t i = 0; i < v.size(); ++i)
      if (v[i] < 0.0) Fail(object, "holds " + NumberText(v[i]) + " at element " + std::to_string(i) + ", which must be >= 0");
    return v;
  }
  // The text `object` as a value of enum T (its name table, enum_names.h).
  template <class T>
  T Enum(const std::string& object, const std::string& what) const {
    try {
      return ParseEnum<T>(r_.Text(object), what);
    } catch (const InputError& e) {
      Fail(object, e.message());
    }
  }
  std::size_t Index(const std::string& object, double value, std::size_t bound) const {
    if (!(value >= 0.0 && value < double(bound) && value == std::floor(value)))
      Fail(object, "holds the index " + NumberText(value) + ", not one of 0.." + std::to_string(bound) + "-1");
    return static_cast<std::size_t>(value);
  }
  // A whole number in [lo, hi] (integers of the store are int64; deb's are int).
  int Whole(const std::string& object, std::int64_t value, int lo, int hi) const {
    if (value < lo || value > hi)
      Fail(object, "holds " + std::to_string(value) + ", not one of " + std::to_string(lo) + ".." + std::to_string(hi));
    return static_cast<int>(value);
  }
  // `names` (of `list_object`'s entries) each once.
  void Unique(const std::string& list_object, const std::vector<std::string>& names, const std::string& what) const {
    std::set<std::string> seen;
    for (std::size_t i = 0; i < names.size(); ++i)
      if (!seen.insert(names[i]).second)
        Fail(At(list_object, i) + "/name", "holds the name '" + Excerpt(names[i]) + "', which another " + what +
                                                " has; names in a budget are unique");
  }

 private:
  const std::string& Checked(const std::string& object, const std::string& text) const {
    for (std::size_t i = 0; i < text.size(); ++i)
      if (ControlAt(text, i))
        Fail(object, "holds a control character at character " + std::to_string(i + 1) +
                         " ('" + Excerpt(text) + "'); names, units and channels are printable text");
    return text;
  }

  Hdf5Reader r_;
  std::string file_;
};

// The figures of a band requirement or band, by the budget's rules.
void CheckBand(const Reading& in, const std::string& object, double lo_hz, double hi_hz) {
  if (!(std::isfinite(lo_hz) && std::isfinite(hi_hz) && lo_hz > 0.0 && hi_hz > lo_hz))
    in.Fail(object, "holds the band [" + NumberText(lo_hz) + ", " + NumberText(hi_hz) +
                        "] Hz; a band needs 0 < lo_hz < hi_hz");
}

// A group path by the budget's rules (GroupSegments: names, depth, 'total').
std::string Group(const Reading& in, const std::string& object) {
  const std::string group = in.Printable(object);
  if (!group.empty()) {
    try {
      GroupSegments(group);
    } catch (const InputError& e) {
      in.Fail(object, e.message());
    }
  }
  return group;
}

ContributorResult ReadContributor(const Reading& in, const std::string& at, std::size_t n) {
  const Hdf5Reader& r = in.r();
  ContributorResult c;
  c.name = in.Name(at + "/name");
  c.source = in.Printable(at + "/source");
  c.path = in.Printable(at + "/path");
  c.inputs = in.Printables(at + "/inputs", kMaxChannels);
  c.group = Group(in, at + "/group");
  c.psd = in.NonNegative(at + "/psd", in.Numbers(at + "/psd", n));
  c.cps = in.NonNegative(at + "/cps", in.Numbers(at + "/cps", n));
  c.variance = in.NonNegative(at + "/variance");
  c.exact_variance = FromNone(in.NonNegative(at + "/exact_variance", true));
  c.exact_note = r.Text(at + "/exact_note");
  c.tail_variance_estimate = r.Number(at + "/tail_variance_estimate");
  for (const auto& t : in.Rows(at + "/tones", 2, limits::kMaxTones)) {
    if (!(t[0] > 0.0) || t[1] < 0.0)
      in.Fail(at + "/tones", "holds a tone at " + NumberText(t[0]) + " Hz of variance " + NumberText(t[1]) +
                                 "; a tone needs f_hz > 0 and a variance >= 0");
    c.tones.push_back({t[0], t[1]});
  }
  const std::vector<std::string> channels = in.Printables(at + "/channels/names", kMaxChannels);
  const auto psd = in.Exactly(at + "/channels/psd", channels.size(), channels.empty() ? 0 : n, false);
  const auto cps = in.Exactly(at + "/channels/cps", channels.size(), channels.empty() ? 0 : n, false);
  const auto variance = in.Numbers(at + "/channels/variance", channels.size());
  for (std::size_t k = 0; k < channels.size(); ++k) c.channels.push_back({channels[k], psd[k], cps[k], variance[k]});
  c.cross_variance = r.Number(at + "/channels/cross_variance");
  for (const auto& m : in.Rows(at + "/top_modes", 5, kMaxModes)) {
    if (!(m[0] >= 0.0 && m[0] <= double(limits::kMaxModes) && m[0] == std::floor(m[0])))
      in.Fail(at + "/top_modes", "holds the mode number " + NumberText(m[0]) + ", not one of 0.." +
                                     std::to_string(limits::kMaxModes));
    c.top_modes.push_back({static_cast<int>(m[0]), m[1], m[2], m[3], m[4]});
  }
  c.top_modes_of = in.Enum<ModeSplit>(at + "/top_modes_of", "mode split");
  return c;
}

void ReadOutput(const Reading& in, const std::string& at, std::size_t n, OutputOutline* spec, OutputResult* o) {
  const Hdf5Reader& r = in.r();
  o->name = in.Name(at + "/name");
  o->signal = in.Printable(at + "/signal");
  o->unit = in.Printable(at + "/unit");
  o->variance = in.NonNegative(at + "/variance");
  o->rms_max = FromNone(r.Number(at + "/rms_max", true));
  if (o->rms_max && !(*o->rms_max > 0.0))
    in.Fail(at + "/rms_max", "holds the requirement " + NumberText(*o->rms_max) + ", which must be > 0 (as in a budget)");
  const std::string metric = r.Text(at + "/metric/type");
  if (!metric.empty()) {
    OutputMetric m;
    m.type = in.Enum<MetricType>(at + "/metric/type", "metric type");
    m.window_s = r.Number(at + "/metric/window_s");
    if (!(m.window_s > 0.0))
      in.Fail(at + "/metric/window_s", "holds the window " + NumberText(m.window_s) + " s, which must be > 0");
    o->metric = m;
  }
  if (r.Integer(at + "/weighting/present") != 0) {
    // The filter itself is not stored: only what a report says of it.
    spec->weighting = WeightingOutline{in.Printable(at + "/weighting/unit"), r.Text(at + "/weighting/description")};
  }
  const std::vector<std::string> term_signals = in.Printables(at + "/combination/signals", kMaxTexts);
  const std::vector<double> term_weights = in.Numbers(at + "/combination/weights", term_signals.size());
  const std::vector<std::string> term_units = in.Printables(at + "/combination/units", kMaxTexts);
  if (term_units.size() != term_signals.size()) in.Fail(at + "/combination/units", "does not match the signals");
  for (std::size_t i = 0; i < term_signals.size(); ++i)
    spec->combination.push_back({term_signals[i], term_weights[i], term_units[i]});
  o->total_psd = in.NonNegative(at + "/total_psd", in.Numbers(at + "/total_psd", n));
  o->total_cps = in.NonNegative(at + "/total_cps", in.Numbers(at + "/total_cps", n));
  const auto limits = in.Rows(at + "/band_requirements/limits", 3, kMaxEntries);
  const auto requirement_variance =
      in.NonNegative(at + "/band_requirements/variance", in.Numbers(at + "/band_requirements/variance", limits.size()));
  for (std::size_t i = 0; i < limits.size(); ++i) {
    const BandRequirement b{limits[i][0], limits[i][1], limits[i][2]};
    CheckBand(in, at + "/band_requirements/limits", b.lo_hz, b.hi_hz);
    if (!(b.rms_max > 0.0))
      in.Fail(at + "/band_requirements/limits", "holds the requirement " + NumberText(b.rms_max) +
                                                    ", which must be > 0 (as in a budget)");
    o->band_requirements.push_back({b, requirement_variance[i]});
  }
  const std::size_t contributors = in.Count(at + "/contributors/names", kMaxEntries);
  for (std::size_t c = 0; c < contributors; ++c)
    o->contributors.push_back(ReadContributor(in, At(at + "/contributors", c), n));
  const auto edges = in.Rows(at + "/bands/edges_hz", 2, kMaxEntries);
  for (const auto& e : edges) CheckBand(in, at + "/bands/edges_hz", e[0], e[1]);
  const auto band_variance = in.NonNegative(at + "/bands/variance", in.Numbers(at + "/bands/variance", edges.size()));
  const auto band_contributors =
      in.Exactly(at + "/bands/contributor_variance", edges.size(), edges.empty() ? 0 : contributors, false);
  for (std::size_t b = 0; b < edges.size(); ++b)
    o->bands.push_back({Band{edges[b][0], edges[b][1]}, band_variance[b], band_contributors[b]});
  const std::size_t references = in.Count(at + "/references/names", kMaxEntries);
  for (std::size_t i = 0; i < references; ++i) {
    const std::string ra = At(at + "/references", i);
    ReferenceResult ref;
    ref.name = in.Printable(ra + "/name");
    ref.psd = in.NonNegative(ra + "/psd", in.Numbers(ra + "/psd", n));
    ref.cps = in.NonNegative(ra + "/cps", in.Numbers(ra + "/cps", n));
    ref.variance = in.NonNegative(ra + "/variance");
    ref.budget_variance = in.NonNegative(ra + "/budget_variance");
    const std::vector<double> covered = in.Numbers(ra + "/covered_hz", 2);
    ref.covered_lo_hz = covered[0];
    ref.covered_hi_hz = covered[1];
    for (double v : in.Numbers(ra + "/band_variance", edges.size(), true)) ref.band_variance.push_back(FromNone(v));
    o->references.push_back(std::move(ref));
  }
}

std::optional<PhaseCrossover> PhaseCrossoverOf(const Reading& in, const std::string& object) {
  const std::vector<double> v = in.UpTo(object, 2);
  if (v.empty()) return std::nullopt;
  if (v.size() != 2) in.Fail(object, "holds " + std::to_string(v.size()) + " values, not 0 or 2");
  return PhaseCrossover{v[0], v[1]};
}

void ReadLoop(const Reading& in, const std::string& at, std::size_t n, LoopResult* r, LoopTrace* trace) {
  const Hdf5Reader& h = in.r();
  r->plant = in.Printable(at + "/plant");
  r->controller = in.Printable(at + "/controller");
  r->sign = in.Whole(at + "/sign", h.Integer(at + "/sign"), -1, 1);
  if (r->sign == 0) in.Fail(at + "/sign", "holds 0, not -1 or +1");
  r->paths = in.Printables(at + "/paths", kMaxEntries);
  r->evaluated = h.Integer(at + "/evaluated") != 0;
  r->note = h.Text(at + "/note");
  if (h.Has(at + "/same_loop/plants")) {
    const std::vector<std::string> plants = in.Printables(at + "/same_loop/plants", kMaxEntries);
    const std::vector<std::string> controllers = in.Printables(at + "/same_loop/controllers", plants.size());
    const std::vector<double> signs = in.Numbers(at + "/same_loop/signs", plants.size());
    if (controllers.size() != plants.size() || signs.size() != plants.size())
      in.Fail(at + "/same_loop", "lists " + std::to_string(plants.size()) + " plants but " +
                                     std::to_string(controllers.size()) + " controllers and " +
                                     std::to_string(signs.size()) + " signs");
    for (std::size_t i = 0; i < plants.size(); ++i) {
      if (signs[i] != -1.0 && signs[i] != 1.0) in.Fail(at + "/same_loop/signs", "holds a sign other than -1 or +1");
      r->same_loop.push_back({plants[i], controllers[i], signs[i] < 0 ? -1 : 1});
    }
  }
  if (h.Has(at + "/required_margins")) {
    const std::vector<double> q = h.Numbers(at + "/required_margins", AtMost(3), true);
    if (q.size() != 3) in.Fail(at + "/required_margins", "holds " + std::to_string(q.size()) + " values, not 3");
    for (double v : q)
      if (!std::isnan(v) && !(v > 0.0)) in.Fail(at + "/required_margins", "holds a margin that is not > 0");
    if (!std::isnan(q[0])) r->required.gain_db = q[0];
    if (!std::isnan(q[1])) r->required.phase_deg = q[1];
    if (!std::isnan(q[2])) r->required.modulus = q[2];
  }
  LoopMargins& m = r->margins;
  m.channels = in.Whole(at + "/margins/channels", h.Integer(at + "/margins/channels"), 0, limits::kMaxChannels);
  for (const auto& c : in.Rows(at + "/margins/gain_crossovers", 2, n)) m.gain_crossovers.push_back({c[0], c[1]});
  for (const auto& c : in.Rows(at + "/margins/phase_crossovers", 2, n)) m.phase_crossovers.push_back({c[0], c[1]});
  if (const auto pm = PhaseCrossoverOf(in, at + "/margins/phase_margin")) m.phase_margin = GainCrossover{pm->f_hz, pm->gain_margin};
  m.upper_gain_margin = PhaseCrossoverOf(in, at + "/margins/upper_gain_margin");
  m.lower_gain_margin = PhaseCrossoverOf(in, at + "/margins/lower_gain_margin");
  const std::vector<double> modulus = in.Numbers(at + "/margins/modulus_margin", 2);
  m.modulus_margin = modulus[0];
  m.modulus_margin_f_hz = modulus[1];
  if (h.Has(at + "/approximations/blocks")) {
    const std::vector<std::string> blocks = in.Printables(at + "/approximations/blocks", kMaxEntries);
    const std::vector<std::string> how = in.Printables(at + "/approximations/approximations", blocks.size());
    const auto errors = in.Rows(at + "/approximations/errors", 3, blocks.size());
    if (how.size() != blocks.size() || errors.size() != blocks.size())
      in.Fail(at + "/approximations", "lists " + std::to_string(blocks.size()) + " blocks but " +
                                          std::to_string(how.size()) + " approximations and " +
                                          std::to_string(errors.size()) + " errors");
    for (std::size_t i = 0; i < blocks.size(); ++i)
      r->approximations.push_back({blocks[i], how[i], errors[i][0], errors[i][1], errors[i][2]});
  }
  trace->f_hz = in.UpTo(at + "/trace/f_hz", limits::kMaxGridPoints);
  const std::vector<double> re = in.Numbers(at + "/trace/loop_gain_re", trace->f_hz.size());
  const std::vector<double> im = in.Numbers(at + "/trace/loop_gain_im", trace->f_hz.size());
  for (std::size_t i = 0; i < re.size(); ++i) trace->loop_gain.emplace_back(re[i], im[i]);
}

Eigen::MatrixXd MatrixOf(const std::vector<std::vector<double>>& rows, std::size_t n) {
  Eigen::MatrixXd m(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) m(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = rows[i][j];
  return m;
}

CovarianceResult ReadCovariance(const Reading& in, const std::string& at, std::size_t outputs,
                                std::size_t contributors) {
  const Hdf5Reader& r = in.r();
  CovarianceResult c;
  c.outputs = in.Printables(at + "/outputs", outputs);
  const std::size_t n = c.outputs.size();
  c.units = in.Printables(at + "/units", n);
  if (c.units.size() != n) in.Fail(at + "/units", "does not match the outputs");
  for (double i : in.Numbers(at + "/index", n)) c.index.push_back(in.Index(at + "/index", i, outputs));
  c.matrix = MatrixOf(in.Exactly(at + "/matrix", n, n, false), n);
  c.correlation = MatrixOf(in.Exactly(at + "/correlation", n, n, true), n);
  const auto exact = in.Rows(at + "/exact_matrix", n, n);
  if (!exact.empty()) {
    if (exact.size() != n) in.Fail(at + "/exact_matrix", "has " + std::to_string(exact.size()) + " rows, not " + std::to_string(n));
    c.exact_matrix = MatrixOf(exact, n);
  }
  c.exact_note = r.Text(at + "/exact_note");
  const std::vector<std::string> names = in.Printables(at + "/contributors/names", contributors);
  if (names.size() != contributors)
    in.Fail(at + "/contributors/names", "lists " + std::to_string(names.size()) + " contributors, the budget " +
                                            std::to_string(contributors));
  for (std::size_t i = 0; i < names.size(); ++i)
    c.contributors.push_back({names[i], MatrixOf(in.Exactly(At(at + "/contributors", i) + "/matrix", n, n, false), n)});
  return c;
}

// The panels of a stored grid, as FrequencyGrid demands them: each
// kPanelNodes points at the Lobatto nodes of its ends, in order, touching
// but not overlapping (a store's panels are not trusted to be panels).
void CheckPanels(const Reading& in, const std::vector<double>& f_hz, const std::vector<std::size_t>& panels) {
  const std::vector<double>& x = FrequencyGrid::LobattoNodes();
  const std::size_t nodes = FrequencyGrid::kPanelNodes;
  std::size_t next_free = 0;
  for (std::size_t p : panels) {
    if (p < next_free || p + nodes > f_hz.size())
      in.Fail("result/grid/panel_starts", "holds the panel start " + std::to_string(p) +
                                              ": panels follow each other and have " + std::to_string(nodes) +
                                              " points within the grid's " + std::to_string(f_hz.size()));
    const double a = f_hz[p], b = f_hz[p + nodes - 1];
    for (std::size_t j = 1; j + 1 < nodes; ++j)
      if (!(std::abs(f_hz[p + j] - (a + 0.5 * (b - a) * (x[j] + 1.0))) <= 1e-9 * (b - a)))
        in.Fail("result/grid/panel_starts", "holds the panel start " + std::to_string(p) + ", but the points from " +
                                                std::to_string(p) + " do not lie at the Lobatto nodes of a panel");
    next_free = p + nodes - 1;
  }
}

// Whether two rows of numbers hold the same bits (a store read back draws
// exactly what the run drew, signs of zeros included).
bool SameBits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}
bool SameBits(const std::vector<std::vector<double>>& a, const std::vector<std::vector<double>>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t r = 0; r < a.size(); ++r)
    if (!SameBits(a[r], b[r])) return false;
  return true;
}

// The first response before traces.paths[c][o] (in the order the store
// writes them) whose frequencies, gains and phases are the same in every
// bit, if any.
std::optional<std::pair<std::size_t, std::size_t>> EarlierSameResponse(const ResponseTraces& traces, std::size_t c,
                                                                       std::size_t o) {
  const PathResponse& p = traces.paths[c][o];
  for (std::size_t ec = 0; ec <= c; ++ec)
    for (std::size_t eo = 0; eo < traces.paths[ec].size() && (ec < c || eo < o); ++eo) {
      const PathResponse& e = traces.paths[ec][eo];
      if (SameBits(e.f_hz, p.f_hz) && SameBits(e.gain2, p.gain2) && SameBits(e.phase_rad, p.phase_rad))
        return std::make_pair(ec, eo);
    }
  return std::nullopt;
}

}  // namespace

void WriteResultStore(const BudgetResult& result, const RunInfo& info, const std::string& file) {
  const BudgetOutline& outline = result.outline;
  DEB_DEMAND(result.traces && result.traces->paths.size() == outline.contributors.size());
  DEB_DEMAND(result.outputs.size() == outline.outputs.size());
  Hdf5Writer w(file);
  w.Text("schema", kResultStoreSchema);
  w.Integer("schema_version", kResultStoreVersion);
  w.Text("deb_version", DEB_VERSION);
  w.Text("budget/name", outline.name);
  w.Text("budget/description", outline.description);
  w.Text("budget/file", info.budget_file);
  w.Text("budget/sha256", info.budget_sha256);
  w.Text("budget/text", info.budget_text ? *info.budget_text : "");
  w.Text("budget/grid_type", ToString(outline.grid_kind));
  std::vector<std::vector<double>> bands;
  for (const Band& b : outline.bands) bands.push_back({b.lo_hz, b.hi_hz});
  w.Rows("budget/bands", bands);
  w.Number("run/seconds", info.seconds ? *info.seconds : kNone);
  w.Texts("budget/sources/names", Names(outline.sources, kName));
  for (std::size_t i = 0; i < outline.sources.size(); ++i) {
    const SourceOutline& s = outline.sources[i];
    const std::string at = At("budget/sources", i);
    w.Text(at + "/name", s.name);
    w.Text(at + "/description", s.description);
    w.Text(at + "/unit", s.unit);
    w.Texts(at + "/channels", s.channels);
  }
  w.Texts("budget/contributors/names", Names(outline.contributors, kName));
  for (std::size_t i = 0; i < outline.contributors.size(); ++i) {
    const Contributor& c = outline.contributors[i];
    const std::string at = At("budget/contributors", i);
    w.Text(at + "/name", c.name);
    w.Text(at + "/source", c.source);
    w.Text(at + "/path", c.path);
    w.Texts(at + "/inputs", c.inputs);
    w.Text(at + "/group", c.group);
    w.Text(at + "/exact", ToString(c.exact));
    w.Integer(at + "/breakdown_channels", c.breakdown_channels ? 1 : 0);
  }

  w.Text("result/budget_name", outline.name);
  w.Numbers("result/grid/f_hz", result.grid.f_hz());
  w.Numbers("result/grid/panel_starts", Indices(result.grid.panel_starts()));
  w.Texts("result/warnings", result.warnings);
  w.Texts("result/outputs/names", Names(result.outputs, kName));
  for (std::size_t o = 0; o < result.outputs.size(); ++o)
    WriteOutput(w, At("result/outputs", o), outline.outputs[o], result.outputs[o]);
  w.Texts("budget/covariance", outline.covariance);
  // What the report says of studies the budget holds but this run is not.
  w.Integer("budget/has_sweep", outline.has_sweep ? 1 : 0);
  w.Integer("budget/uncertain_parameters", static_cast<std::int64_t>(outline.uncertain_parameters));
  if (!outline.parameters.empty()) {
    w.Texts("budget/parameters/names", Names(outline.parameters, kName));
    for (std::size_t i = 0; i < outline.parameters.size(); ++i) {
      const ParameterOutline& p = outline.parameters[i];
      const std::string at = At("budget/parameters", i);
      w.Text(at + "/name", p.name);
      w.Text(at + "/expression", p.expression);
      w.Text(at + "/description", p.description);
      w.Integer(at + "/derived", p.derived ? 1 : 0);
      w.Number(at + "/value", p.value);
      w.Text(at + "/unit", p.unit);
    }
  }
  w.Integer("result/covariance/present", result.covariance ? 1 : 0);
  if (result.covariance) WriteCovariance(w, "result/covariance", *result.covariance);
  const ResponseTraces& traces = *result.traces;
  w.Texts("result/loops/names", Names(result.loops, [](const LoopResult& l) { return l.plant + " " + l.controller; }));
  for (std::size_t i = 0; i < result.loops.size(); ++i)
    WriteLoop(w, At("result/loops", i), result.loops[i], traces.loops[i]);
  std::vector<std::vector<double>> poles;
  for (const auto& p : traces.poles_hz) poles.push_back(p ? std::vector<double>{p->first, p->second} : std::vector<double>{kNone, kNone});
  w.Rows("result/traces/poles_hz", poles);
  for (std::size_t c = 0; c < traces.paths.size(); ++c)
    for (std::size_t o = 0; o < traces.paths[c].size(); ++o) {
      const PathResponse& p = traces.paths[c][o];
      const std::string at = At(At("result/traces/paths", c), o);
      w.Texts(at + "/channels", p.channels);
      w.Text(at + "/unit", p.unit);
      // Contributors of one path and inputs share its response: kept once.
      if (const auto same = EarlierSameResponse(traces, c, o)) {
        w.Integer(at + "/same_as_contributor", static_cast<std::int64_t>(same->first));
        w.Integer(at + "/same_as_output", static_cast<std::int64_t>(same->second));
        continue;
      }
      if (!p.f_hz.empty()) w.Numbers(at + "/f_hz", p.f_hz);
      w.Rows(at + "/gain2", p.gain2, formats::Packing::kRuns);
      w.Rows(at + "/phase_rad", p.phase_rad, formats::Packing::kRuns);
    }
  w.Close();
}

namespace {

// The budget's sources and contributors, each contributor's source among the sources.
void ReadSourcesAndContributors(const Reading& in, BudgetOutline* b) {
  const Hdf5Reader& r = in.r();
  const std::size_t sources = in.Count("budget/sources/names", kMaxEntries);
  for (std::size_t i = 0; i < sources; ++i) {
    const std::string at = At("budget/sources", i);
    SourceOutline src;
    src.name = in.Name(at + "/name");
    src.description = r.Text(at + "/description");
    src.unit = in.Printable(at + "/unit");
    src.channels = in.Printables(at + "/channels", kMaxChannels);
    b->sources.push_back(std::move(src));
  }
  in.Unique("budget/sources", Names(b->sources, kName), "source");
  const std::size_t contributors = in.Count("budget/contributors/names", kMaxEntries);
  for (std::size_t i = 0; i < contributors; ++i) {
    const std::string at = At("budget/contributors", i);
    Contributor c;
    c.name = in.Name(at + "/name");
    if (c.name == "total") in.Fail(at + "/name", "holds the name 'total', which is reserved for the sum of all contributors");
    c.source = in.Printable(at + "/source");
    c.path = in.Printable(at + "/path");
    c.inputs = in.Printables(at + "/inputs", kMaxChannels);
    c.group = Group(in, at + "/group");
    c.exact = in.Enum<ExactVariance>(at + "/exact", "exact-variance mode");
    c.breakdown_channels = r.Integer(at + "/breakdown_channels") != 0;
    bool known = false;
    for (const SourceOutline& src : b->sources) known |= src.name == c.source;
    if (!known) in.Fail(at + "/source", "names the source '" + Excerpt(c.source) + "', which the store does not hold");
    b->contributors.push_back(std::move(c));
  }
  in.Unique("budget/contributors", Names(b->contributors, kName), "contributor");
}

// The frequency grid and its panels, checked as FrequencyGrid checks a grid.
FrequencyGrid ReadGrid(const Reading& in) {
  std::vector<double> f_hz = in.UpTo("result/grid/f_hz", limits::kMaxGridPoints);
  std::vector<std::size_t> panels;
  for (double p : in.UpTo("result/grid/panel_starts", f_hz.size()))
    panels.push_back(in.Index("result/grid/panel_starts", p, f_hz.size()));
  try {
    static_cast<void>(FrequencyGrid(f_hz));  // throws on a bad grid
  } catch (const InputError& e) {
    in.Fail("result/grid", e.message());
  }
  CheckPanels(in, f_hz, panels);
  return FrequencyGrid(std::move(f_hz), std::move(panels));
}

// The parameters, in stores of budgets that have them (none before them).
void ReadParameters(const Reading& in, BudgetOutline* b) {
  const Hdf5Reader& r = in.r();
  if (r.Has("budget/parameters/names")) {
    const std::size_t parameters = in.Count("budget/parameters/names", kMaxParameters);
    for (std::size_t i = 0; i < parameters; ++i) {
      const std::string at = At("budget/parameters", i);
      ParameterOutline p;
      p.name = r.Text(at + "/name");
      if (!IsParameterName(p.name)) in.Fail(at + "/name", "holds '" + Excerpt(p.name) + "', which is not a parameter name");
      p.expression = in.Printable(at + "/expression");
      p.description = r.Text(at + "/description");
      p.derived = r.Integer(at + "/derived") != 0;
      p.value = r.Number(at + "/value");
      if (!std::isfinite(p.value)) in.Fail(at + "/value", "is not finite");
      p.unit = in.Printable(at + "/unit");
      b->parameters.push_back(std::move(p));
    }
    in.Unique("budget/parameters", Names(b->parameters, kName), "parameter");
  }
}

// The loops and every path's response, over the result's grid.
std::shared_ptr<ResponseTraces> ReadTraces(const Reading& in, const BudgetOutline& b, BudgetResult* res) {
  const Hdf5Reader& r = in.r();
  const std::size_t n = res->grid.size(), outputs = res->outputs.size(), contributors = b.contributors.size();
  auto traces = std::make_shared<ResponseTraces>();
  const std::size_t loops = in.Count("result/loops/names", kMaxEntries);
  res->loops.resize(loops);
  traces->loops.resize(loops);
  for (std::size_t i = 0; i < loops; ++i) ReadLoop(in, At("result/loops", i), n, &res->loops[i], &traces->loops[i]);
  for (const auto& p : in.Exactly("result/traces/poles_hz", contributors, contributors == 0 ? 0 : 2, true)) {
    const bool none = std::isnan(p[0]) || std::isnan(p[1]);
    traces->poles_hz.push_back(none ? std::nullopt : std::optional<std::pair<double, double>>({p[0], p[1]}));
  }
  traces->paths.resize(contributors);
  for (std::size_t c = 0; c < contributors; ++c)
    for (std::size_t o = 0; o < outputs; ++o) {
      const std::string at = At(At("result/traces/paths", c), o);
      PathResponse p;
      p.contributor = b.contributors[c].name;
      p.output = res->outputs[o].name;
      p.channels = in.Printables(at + "/channels", kMaxChannels);
      p.unit = in.Printable(at + "/unit");
      if (r.Has(at + "/same_as_contributor")) {  // schema version 2: gains and phases kept once
        const std::int64_t sc = r.Integer(at + "/same_as_contributor"), so = r.Integer(at + "/same_as_output");
        if (sc < 0 || so < 0 || static_cast<std::uint64_t>(so) >= outputs ||
            static_cast<std::uint64_t>(sc) * outputs + static_cast<std::uint64_t>(so) >= c * outputs + o)
          in.Fail(at + "/same_as_contributor", "names the response " + std::to_string(sc) + "/" + std::to_string(so) +
                                                   ", which is not one written before it");
        const PathResponse& same = traces->paths[static_cast<std::size_t>(sc)][static_cast<std::size_t>(so)];
        p.f_hz = same.f_hz;
        p.gain2 = same.gain2;
        p.phase_rad = same.phase_rad;
      } else {
        // Version 2: the response at its own frequencies, a rising part of the grid's.
        if (r.Has(at + "/f_hz")) {
          p.f_hz = in.UpTo(at + "/f_hz", n);
          if (p.f_hz.empty() || !std::is_sorted(p.f_hz.begin(), p.f_hz.end(), std::less_equal<double>()) ||
              p.f_hz.front() < res->grid.min_hz() || p.f_hz.back() > res->grid.max_hz())
            in.Fail(at + "/f_hz", "does not hold rising frequencies within the grid's " +
                                      std::to_string(res->grid.min_hz()) + " to " + std::to_string(res->grid.max_hz()) +
                                      " Hz");
        }
        const std::size_t points = p.f_hz.empty() ? n : p.f_hz.size();
        p.gain2 = in.Exactly(at + "/gain2", p.channels.size(), points, false);
        p.phase_rad = in.Exactly(at + "/phase_rad", p.gain2.size(), p.gain2.empty() ? 0 : points, false);
      }
      traces->paths[c].push_back(std::move(p));
    }
  return traces;
}

}  // namespace

BudgetResult ReadResultStore(const std::string& file, RunInfo* info) {
  const Reading in(file);
  const Hdf5Reader& r = in.r();
  if (!r.Has("schema") || r.Text("schema") != kResultStoreSchema)
    throw InputError(file + ": not a result store of deb (no /schema '" + std::string(kResultStoreSchema) + "')");
  const std::int64_t version = r.Integer("schema_version");
  if (version < 1 || version > kResultStoreVersion)
    throw InputError(file + ": result store schema version " + std::to_string(version) + "; this deb (" DEB_VERSION
                            ") reads versions 1 to " + std::to_string(kResultStoreVersion));
  BudgetResult res;
  BudgetOutline& b = res.outline;
  b.name = in.Name("budget/name");
  b.description = r.Text("budget/description");
  RunInfo run;
  run.budget_file = r.Text("budget/file");
  run.budget_sha256 = in.Printable("budget/sha256");
  run.budget_text = r.Text("budget/text");
  b.grid_kind = in.Enum<GridKind>("budget/grid_type", "grid type");
  for (const auto& band : in.Rows("budget/bands", 2, kMaxEntries)) {
    CheckBand(in, "budget/bands", band[0], band[1]);
    b.bands.push_back({band[0], band[1]});
  }
  run.seconds = FromNone(r.Number("run/seconds", true));
  ReadSourcesAndContributors(in, &b);
  const std::size_t contributors = b.contributors.size();

  if (in.Name("result/budget_name") != b.name)
    in.Fail("result/budget_name", "holds another name than budget/name ('" + Excerpt(b.name) + "')");
  res.grid = ReadGrid(in);
  const std::size_t n = res.grid.size();
  res.warnings = r.Texts("result/warnings", AtMost(kMaxTexts));
  const std::size_t outputs = in.Count("result/outputs/names", kMaxEntries);
  b.outputs.resize(outputs);
  res.outputs.resize(outputs);
  for (std::size_t o = 0; o < outputs; ++o) {
    const std::string at = At("result/outputs", o);
    ReadOutput(in, at, n, &b.outputs[o], &res.outputs[o]);
    if (res.outputs[o].contributors.size() != contributors)
      in.Fail(at + "/contributors/names", "lists " + std::to_string(res.outputs[o].contributors.size()) +
                                              " contributors, the budget " + std::to_string(contributors));
  }
  in.Unique("result/outputs", Names(res.outputs, kName), "output");
  b.covariance = in.Printables("budget/covariance", outputs);
  ReadParameters(in, &b);
  // Stores written before they were kept: no sweep, no tolerances.
  if (r.Has("budget/has_sweep")) b.has_sweep = r.Integer("budget/has_sweep") != 0;
  if (r.Has("budget/uncertain_parameters")) {
    const std::int64_t n = r.Integer("budget/uncertain_parameters");
    if (n < 0 || n > static_cast<std::int64_t>(kMaxParameters))
      in.Fail("budget/uncertain_parameters", "holds " + std::to_string(n) + ", not a count of parameters (0 to " +
                                                 std::to_string(kMaxParameters) + ")");
    b.uncertain_parameters = static_cast<std::size_t>(n);
  }
  if (r.Integer("result/covariance/present") != 0)
    res.covariance = ReadCovariance(in, "result/covariance", outputs, contributors);
  res.traces = ReadTraces(in, b, &res);
  if (info) *info = std::move(run);
  return res;
}

}  // namespace deb
