#include "deb/load/budget_overrides.h"

#include "deb/core/error.h"
#include "deb/core/limits.h"
#include "deb/load/key_path.h"

namespace deb {

BudgetOverride ParseBudgetOverride(const std::string& text) {
  const std::size_t eq = text.find('=');
  const auto fail = [&](const std::string& why) {
    throw InputError("--set '" + text + "': " + why + " (write KEY.PATH=VALUE, e.g. sources[0].spectrum.level=2e-3)");
  };
  if (eq == std::string::npos) fail("no '='");
  BudgetOverride o{text.substr(0, eq), text.substr(eq + 1)};
  if (o.key_path.empty()) fail("the key path before '=' is empty");
  if (o.value.find_first_not_of(" \t") == std::string::npos) fail("the value after '=' is empty");
  load::ParseKeyPath(o.key_path);  // malformed paths fail here, before any file is read
  return o;
}

namespace load {

void ApplyOverrides(YAML::Node root, const std::vector<BudgetOverride>& overrides, const std::string& file) {
  if (overrides.size() > limits::kMaxOverrides)
    throw InputError(file + ": " + std::to_string(overrides.size()) + " --set options, more than the " +
                     std::to_string(limits::kMaxOverrides) + " deb accepts");
  for (const BudgetOverride& o : overrides) {
    const std::string what = file + ": --set " + o.key_path + "=" + o.value + ": ";
    KeyPath path;
    YAML::Node value;
    try {
      path = ParseKeyPath(o.key_path);
      value = YAML::Load(o.value);
      // YAML::Load keeps the first of several documents: refuse the rest
      // rather than drop them.
      if (const std::size_t documents = YAML::LoadAll(o.value).size(); documents > 1)
        throw InputError("the value holds " + std::to_string(documents) +
                         " YAML documents ('---' starts each); give one value");
    } catch (const YAML::Exception& e) {
      throw InputError(what + "the value is not YAML (" + e.msg + ")");
    } catch (const InputError& e) {
      throw InputError(what + e.message());
    }
    // A parameter by its name: --set k_iso=6e4N/m.
    const std::string why = ReplaceAt(root, ResolveParameterName(root, path), value);
    if (!why.empty()) throw InputError(what + why);
  }
}

std::string OverridesNote(const std::vector<BudgetOverride>& overrides) {
  std::string note;
  for (const BudgetOverride& o : overrides) note += (note.empty() ? "" : ", ") + ("--set " + o.key_path + "=" + o.value);
  return note;
}

std::string OverriddenText(const std::string& text, const std::vector<BudgetOverride>& overrides,
                           const std::string& file) {
  if (overrides.empty()) return text;
  YAML::Node root = YAML::Load(text);
  ApplyOverrides(root, overrides, file);
  YAML::Emitter emitter;
  emitter << root;
  return emitter.c_str();
}

}  // namespace load
}  // namespace deb
