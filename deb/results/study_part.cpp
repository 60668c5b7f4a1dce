#include "deb/results/study_part.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>

#include "deb/core/error.h"
#include "deb/core/input_file.h"
#include "deb/uncertainty/sample_design.h"
#include "deb/version.h"

namespace deb {

namespace {

using Json = nlohmann::ordered_json;

constexpr const char* kKind = "deb uncertainty part";
constexpr const char* kSweepKind = "deb sweep part";

std::string PartPath(const std::string& dir) {
  const std::string path = (std::filesystem::path(dir) / "part.json").string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError(dir + ": no part.json: not a part of a sharded study (deb uncertainty|sweep --shard K/N writes one)");
  return path;
}

Json ReadPartJson(const std::string& path) {
  const std::string text = ReadInputFile(path, "a study's part", kMaxPartBytes);
  try {
    Json j = Json::parse(text);
    if (!j.is_object()) throw InputError(path + ": not a part of a sharded study");
    return j;
  } catch (const Json::exception& e) {
    throw InputError(path + ": not JSON: " + e.what());
  }
}

void HeaderToJson(const StudyPartHeader& h, Json* j) {
  (*j)["deb_version"] = DEB_VERSION;
  (*j)["digest"] = h.digest;
  (*j)["budget"] = h.budget;
  (*j)["overrides"] = h.overrides;
  (*j)["method"] = h.method;
  (*j)["seed"] = h.seed;
  (*j)["samples"] = h.samples;
  (*j)["shard"] = {h.shard.index, h.shard.count};
}

// A whole number >= 0 as the JSON writes one (not a float, which converted
// to an integer out of range is undefined, nor a negative number).
std::uint64_t Count(const Json& x, const std::string& what, const std::string& path) {
  if (!x.is_number_unsigned()) throw InputError(path + ": " + what + " must be a whole number >= 0, not " + x.dump());
  return x.get<std::uint64_t>();
}

// The header and the block [begin, end) of total; checks the shard and the block.
StudyPartHeader HeaderFromJson(const Json& j, const std::string& path, std::size_t* total, std::size_t* begin,
                               std::size_t* end) {
  const auto fail = [&](const std::string& why) { return InputError(path + ": " + why); };
  StudyPartHeader h;
  h.digest = j.at("digest").get<std::string>();
  h.budget = j.at("budget").get<std::string>();
  h.overrides = j.at("overrides").get<std::vector<std::string>>();
  h.method = j.at("method").get<std::string>();
  h.seed = Count(j.at("seed"), "seed", path);
  h.samples = Count(j.at("samples"), "samples", path);
  const Json& shard = j.at("shard");
  if (!shard.is_array() || shard.size() != 2) throw fail("shard must be [K, N]");
  h.shard = {Count(shard[0], "shard", path), Count(shard[1], "shard", path)};
  *total = Count(j.at("evaluations"), "evaluations", path);
  *begin = Count(j.at("begin"), "begin", path);
  *end = Count(j.at("end"), "end", path);
  const StudyShard& s = h.shard;
  if (!s.Valid())
    throw fail("shard " + std::to_string(s.index) + "/" + std::to_string(s.count) + " is not K/N with 1 <= K <= N <= " +
               std::to_string(kMaxShards));
  if (std::make_pair(*begin, *end) != s.Range(*total))
    throw fail("evaluations " + std::to_string(*begin) + " to " + std::to_string(*end) + " are not shard " +
               std::to_string(s.index) + "/" + std::to_string(s.count) + "'s");
  return h;
}

double FiniteNumber(const Json& x, const std::string& path) {
  if (!x.is_number()) throw InputError(path + ": a figure is not a number");
  const double v = x.get<double>();
  if (!std::isfinite(v)) throw InputError(path + ": a figure is not finite");
  return v;
}

Json SweepResultToJson(const BudgetResult& r) {
  Json outputs = Json::array();
  for (const OutputResult& o : r.outputs) {
    Json jo;
    jo["name"] = o.name;
    jo["signal"] = o.signal;
    jo["unit"] = o.unit;
    jo["variance"] = o.variance;
    jo["rms_max"] = o.rms_max ? Json(*o.rms_max) : Json(nullptr);
    Json cs = Json::array();
    for (const ContributorResult& c : o.contributors)
      cs.push_back({{"name", c.name}, {"source", c.source}, {"path", c.path}, {"group", c.group}, {"variance", c.variance}});
    jo["contributors"] = cs;
    Json bs = Json::array();
    for (const BandRequirementResult& b : o.band_requirements)
      bs.push_back({{"lo_hz", b.requirement.lo_hz}, {"hi_hz", b.requirement.hi_hz}, {"rms_max", b.requirement.rms_max},
                    {"variance", b.variance}});
    jo["band_requirements"] = bs;
    outputs.push_back(jo);
  }
  return {{"outputs", outputs}};
}

// @throws Json::exception for a missing key or a wrong type; InputError for
//   a figure that is not a finite number.
BudgetResult SweepResultFromJson(const Json& jr, const std::string& path) {
  BudgetResult r;
  for (const Json& jo : jr.at("outputs")) {
    OutputResult o;
    o.name = jo.at("name").get<std::string>();
    o.signal = jo.at("signal").get<std::string>();
    o.unit = jo.at("unit").get<std::string>();
    o.variance = FiniteNumber(jo.at("variance"), path);
    if (!jo.at("rms_max").is_null()) o.rms_max = FiniteNumber(jo.at("rms_max"), path);
    for (const Json& jc : jo.at("contributors")) {
      ContributorResult c;
      c.name = jc.at("name").get<std::string>();
      c.source = jc.at("source").get<std::string>();
      c.path = jc.at("path").get<std::string>();
      c.group = jc.at("group").get<std::string>();
      c.variance = FiniteNumber(jc.at("variance"), path);
      o.contributors.push_back(std::move(c));
    }
    for (const Json& jb : jo.at("band_requirements")) {
      BandRequirementResult b;
      b.requirement.lo_hz = FiniteNumber(jb.at("lo_hz"), path);
      b.requirement.hi_hz = FiniteNumber(jb.at("hi_hz"), path);
      b.requirement.rms_max = FiniteNumber(jb.at("rms_max"), path);
      b.variance = FiniteNumber(jb.at("variance"), path);
      o.band_requirements.push_back(b);
    }
    r.outputs.push_back(std::move(o));
  }
  return r;
}

SweepPartFile SweepPartFromJson(const Json& j, const std::string& path) {
  SweepPartFile f;
  try {
    f.header = HeaderFromJson(j, path, &f.total, &f.begin, &f.end);
    for (const Json& jr : j.at("results")) f.results.push_back(SweepResultFromJson(jr, path));
  } catch (const Json::exception& e) {
    throw InputError(path + ": a key is missing or of the wrong type: " + e.what());
  }
  if (f.results.size() != f.end - f.begin)
    throw InputError(path + ": " + std::to_string(f.results.size()) + " results for " +
                     std::to_string(f.end - f.begin) + " variants");
  return f;
}

UncertaintyPartFile UncertaintyPartFromJson(const Json& j, const std::string& path) {
  const auto fail = [&](const std::string& why) { return InputError(path + ": " + why); };
  UncertaintyPartFile f;
  try {
    f.header = HeaderFromJson(j, path, &f.part.total, &f.part.begin, &f.part.end);
    if (f.header.samples < 1 || f.header.samples > kMaxUncertaintySamples)
      throw fail("samples " + std::to_string(f.header.samples) + " outside 1 to " +
                 std::to_string(kMaxUncertaintySamples));
    try {
      ParseSamplingMethod(f.header.method);
    } catch (const InputError& e) {
      throw fail("method: " + e.message());
    }
    const Json& values = j.at("values");
    if (!values.is_array()) throw fail("values must be a list");
    for (const Json& row : values) {
      if (!row.is_array()) throw fail("values must be a list of lists of numbers");
      std::vector<double> v;
      for (const Json& x : row) v.push_back(FiniteNumber(x, path));
      f.part.values.push_back(std::move(v));
    }
  } catch (const Json::exception& e) {
    throw fail(std::string("a key is missing or of the wrong type: ") + e.what());
  }
  if (f.part.values.size() != f.part.end - f.part.begin)
    throw fail(std::to_string(f.part.values.size()) + " rows of values for " +
               std::to_string(f.part.end - f.part.begin) + " evaluations");
  return f;
}

}  // namespace

std::string SweepResultText(const BudgetResult& r) { return SweepResultToJson(r).dump(); }

BudgetResult SweepResultFromText(const std::string& text) {
  try {
    return SweepResultFromJson(Json::parse(text), "a sweep variant's result");
  } catch (const Json::exception& e) {
    throw InputError(std::string("a sweep variant's result: ") + e.what());
  }
}

std::string SweepPartJson(const SweepPartFile& part) {
  Json j;
  j["kind"] = kSweepKind;
  HeaderToJson(part.header, &j);
  j["evaluations"] = part.total;
  j["begin"] = part.begin;
  j["end"] = part.end;
  Json results = Json::array();
  for (const BudgetResult& r : part.results) results.push_back(SweepResultToJson(r));
  j["results"] = results;
  return j.dump() + "\n";
}

std::string UncertaintyPartJson(const StudyPartHeader& h, const UncertaintyPart& part) {
  Json j;
  j["kind"] = kKind;
  HeaderToJson(h, &j);
  j["evaluations"] = part.total;
  j["begin"] = part.begin;
  j["end"] = part.end;
  // nlohmann writes a double with the digits that read back to it exactly.
  j["values"] = part.values;
  return j.dump() + "\n";
}

std::variant<UncertaintyPartFile, SweepPartFile> ReadStudyPart(const std::string& dir) {
  const std::string path = PartPath(dir);
  const Json j = ReadPartJson(path);
  const auto at = j.find("kind");
  const std::string kind = at != j.end() && at->is_string() ? at->get<std::string>() : "";
  if (kind == kKind) return UncertaintyPartFromJson(j, path);
  if (kind == kSweepKind) return SweepPartFromJson(j, path);
  throw InputError(path + ": not the part of a sharded study (deb uncertainty|sweep --shard K/N writes one)");
}

}  // namespace deb
