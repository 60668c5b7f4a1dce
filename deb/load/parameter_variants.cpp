#include "deb/load/parameter_variants.h"

#include <yaml-cpp/yaml.h>

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <mutex>

#include "deb/core/error.h"
#include "deb/core/number_text.h"
#include "deb/load/budget_extends.h"
#include "deb/load/budget_overrides.h"
#include "deb/load/budget_variant.h"
#include "deb/load/key_path.h"
#include "deb/load/parameters_yaml.h"

namespace deb::load {

namespace {

class Variants {
 public:
  Variants(const std::string& text, std::shared_ptr<const KeyPositions> positions, std::string base_dir,
           std::vector<VariedParameter> varied, std::string note)
      : document_(YAML::Load(text)), positions_(std::move(positions)), base_dir_(std::move(base_dir)),
        varied_(std::move(varied)), note_(std::move(note)) {
    RemoveStudyKeys(document_);
    for (const VariedParameter& p : varied_)
      steps_.push_back(ResolveParameterName(document_, ParseKeyPath(p.name)));
  }

  Budget At(const std::vector<double>& values) const {
    DEB_DEMAND(values.size() == steps_.size());
    // Each thread loads from its own copy of the document, made once and
    // then reused: a variant writes the same keys every time, and loading
    // only reads (YamlNode reads through const nodes, which add nothing).
    // The copy is made under a lock: yaml-cpp does not promise that reading
    // one node from several threads is safe.
    thread_local std::uint64_t copy_of = 0;
    thread_local YAML::Node copy;
    if (copy_of != id_) {
      const std::lock_guard<std::mutex> lock(mutex_);
      copy = YAML::Clone(document_);
      copy_of = id_;
    }
    YAML::Node& v = copy;
    std::string note = note_;
    for (std::size_t k = 0; k < steps_.size(); ++k) {
      const VariedParameter& p = varied_[k];
      const std::string text = NumberText(values[k] / p.unit_si) + (p.unit.empty() ? "" : " " + p.unit);
      const std::string why = SetTextAt(v, steps_[k], text);
      DEB_DEMAND(why.empty());
      note += (k ? ", " : " ") + p.name + " = " + text;
    }
    return LoadBudgetVariantNode(v, positions_, note, base_dir_);
  }

 private:
  YAML::Node document_;
  std::shared_ptr<const KeyPositions> positions_;
  std::string base_dir_;
  std::vector<VariedParameter> varied_;
  std::vector<KeyPath> steps_;
  std::string note_;
  mutable std::mutex mutex_;
  // Tells this document's copies from another Variants' (never 0).
  const std::uint64_t id_ = next_id_.fetch_add(1) + 1;
  static inline std::atomic<std::uint64_t> next_id_{0};
};

}  // namespace

StudyBudget ReadStudyBudget(const std::string& path, const std::vector<BudgetOverride>& overrides) {
  StudyBudget b;
  // The budget as --set changes it, checked whole (its study keys too).
  b.checked = LoadBudgetFile(path, overrides);
  b.text = OverriddenText(ReadBudgetFile(path).text(), overrides, path);
  b.reader = std::make_shared<const YamlReader>(YamlReader::FromString(b.text, path));
  const YamlNode root = b.reader->Root();
  b.parameters =
      root.Has("parameters") ? ParseParameters(root.Required("parameters")) : std::make_shared<ParameterSet>();
  return b;
}

std::function<Budget(const std::vector<double>&)> ParameterVariants(const StudyBudget& budget, const std::string& path,
                                                                    const std::vector<BudgetOverride>& overrides,
                                                                    const std::vector<VariedParameter>& varied,
                                                                    const std::string& note) {
  const std::string dir = std::filesystem::path(path).parent_path().string();
  std::string full = OverridesNote(overrides);
  full += (full.empty() ? "" : "; ") + note;
  const auto variants =
      std::make_shared<const Variants>(budget.text, budget.checked.positions, dir.empty() ? "." : dir, varied, full);
  return [variants](const std::vector<double>& values) { return variants->At(values); };
}

}  // namespace deb::load
