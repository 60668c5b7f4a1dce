#include "deb/load/uff_yaml.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <optional>

#include "deb/core/input_file.h"
#include "deb/core/limits.h"
#include "deb/core/number_text.h"
#include "deb/formats/uff58_file.h"
#include "deb/spectra/channel_set.h"
#include "deb/spectra/converted_spectrum.h"
#include "deb/spectra/measured_spectrum.h"
#include "deb/spectra/scaled_spectrum.h"
#include "deb/systems/frequency_model.h"
#include "deb/units/unit.h"

namespace deb::load {
namespace {

using formats::Uff58Record;
using formats::UffDof;
using formats::UffFunction;

// The datasets `records` as a list for a message: "#1 (PSD, ...), #2 (...)",
// at most 20.
std::string Listed(const std::vector<const Uff58Record*>& records) {
  std::string s;
  const std::size_t shown = std::min<std::size_t>(records.size(), 20);
  for (std::size_t i = 0; i < shown; ++i) s += (i ? ", " : "") + records[i]->Describe();
  if (records.size() > shown) s += " and " + std::to_string(records.size() - shown) + " more";
  return s.empty() ? "none" : s;
}

std::string AllListed(const std::vector<Uff58Record>& records) {
  std::vector<const Uff58Record*> all;
  for (const Uff58Record& r : records) all.push_back(&r);
  return Listed(all);
}

// The abscissa of `r` in Hz: its units label Hz, or none with the data type 18 (frequency).
void RequireHz(const YamlNode& file, const std::string& path, const Uff58Record& r) {
  std::string u = r.abscissa.units;
  for (char& ch : u) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  const bool none = u.empty() || u == "none";
  if (u == "hz" || (none && r.abscissa.data_type == 18)) return;
  file.Fail(path + ": dataset " + r.Describe() + " has its abscissa in '" + Excerpt(r.abscissa.units) +
            "' (data type " + std::to_string(r.abscissa.data_type) + "), not in Hz: deb reads spectra and FRFs over frequency");
}

// The points of `r` above 0 Hz, from its first such point: their indices.
std::size_t FirstPositive(const Uff58Record& r) {
  std::size_t i = 0;
  while (i < r.x.size() && r.x[i] <= 0.0) ++i;
  return i;
}

// The datasets `chosen` share the frequencies of the first; the frequencies above 0 Hz.
std::vector<double> SharedFrequencies(const YamlNode& file, const std::string& path,
                                      const std::vector<const Uff58Record*>& chosen) {
  const Uff58Record& first = *chosen.front();
  for (const Uff58Record* r : chosen) {
    RequireHz(file, path, *r);
    if (r->x != first.x)
      file.Fail(path + ": dataset " + r->Describe() + " has other frequencies than " + first.Describe() + " (" +
                std::to_string(r->points()) + " and " + std::to_string(first.points()) +
                " points): the datasets of one path or source must share them");
  }
  const std::size_t from = FirstPositive(first);
  return std::vector<double>(first.x.begin() + static_cast<std::ptrdiff_t>(from), first.x.end());
}

std::vector<UffDof> Dofs(const YamlNode& list) {
  std::vector<UffDof> dofs;
  for (const YamlNode& e : list.Elements()) dofs.push_back(AtNode(e, [&] { return formats::ParseUffDof(e.AsString()); }));
  if (dofs.empty()) list.Fail("list at least one DOF NODE:DIRECTION");
  return dofs;
}

// Every distinct DOF of one side of `records`, in file order.
std::vector<UffDof> DistinctDofs(const std::vector<const Uff58Record*>& records, bool response) {
  std::vector<UffDof> dofs;
  for (const Uff58Record* r : records) {
    const UffDof& d = response ? r->response : r->reference;
    if (std::find(dofs.begin(), dofs.end(), d) == dofs.end()) dofs.push_back(d);
  }
  return dofs;
}

// The unit of a channel from the file: one label for every dataset of the row or column.
std::optional<std::string> FileUnit(const std::vector<const Uff58Record*>& records, bool numerator) {
  std::optional<std::string> unit;
  for (const Uff58Record* r : records) {
    const std::optional<std::string> u = formats::UffUnitText(numerator ? r->numerator.units : r->denominator.units);
    if (!u || (unit && *unit != *u)) return std::nullopt;
    unit = u;
  }
  return unit;
}

std::vector<std::string> DeclaredUnits(const YamlNode& node, const std::string& single, const std::string& list,
                                       std::size_t count) {
  const auto one = node.Optional(single), many = node.Optional(list);
  if (one && many) many->Fail("give '" + single + "' or '" + list + "', not both");
  if (one) return std::vector<std::string>(count, one->AsString());
  if (!many) return {};
  std::vector<std::string> units = many->AsStrings();
  if (units.size() != count)
    many->Fail(std::to_string(units.size()) + " unit(s) given, the path has " + std::to_string(count));
  return units;
}

// The file's datasets; an error in the file is reported at the budget's
// `file:` key, the file's own line (or byte) kept in the message, as for
// every data file a budget names.
std::vector<Uff58Record> ReadAtKey(const YamlNode& file, const std::string& path) {
  try {
    return formats::ReadUff58(path);
  } catch (const InputError& e) {
    file.Fail(e.what());
  }
}

// What a source may take from a universal file: the candidates' kind, in
// messages.
struct DatasetKind {
  std::string one, many, rule;  // "time response", "time responses", "no time response (function type 1)"
};

// The datasets a source's `responses:` (DOFs) or `datasets:` (positions)
// choose among `candidates`, or the one candidate when it gives neither.
std::vector<const Uff58Record*> Choose(const YamlNode& spec, const YamlNode& file, const std::string& path,
                                       const std::vector<Uff58Record>& records,
                                       const std::vector<const Uff58Record*>& candidates, const DatasetKind& kind) {
  const auto responses_node = spec.Optional("responses"), datasets_node = spec.Optional("datasets");
  if (responses_node && datasets_node) datasets_node->Fail("give 'responses' or 'datasets', not both");
  std::vector<const Uff58Record*> chosen;
  if (datasets_node) {
    for (const YamlNode& e : datasets_node->Elements()) {
      const int k = e.AsInt();
      const auto it = std::find_if(records.begin(), records.end(), [&](const Uff58Record& r) { return r.index == k; });
      if (it == records.end())
        e.Fail(path + " has no dataset 58 #" + std::to_string(k) + "; its datasets 58: " + AllListed(records));
      if (std::find(candidates.begin(), candidates.end(), &*it) == candidates.end())
        e.Fail("dataset " + it->Describe() + " of " + path + " is " + kind.rule);
      chosen.push_back(&*it);
    }
    if (chosen.empty()) datasets_node->Fail("list at least one dataset number");
  } else if (responses_node) {
    for (const YamlNode& e : responses_node->Elements()) {
      const UffDof dof = AtNode(e, [&] { return formats::ParseUffDof(e.AsString()); });
      const Uff58Record* found = nullptr;
      for (const Uff58Record* r : candidates) {
        if (!(r->response == dof)) continue;
        if (found)
          e.Fail(path + ": datasets " + found->Describe() + " and " + r->Describe() + " both hold a " + kind.one +
                 " of " + formats::ToString(dof) + ": choose one with 'datasets' (numbers)");
        found = r;
      }
      if (!found)
        e.Fail(path + " holds no " + kind.one + " of response " + formats::ToString(dof) + "; its " + kind.many +
               ": " + Listed(candidates));
      chosen.push_back(found);
    }
    if (chosen.empty()) responses_node->Fail("list at least one DOF NODE:DIRECTION");
  } else {
    if (candidates.size() != 1)
      file.Fail(path + " holds " + std::to_string(candidates.size()) + " " + kind.many +
                "; choose with 'responses' (DOFs) or 'datasets' (numbers): " + Listed(candidates));
    chosen = candidates;
  }
  if (chosen.size() > static_cast<std::size_t>(limits::kMaxChannels))
    file.Fail(std::to_string(chosen.size()) + " datasets are more than the " + std::to_string(limits::kMaxChannels) +
              " channels a source may have");
  return chosen;
}

}  // namespace

void ParseUffFrfPath(const YamlNode& node, const std::string& path, Path& p) {
  const YamlNode file = node.Required("file");
  const std::vector<Uff58Record> records = ReadAtKey(file, path);
  std::vector<const Uff58Record*> frfs;
  for (const Uff58Record& r : records)
    if (r.function == UffFunction::kFrf || r.function == UffFunction::kTransmissibility) frfs.push_back(&r);
  if (frfs.empty())
    file.Fail(path + " holds no FRF (function type 4) or transmissibility (5) dataset; its datasets 58: " +
              AllListed(records));
  const auto responses_node = node.Optional("responses"), references_node = node.Optional("references");
  const std::vector<UffDof> responses = responses_node ? Dofs(*responses_node) : DistinctDofs(frfs, true);
  const std::vector<UffDof> references = references_node ? Dofs(*references_node) : DistinctDofs(frfs, false);
  const std::size_t n_out = responses.size(), n_in = references.size();
  if (n_out > static_cast<std::size_t>(limits::kMaxChannels) || n_in > static_cast<std::size_t>(limits::kMaxChannels))
    file.Fail(path + ": more than " + std::to_string(limits::kMaxChannels) + " outputs or inputs");
  // entry[i][j]: the dataset with response i and reference j.
  std::vector<std::vector<const Uff58Record*>> entry(n_out, std::vector<const Uff58Record*>(n_in, nullptr));
  std::vector<const Uff58Record*> chosen;
  for (std::size_t i = 0; i < n_out; ++i)
    for (std::size_t j = 0; j < n_in; ++j) {
      for (const Uff58Record* r : frfs) {
        if (!(r->response == responses[i] && r->reference == references[j])) continue;
        if (entry[i][j])
          file.Fail(path + ": datasets " + entry[i][j]->Describe() + " and " + r->Describe() +
                    " both hold the FRF from " + formats::ToString(references[j]) + " to " +
                    formats::ToString(responses[i]) + "; deb cannot tell which to take");
        entry[i][j] = r;
      }
      if (!entry[i][j]) {
        const YamlNode at = responses_node ? *responses_node : references_node ? *references_node : file;
        at.Fail(path + " holds no FRF with response " + formats::ToString(responses[i]) + " and reference " +
                formats::ToString(references[j]) + "; its FRFs: " + Listed(frfs));
      }
      chosen.push_back(entry[i][j]);
    }
  const std::vector<double> f_hz = SharedFrequencies(file, path, chosen);
  const std::size_t from = chosen.front()->points() - f_hz.size();

  // Units: declared (converted to) or the file's numerator and denominator.
  std::vector<std::string> out_units = DeclaredUnits(node, "output_unit", "output_units", n_out);
  std::vector<std::string> in_units = DeclaredUnits(node, "input_unit", "input_units", n_in);
  const bool declared_out = !out_units.empty(), declared_in = !in_units.empty();
  for (std::size_t i = 0; i < n_out && !declared_out; ++i) {
    const auto u = FileUnit(entry[i], true);
    if (!u)
      node.Fail("missing 'output_unit': the datasets of response " + formats::ToString(responses[i]) +
                " do not give one numerator unit (record 9) for it");
    out_units.push_back(*u);
  }
  for (std::size_t j = 0; j < n_in && !declared_in; ++j) {
    std::vector<const Uff58Record*> column;
    for (std::size_t i = 0; i < n_out; ++i) column.push_back(entry[i][j]);
    const auto u = FileUnit(column, false);
    if (!u)
      node.Fail("missing 'input_unit': the datasets of reference " + formats::ToString(references[j]) +
                " do not give one denominator unit (record 10) for it");
    in_units.push_back(*u);
  }
  const YamlNode unit_at = node.Has("output_unit")    ? node.Required("output_unit")
                           : node.Has("output_units") ? node.Required("output_units")
                                                      : node;
  std::vector<Eigen::MatrixXcd> h(f_hz.size(), Eigen::MatrixXcd::Zero(static_cast<Eigen::Index>(n_out),
                                                                       static_cast<Eigen::Index>(n_in)));
  for (std::size_t i = 0; i < n_out; ++i)
    for (std::size_t j = 0; j < n_in; ++j) {
      const Uff58Record& r = *entry[i][j];
      std::optional<UnitConversion> conversion;
      if (const std::optional<std::string> unit = formats::UffOrdinateUnit(r)) {
        const std::string to = "(" + out_units[i] + ")/(" + in_units[j] + ")";
        try {
          conversion = ConvertUnit(*unit, to);
        } catch (const InputError& e) {
          unit_at.Fail("dataset " + r.Describe() + " of " + path + " is in '" + *unit + "' (records 9 and 10), which does not convert to " + to + ": " + e.message());
        }
      }
      for (std::size_t k = 0; k < f_hz.size(); ++k) {
        const std::complex<double> v = r.y[from + k];
        h[k](static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) =
            conversion ? conversion->ResponseFactor(f_hz[k]) * v : v;
      }
    }
  const Extrapolation extrapolation =
      node.Has("extrapolation")
          ? AtNode(node.Required("extrapolation"), [&] { return ParseExtrapolation(node.Required("extrapolation").AsString()); })
          : Extrapolation::kError;
  MeasuredResponse response =
      AtNode(file, [&] { return MeasuredResponse(f_hz, std::move(h), extrapolation, path); });
  for (const UffDof& d : responses) p.output_names.push_back(formats::ToString(d));
  for (const UffDof& d : references) p.input_names.push_back(formats::ToString(d));
  p.output_units = out_units;
  p.input_units = in_units;
  p.system = StateSpace::Gain(Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(n_out), static_cast<Eigen::Index>(n_in)));
  p.measured = std::make_shared<const FrequencyModel>(std::move(response));
}

std::shared_ptr<const Spectrum> ParseUffSpectrum(const YamlNode& node, const YamlNode& spec, const std::string& path,
                                                 Source* s) {
  const YamlNode file = spec.Required("file");
  if (spec.Has("columns"))
    spec.Required("columns").Fail("a universal file has no columns: choose its datasets with 'responses' (DOFs) or 'datasets' (numbers)");
  const std::vector<Uff58Record> records = ReadAtKey(file, path);
  std::vector<const Uff58Record*> spectra;
  for (const Uff58Record& r : records)
    if (r.function == UffFunction::kPsd || r.function == UffFunction::kAutoSpectrum) spectra.push_back(&r);

  const std::vector<const Uff58Record*> chosen =
      Choose(spec, file, path, records, spectra, {"PSD or auto spectrum", "PSDs and auto spectra",
                                                  "no PSD (function type 9) or auto spectrum (2)"});
  const std::vector<double> f_hz = SharedFrequencies(file, path, chosen);
  const std::size_t from = chosen.front()->points() - f_hz.size();
  const auto unit_node = node.Optional("unit");
  if (unit_node) s->unit = unit_node->AsString();
  Eigen::MatrixXd psd(static_cast<Eigen::Index>(f_hz.size()), static_cast<Eigen::Index>(chosen.size()));
  std::vector<std::optional<UnitConversion>> conversions;
  std::vector<std::string> table_units;  // the unit of each dataset's values (a PSD in its square per Hz)
  for (std::size_t c = 0; c < chosen.size(); ++c) {
    const Uff58Record& r = *chosen[c];
    const std::optional<formats::UffDensityUnit> density = formats::UffDensity(r);
    const std::optional<std::string> unit = formats::UffOrdinateUnit(r);
    if (!density && (unit || r.function == UffFunction::kAutoSpectrum))
      file.Fail(path + ": dataset " + r.Describe() + " is in '" + unit.value_or("NONE") +
                "' (records 9 and 10), which is no density: deb reads spectra as a PSD in unit^2/Hz or an ASD in "
                "unit/sqrt(Hz); " +
                (r.function == UffFunction::kAutoSpectrum
                     ? "an auto spectrum in another unit is a power or RMS spectrum, which depends on the analyser's "
                       "resolution: export it as a PSD"
                     : "a PSD's unit must say so"));
    for (std::size_t k = 0; k < f_hz.size(); ++k) {
      const std::complex<double> v = r.y[from + k];
      if (v.imag() != 0.0)
        file.Fail(path + ": dataset " + r.Describe() + " has a value with an imaginary part at " +
                  Excerpt(std::to_string(f_hz[k])) + " Hz; a PSD is real");
      psd(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(c)) =
          density && density->amplitude ? v.real() * v.real() : v.real();
    }
    if (!density) {
      if (!unit_node)
        node.Fail("missing 'unit': dataset " + r.Describe() + " of " + path + " gives no unit (record 9 is NONE)");
      s->notes.push_back("dataset " + r.Describe() + " of " + path + " gives no unit: its values are read as a PSD in " +
                         PsdUnitLabel(s->unit));
      conversions.emplace_back();
      table_units.push_back(s->unit);
      continue;
    }
    if (!unit_node) {
      if (c > 0 && s->unit != density->signal_unit)
        node.Fail("missing 'unit': the datasets are in " + s->unit + " and " + density->signal_unit +
                  "; give the unit to convert them to");
      s->unit = density->signal_unit;
    }
    const YamlNode at = unit_node ? *unit_node : node;
    conversions.push_back(AtNode(at, [&] { return ConvertUnit(density->signal_unit, s->unit); }));
    table_units.push_back(density->signal_unit);
  }
  // One channel per dataset, the conversion of its unit applied.
  MeasuredSpectrumOptions options;
  if (auto e = spec.Optional("extrapolation"))
    options.extrapolation = AtNode(*e, [&] { return ParseExtrapolation(e->AsString()); });
  options.origin = path;
  std::vector<std::string> names;
  for (const Uff58Record* r : chosen) {
    std::string name = r->response_entity.empty() || r->response_entity == "NONE" ? formats::ToString(r->response)
                                                                                  : r->response_entity;
    if (std::find(names.begin(), names.end(), name) != names.end()) name += " #" + std::to_string(r->index);
    names.push_back(name);
  }
  std::vector<std::shared_ptr<const Spectrum>> channels;
  for (std::size_t c = 0; c < chosen.size(); ++c) {
    MeasuredSpectrumOptions one = options;
    one.channel_names = {names[c]};
    one.unit = table_units[c];
    std::shared_ptr<const Spectrum> m = AtNode(file, [&] {
      return std::make_shared<MeasuredSpectrum>(f_hz, Eigen::MatrixXd(psd.col(static_cast<Eigen::Index>(c))), one);
    });
    const std::optional<UnitConversion>& conv = conversions[c];
    if (conv && !conv->IsPureScale())
      m = std::make_shared<ConvertedSpectrum>(m, conv->scale, conv->derivative_order, s->unit);
    else if (conv && conv->scale != 1.0)
      m = std::make_shared<ScaledSpectrum>(m, conv->scale * conv->scale);
    channels.push_back(m);
  }
  s->channel_names = names;
  if (auto c = node.Optional("channels")) {
    s->channel_names = c->AsStrings();
    if (s->channel_names.size() != chosen.size())
      c->Fail("the file gives " + std::to_string(chosen.size()) + " dataset(s) but " +
              std::to_string(s->channel_names.size()) + " channel names are listed");
  }
  if (channels.size() == 1) return channels.front();
  return std::make_shared<IndependentChannels>(std::move(channels));
}

TimeSeries ReadUffRecording(const YamlNode& spec, const std::string& path) {
  const YamlNode file = spec.Required("file");
  for (const char* key : {"format", "rate_hz", "file_channels", "columns"})
    if (spec.Has(key))
      spec.Required(key).Fail(std::string("not with a universal file, which gives its sample rate (record 7) and ") +
                              "its channels (datasets): choose them with 'responses' (DOFs) or 'datasets' (numbers)");
  const std::vector<Uff58Record> records = ReadAtKey(file, path);
  std::vector<const Uff58Record*> responses;
  for (const Uff58Record& r : records)
    if (r.function == UffFunction::kTimeResponse) responses.push_back(&r);
  const std::vector<const Uff58Record*> chosen =
      Choose(spec, file, path, records, responses,
             {"time response", "time responses", "no time response (function type 1)"});
  const Uff58Record& first = *chosen.front();
  // The time step in seconds: the abscissa's unit, or seconds for the data type time (17) without one.
  const auto step_s = [&](const Uff58Record& r) {
    const std::string at = path + ": dataset " + r.Describe() + ": ";
    const std::optional<std::string> x_unit = formats::UffUnitText(r.abscissa.units);
    if (x_unit ? !AtNode(file, [&] { return UnitsCommensurate(*x_unit, "s"); }) : r.abscissa.data_type != 17)
      file.Fail(at + "its abscissa is in '" + r.abscissa.units + "' (record 8), not in time");
    const double dt = x_unit ? r.abscissa_increment * AtNode(file, [&] { return ConvertUnit(*x_unit, "s"); }).scale
                             : r.abscissa_increment;
    if (!(dt > 0.0) || !std::isfinite(1.0 / dt))
      file.Fail(at + "a time step of " + NumberText(dt) + " s (record 7): it must be > 0");
    return dt;
  };
  const double dt_s = step_s(first);
  const std::optional<std::string> unit = formats::UffOrdinateUnit(first);
  std::vector<std::string> names;
  for (const Uff58Record* r : chosen) {
    const std::string at = path + ": dataset " + r->Describe() + ": ";
    if (r->is_complex()) file.Fail(at + "complex values; a time response is real");
    if (!r->even_spacing) file.Fail(at + "uneven spacing; a recording is sampled at one rate");
    if (step_s(*r) != dt_s || r->points() != first.points())
      file.Fail(at + std::to_string(r->points()) + " samples every " + NumberText(step_s(*r)) + " s, but dataset " +
                first.Describe() + " has " + std::to_string(first.points()) + " every " + NumberText(dt_s) +
                " s: the channels of one recording share them");
    if (formats::UffOrdinateUnit(*r) != unit)
      file.Fail(at + "in '" + formats::UffOrdinateUnit(*r).value_or("NONE") + "', dataset " + first.Describe() +
                " in '" + unit.value_or("NONE") + "': the channels of one recording share a unit");
    std::string name = formats::ToString(r->response);
    if (std::find(names.begin(), names.end(), name) != names.end()) name += " #" + std::to_string(r->index);
    names.push_back(name);
  }
  Eigen::MatrixXd samples(static_cast<Eigen::Index>(first.points()), static_cast<Eigen::Index>(chosen.size()));
  for (std::size_t c = 0; c < chosen.size(); ++c)
    for (std::size_t n = 0; n < first.points(); ++n)
      samples(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(c)) = chosen[c]->y[n].real();
  return AtNode(file, [&] { return TimeSeries(1.0 / dt_s, std::move(samples), names, unit.value_or(""), path); });
}

}  // namespace deb::load
