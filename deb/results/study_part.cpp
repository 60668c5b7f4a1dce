#include "deb/results/study_part.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>

#include "deb/core/error.h"
#include "deb/core/input_file.h"
#include "deb/version.h"

namespace deb {

namespace {

using Json = nlohmann::ordered_json;

constexpr const char* kKind = "deb uncertainty part";

}  // namespace

std::string UncertaintyPartJson(const StudyPartHeader& h, const UncertaintyPart& part) {
  Json j;
  j["kind"] = kKind;
  j["deb_version"] = DEB_VERSION;
  j["digest"] = h.digest;
  j["budget"] = h.budget;
  j["overrides"] = h.overrides;
  j["method"] = h.method;
  j["seed"] = h.seed;
  j["samples"] = h.samples;
  j["shard"] = {h.shard.index, h.shard.count};
  j["evaluations"] = part.total;
  j["begin"] = part.begin;
  j["end"] = part.end;
  // nlohmann writes a double with the digits that read back to it exactly.
  j["values"] = part.values;
  return j.dump() + "\n";
}

UncertaintyPartFile ReadUncertaintyPart(const std::string& dir) {
  const std::string path = (std::filesystem::path(dir) / "part.json").string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError(dir + ": no part.json: not a part of a sharded study (deb uncertainty --shard K/N writes one)");
  const std::string text = ReadInputFile(path, "a study's part", kMaxPartBytes);
  const auto fail = [&](const std::string& why) { return InputError(path + ": " + why); };
  Json j;
  try {
    j = Json::parse(text);
  } catch (const Json::exception& e) {
    throw fail(std::string("not JSON: ") + e.what());
  }
  if (!j.is_object() || j.value("kind", "") != kKind)
    throw fail("not the part of a sharded uncertainty study (deb uncertainty --shard K/N writes one)");
  UncertaintyPartFile f;
  try {
    f.header.digest = j.at("digest").get<std::string>();
    f.header.budget = j.at("budget").get<std::string>();
    f.header.overrides = j.at("overrides").get<std::vector<std::string>>();
    f.header.method = j.at("method").get<std::string>();
    f.header.seed = j.at("seed").get<std::uint64_t>();
    f.header.samples = j.at("samples").get<std::size_t>();
    const auto shard = j.at("shard").get<std::vector<std::size_t>>();
    if (shard.size() != 2) throw fail("shard must be [K, N]");
    f.header.shard = {shard[0], shard[1]};
    f.part.total = j.at("evaluations").get<std::size_t>();
    f.part.begin = j.at("begin").get<std::size_t>();
    f.part.end = j.at("end").get<std::size_t>();
    const Json& values = j.at("values");
    if (!values.is_array()) throw fail("values must be a list");
    for (const Json& row : values) {
      if (!row.is_array()) throw fail("values must be a list of lists of numbers");
      std::vector<double> v;
      for (const Json& x : row) {
        if (!x.is_number()) throw fail("values hold something that is not a number");
        v.push_back(x.get<double>());
        if (!std::isfinite(v.back())) throw fail("values hold a number that is not finite");
      }
      f.part.values.push_back(std::move(v));
    }
  } catch (const Json::exception& e) {
    throw fail(std::string("a key is missing or of the wrong type: ") + e.what());
  }
  const StudyShard& s = f.header.shard;
  if (s.count < 1 || s.count > kMaxShards || s.index < 1 || s.index > s.count)
    throw fail("shard " + std::to_string(s.index) + "/" + std::to_string(s.count) + " is not K/N with 1 <= K <= N <= " +
               std::to_string(kMaxShards));
  if (std::make_pair(f.part.begin, f.part.end) != s.Range(f.part.total))
    throw fail("evaluations " + std::to_string(f.part.begin) + " to " + std::to_string(f.part.end) +
               " are not shard " + std::to_string(s.index) + "/" + std::to_string(s.count) + "'s");
  if (f.part.values.size() != f.part.end - f.part.begin)
    throw fail(std::to_string(f.part.values.size()) + " rows of values for " +
               std::to_string(f.part.end - f.part.begin) + " evaluations");
  return f;
}

}  // namespace deb
