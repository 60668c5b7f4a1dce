#include "deb/load/yaml_reader.h"

#include <stdexcept>
#include <limits>
#include <cstdlib>
#include <cmath>
#include <set>
#include <tuple>
#include <sstream>
#include <utility>

#include "deb/core/input_file.h"
#include "deb/core/limits.h"
#include "deb/core/suggest.h"
#include "deb/units/quantity.h"

namespace deb::load {
namespace {

InputLocation Where(const std::string& name, const YAML::Mark& mark, const std::string& key) {
  if (mark.is_null()) return {name, 0, 0, key};
  return {name, mark.line + 1, mark.column + 1, key};
}

std::string Join(const std::set<std::string>& items) {
  std::string s;
  for (const auto& i : items) s += (s.empty() ? "" : ", ") + i;
  return s;
}

// What every deb document must be, checked once over the whole tree before
// anything reads it: map keys are plain scalars (a "? {}" key is no name) and
// no key appears twice in one map (yaml-cpp keeps both and lookups see only
// the first, so an edited duplicate would be ignored without a word). The
// same walk records every node's position by key path. A node reached again
// through an alias (same position in the text) is recorded but not walked
// again, so a few lines of nested aliases cannot make the walk explode.
class DocumentCheck {
 public:
  DocumentCheck(const std::string& name, KeyPositions* positions) : name_(name), positions_(positions) {}

  void Walk(const YAML::Node& node, const std::string& key) {
    const YAML::Mark m = node.Mark();
    if (!m.is_null()) positions_->Record(key, m.line + 1, m.column + 1);
    if (node.IsScalar()) Utf8(node, key);
    if (!node.IsMap() && !node.IsSequence()) return;
    if (!seen_.insert({m.pos, m.line, m.column}).second) return;
    if (node.IsSequence()) {
      for (std::size_t i = 0; i < node.size(); ++i) Walk(node[i], key + "[" + std::to_string(i) + "]");
      return;
    }
    std::set<std::string> keys;
    for (const auto& kv : node) {
      if (!kv.first.IsScalar())
        Fail(kv.first.Mark(), key, std::string("a key must be a plain name, not a ") +
                                       (kv.first.IsMap() ? "map" : kv.first.IsSequence() ? "list" : "null") +
                                       " (a '?' complex key)");
      const std::string k = kv.first.Scalar();
      const std::string path = key.empty() ? k : key + "." + k;
      if (!keys.insert(k).second)
        Fail(kv.first.Mark(), key.empty() ? Excerpt(k) : key + "." + Excerpt(k),
             "key '" + Excerpt(k) + "' is given twice in this map; give it once");
      Utf8(kv.first, key.empty() ? Excerpt(k) : key + "." + Excerpt(k));
      Walk(kv.second, path);
    }
  }

 private:
  // Every text of a budget is UTF-8: it reaches summary.json and the reports.
  void Utf8(const YAML::Node& scalar, const std::string& key) const {
    if (const std::string problem = Utf8Problem(scalar.Scalar()); !problem.empty())
      Fail(scalar.Mark(), key, "'" + Excerpt(scalar.Scalar()) + "': " + problem + "; save the file as UTF-8 text");
  }
  [[noreturn]] void Fail(const YAML::Mark& mark, const std::string& key, const std::string& message) const {
    throw InputError(Where(name_, mark, key), message);
  }

  const std::string& name_;
  KeyPositions* positions_;
  std::set<std::tuple<int, int, int>> seen_;
};

}  // namespace

YamlNode::YamlNode(const YamlReader* reader, YAML::Node node, std::string key)
    : reader_(reader), node_(std::move(node)), key_(std::move(key)) {}

void YamlNode::Fail(const std::string& message) const { FailAt(node_, key_, message); }

void YamlNode::FailInText(int column, const std::string& message) const {
  if (reader_->assembled() || !node_.IsDefined() || node_.Mark().is_null()) Fail(message);
  InputLocation where = Where(reader_->name(), node_.Mark(), key_);
  // A quoted scalar's text starts after its quote (yaml-cpp tags it "!").
  where.column += column - 1 + (node_.Tag() == "!" ? 1 : 0);
  throw InputError(where, message);
}

void YamlNode::FailAt(const YAML::Node& at, const std::string& key, const std::string& message) const {
  if (!reader_->assembled() && at.IsDefined() && !at.Mark().is_null())
    throw InputError(Where(reader_->name(), at.Mark(), key), message);
  throw InputError(reader_->positions()->Locate(key), message);
}

bool YamlNode::Has(const std::string& field) const {
  return node_.IsMap() && node_[field].IsDefined() && !node_[field].IsNull();
}

YamlNode YamlNode::Required(const std::string& field) const {
  if (!node_.IsMap()) Fail("expected a map with key '" + field + "'");
  if (!Has(field)) Fail("missing required key '" + field + "'");
  return YamlNode(reader_, node_[field], key_.empty() ? field : key_ + "." + field);
}

std::optional<YamlNode> YamlNode::Optional(const std::string& field) const {
  if (!Has(field)) return std::nullopt;
  return Required(field);
}

std::vector<YamlNode> YamlNode::Elements() const {
  if (!node_.IsSequence()) Fail("expected a list");
  std::vector<YamlNode> out;
  for (std::size_t i = 0; i < node_.size(); ++i)
    out.emplace_back(reader_, node_[i], key_ + "[" + std::to_string(i) + "]");
  return out;
}

std::vector<std::string> YamlNode::Keys() const {
  if (!node_.IsMap()) Fail("expected a map (key: value pairs)");
  std::vector<std::string> keys;
  for (const auto& kv : node_) keys.push_back(kv.first.Scalar());  // plain scalars: DocumentCheck
  return keys;
}

void YamlNode::AllowOnly(const std::set<std::string>& allowed) const {
  if (!node_.IsMap()) Fail("expected a map (key: value pairs)");
  for (const auto& kv : node_) {
    const std::string k = kv.first.Scalar();  // a plain scalar: DocumentCheck
    if (!allowed.count(k)) {
      // The key is quoted as a data file's cell is, at most 40 characters:
      // a file that is no budget (extends: /etc/shadow) makes each of its
      // lines an unknown key.
      const std::string path = key_.empty() ? k : key_ + "." + k;
      InputLocation where = !reader_->assembled() && !kv.first.Mark().is_null()
                                ? Where(reader_->name(), kv.first.Mark(), path)
                                : reader_->positions()->Locate(path);
      where.key_path = key_.empty() ? Excerpt(k) : key_ + "." + Excerpt(k);
      throw InputError(where, "unknown key '" + Excerpt(k) + "'" +
                                  DidYouMean(k, std::vector<std::string>(allowed.begin(), allowed.end())) +
                                  "; allowed here: " + Join(allowed));
    }
  }
}

std::string YamlNode::AsString() const {
  if (!node_.IsScalar()) Fail("expected a single value (a string)");
  return node_.Scalar();
}

namespace {

// The unit a key's name gives its value: "bands[0].lo_hz" takes Hz.
std::string UnitOfKey(const std::string& key) {
  std::string k = key.substr(key.rfind('.') == std::string::npos ? 0 : key.rfind('.') + 1);
  k = k.substr(0, k.find('['));
  const auto ends = [&k](const std::string& suffix) {
    return k.size() > suffix.size() && k.compare(k.size() - suffix.size(), suffix.size(), suffix) == 0;
  };
  if (ends("_hz")) return "Hz";
  if (ends("_s")) return "s";
  if (ends("_deg")) return "arc_degree";
  return "";
}

std::string UnitName(const std::string& unit) { return unit == "arc_degree" ? "degrees" : unit; }

}  // namespace

double YamlNode::AsDouble() const { return AsValueIn(UnitOfKey(key_)); }

double YamlNode::AsValueIn(const std::string& unit) const {
  if (!node_.IsScalar()) Fail("expected a number");
  const std::string text = node_.Scalar();
  double value = 0.0;
  try {
    std::size_t used = 0;
    value = std::stod(text, &used);
    if (used != text.size()) throw std::invalid_argument(text);
  } catch (const std::out_of_range&) {
    // strtod's ERANGE: beyond the largest double, or below the smallest
    // normal one (a subnormal keeps few digits, and no quantity deb reads is
    // that small: it is a unit or exponent slip).
    // strtod returns HUGE_VAL beyond the range, at most DBL_MIN below it.
    if (std::abs(std::strtod(text.c_str(), nullptr)) <= std::numeric_limits<double>::min())
      Fail("value '" + Excerpt(text) + "' is below the smallest normal double, 2.2e-308: write 0, or check its unit");
    Fail("value '" + Excerpt(text) + "' is beyond the largest double, 1.8e308");
  } catch (const std::exception&) {
    if (text == ".inf" || text == "-.inf" || text == ".nan" || text == ".NaN")
      Fail("value '" + text + "' is not finite; a finite number is required");
    return EvaluateExpression(text, unit);
  }
  if (!std::isfinite(value)) Fail("value '" + text + "' is not finite; a finite number is required");
  return value;
}

double YamlNode::EvaluateExpression(const std::string& text, const std::string& unit) const {
  Quantity q;
  try {
    q = reader_->parameters().EvaluateText(text);
  } catch (const ExpressionError& e) {
    FailInText(e.column_in_text(), "expected a number, got '" + Excerpt(text) + "': " + e.reason());
  }
  if (unit.empty() || !q.has_unit) {
    // Where no unit is expected, a dimensionless quantity ("50 %" is 0.5);
    // where one is, a plain number is in it.
    if (q.dimension.IsNone()) return q.value;
  }
  if (unit.empty()) {
    Fail("'" + Excerpt(text) + "' is a quantity in " + q.dimension.Text() +
         "; this value is a plain number (a unit is taken where the key names it: _hz, _s, _deg)");
  }
  if (unit == "Hz" && text.find("rad") != std::string::npos) {
    Fail("'" + Excerpt(text) + "': give frequencies in Hz, not rad/s (deb counts rad as 1, so 10 rad/s would be "
         "read as 10 Hz; write 10/(2*pi) Hz)");
  }
  try {
    return ValueIn(q, unit);
  } catch (const InputError&) {
    Fail("'" + Excerpt(text) + "' is a quantity in " + q.dimension.Text() + "; this value is in " + UnitName(unit));
  }
}

double YamlNode::AsPositive() const { return AsPositiveIn(UnitOfKey(key_)); }

double YamlNode::AsNonNegative() const { return AsNonNegativeIn(UnitOfKey(key_)); }

double YamlNode::AsPositiveIn(const std::string& unit) const {
  const double v = AsValueIn(unit);
  if (!(v > 0.0)) Fail("value " + Excerpt(node_.Scalar()) + " must be > 0");
  return v;
}

double YamlNode::AsNonNegativeIn(const std::string& unit) const {
  const double v = AsValueIn(unit);
  if (!(v >= 0.0)) Fail("value " + Excerpt(node_.Scalar()) + " must be >= 0");
  return v;
}

int YamlNode::AsInt() const {
  const double v = AsDouble();
  if (v != std::floor(v)) Fail("expected a whole number, got '" + node_.Scalar() + "'");
  if (std::abs(v) > 2e9) Fail("value " + node_.Scalar() + " is out of range; a whole number here is at most 2000000000");
  return static_cast<int>(v);
}

bool YamlNode::AsBool() const {
  const std::string t = AsString();
  if (t == "true" || t == "yes" || t == "on") return true;
  if (t == "false" || t == "no" || t == "off") return false;
  Fail("expected true or false, got '" + Excerpt(t) + "'");
}

std::vector<double> YamlNode::AsDoubles() const {
  if (node_.IsScalar()) return {AsDouble()};
  std::vector<double> out;
  for (const auto& e : Elements()) out.push_back(e.AsDouble());
  return out;
}

std::vector<std::string> YamlNode::AsStrings() const {
  if (node_.IsScalar()) return {AsString()};
  std::vector<std::string> out;
  for (const auto& e : Elements()) out.push_back(e.AsString());
  return out;
}

Eigen::MatrixXd YamlNode::AsMatrix() const {
  if (node_.IsScalar()) return Eigen::MatrixXd::Constant(1, 1, AsDouble());
  const auto rows = Elements();
  if (rows.empty()) return Eigen::MatrixXd(0, 0);
  if (!rows.front().IsSequence()) {
    const auto v = AsDoubles();
    return Eigen::Map<const Eigen::RowVectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
  }
  Eigen::MatrixXd m(rows.size(), rows.front().size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto v = rows[i].AsDoubles();
    if (v.size() != static_cast<std::size_t>(m.cols()))
      rows[i].Fail("row has " + std::to_string(v.size()) + " entries, the first row has " +
                   std::to_string(m.cols()) + "; a matrix must be rectangular");
    for (std::size_t j = 0; j < v.size(); ++j) m(i, j) = v[j];
  }
  return m;
}

const ParameterSet& YamlReader::parameters() const {
  static const ParameterSet none;
  return parameters_ ? *parameters_ : none;
}

YamlReader::YamlReader(YAML::Node root, std::string name, std::string text,
                       std::shared_ptr<const KeyPositions> positions)
    : root_(std::move(root)), text_(std::move(text)), name_(std::move(name)), positions_(std::move(positions)) {}

YamlReader YamlReader::FromFile(const std::string& path) {
  return FromString(ReadInputFile(path, "the budget file", limits::kMaxBudgetFileBytes), path);
}

YamlReader YamlReader::FromString(const std::string& text, const std::string& name) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw InputError(Where(name, e.mark, ""), "invalid YAML: " + e.msg);
  }
  auto positions = std::make_shared<KeyPositions>(name);
  DocumentCheck(name, positions.get()).Walk(root, "");
  return YamlReader(std::move(root), name, text, std::move(positions));
}

YamlReader YamlReader::FromAssembled(const std::string& text, const std::string& name,
                                     std::shared_ptr<const KeyPositions> positions) {
  YamlReader reader(YAML::Load(text), name, text, std::move(positions));
  reader.assembled_ = true;
  return reader;
}

YamlReader YamlReader::FromChecked(YAML::Node root, const std::string& name) {
  YamlReader reader(std::move(root), name, "", std::make_shared<KeyPositions>(name));
  reader.assembled_ = true;
  return reader;
}

YamlNode YamlReader::Root() const {
  if (!root_.IsMap()) throw InputError(InputLocation{name_, 0, 0, ""}, "the budget must be a YAML map (key: value pairs)");
  return YamlNode(this, root_, "");
}

}  // namespace deb::load
