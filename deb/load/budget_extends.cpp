#include "deb/load/budget_extends.h"

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <memory>
#include <vector>

#include "deb/core/error.h"
#include "deb/core/limits.h"
#include "deb/load/yaml_node_set.h"

namespace deb::load {
namespace {

namespace fs = std::filesystem;

// Keys whose (scalar) value names a data file, relative to the budget's directory.
constexpr const char* kFileKeys[] = {"file", "modes", "input_shapes", "output_shapes"};

bool IsFileKey(const std::string& key) {
  for (const char* k : kFileKeys)
    if (key == k) return true;
  return false;
}

// Rewrites every relative data-file path in `n` (read from a file in
// `from_dir`) to be relative to `to_dir`. Each node once (`visited`): a node
// reached again through an alias is the same node, so a few lines of nested
// aliases cost a few visits instead of 10^9, and a shared file name is
// rewritten once, not once per alias.
void Rebase(YAML::Node n, const fs::path& from_dir, const fs::path& to_dir, YamlNodeSet& visited) {
  if (!(n.IsSequence() || n.IsMap()) || !visited.Insert(n)) return;
  if (n.IsSequence()) {
    for (std::size_t i = 0; i < n.size(); ++i) Rebase(n[i], from_dir, to_dir, visited);
    return;
  }
  for (auto kv : n) {
    if (IsFileKey(kv.first.Scalar()) && kv.second.IsScalar()) {
      const fs::path p(kv.second.Scalar());
      if (p.is_relative() && visited.Insert(kv.second)) {
        const fs::path target = fs::absolute(from_dir / p).lexically_normal();
        const fs::path relative = target.lexically_relative(fs::absolute(to_dir).lexically_normal());
        kv.second = (relative.empty() ? target : relative).generic_string();
      }
      continue;
    }
    Rebase(kv.second, from_dir, to_dir, visited);
  }
}

// Merges map `over` into map `base`: maps into maps, anything else replaces,
// null removes. `visits` counts the keys merged: maps nested through aliases
// on both sides could make the merge walk 10^9 of them.
void Merge(YAML::Node base, const YAML::Node& over, std::size_t& visits) {
  for (const auto& kv : over) {
    if (++visits > limits::kMaxKeyPathVisits)
      throw InputError("merging the budget into its base visits more than " +
                       std::to_string(limits::kMaxKeyPathVisits) + " keys (nested aliases?)");
    const std::string key = kv.first.Scalar();
    const YAML::Node& existing = static_cast<const YAML::Node&>(base)[key];
    if (kv.second.IsNull()) {
      if (existing) base.remove(key);
      continue;
    }
    if (kv.second.IsMap() && existing && existing.IsMap()) {
      Merge(base[key], kv.second, visits);
      continue;
    }
    base[key] = kv.second;
  }
}

fs::path Directory(const std::string& path) {
  const fs::path dir = fs::path(path).parent_path();
  return dir.empty() ? fs::path(".") : dir;
}

struct Assembled {
  YAML::Node root;
  std::shared_ptr<KeyPositions> positions;
};

Assembled Resolve(const std::string& path, std::vector<std::string>& chain) {
  const YamlReader reader = YamlReader::FromFile(path);
  Assembled out{reader.LoadCopy(), std::make_shared<KeyPositions>(*reader.positions())};
  if (!out.root.IsMap() || !out.root["extends"]) return out;
  const YamlNode extends = reader.Root().Required("extends");
  if (!extends.IsScalar()) extends.Fail("extends names one budget file (a path relative to this file)");
  const std::string name = extends.AsString();
  fs::path base = fs::path(name);
  if (base.is_relative()) base = Directory(path) / base;
  const std::string base_path = base.lexically_normal().string();
  std::error_code ec;
  const fs::path canonical = fs::weakly_canonical(base, ec);
  const std::string key = ec ? base_path : canonical.string();
  std::string trail;
  for (const std::string& f : chain) trail += f + " -> ";
  for (const std::string& f : chain)
    if (f == key) extends.Fail("extends '" + name + "' closes a cycle: " + trail + key);
  if (static_cast<int>(chain.size()) >= kMaxExtendsDepth)
    extends.Fail("extends '" + name + "': more than " + std::to_string(kMaxExtendsDepth) +
                 " budget files in one chain (" + trail + key + ")");
  chain.push_back(key);
  Assembled base_doc = [&] {
    try {
      return Resolve(base_path, chain);
    } catch (const InputError& e) {
      if (e.located()) throw;
      extends.Fail(e.message());
    }
  }();
  chain.pop_back();
  if (!base_doc.root.IsMap()) extends.Fail("the base budget '" + name + "' is not a YAML map (key: value pairs)");
  YamlNodeSet visited;
  Rebase(base_doc.root, Directory(base_path), Directory(path), visited);
  out.root.remove("extends");
  std::size_t visits = 0;
  AtNode(extends, [&] { Merge(base_doc.root, out.root, visits); });
  out.positions->Inherit(*base_doc.positions);
  out.root = base_doc.root;
  return out;
}

}  // namespace

YamlReader ReadBudgetFile(const std::string& path) {
  YamlReader reader = YamlReader::FromFile(path);
  if (!reader.RootHas("extends")) return reader;
  std::error_code ec;
  const fs::path canonical = fs::weakly_canonical(path, ec);
  std::vector<std::string> chain = {ec ? path : canonical.string()};
  Assembled a = Resolve(path, chain);
  YAML::Emitter emitter;
  emitter << a.root;
  return YamlReader::FromAssembled(emitter.c_str(), path, std::move(a.positions));
}

}  // namespace deb::load
