#include "deb/io/yaml_reader.h"

#include <cmath>
#include <fstream>
#include <sstream>

namespace deb::io {
namespace {

std::string Position(const std::string& name, const YAML::Mark& mark) {
  std::ostringstream os;
  os << name;
  if (!mark.is_null()) os << ":" << mark.line + 1 << ":" << mark.column + 1;
  return os.str();
}

std::string Join(const std::set<std::string>& items) {
  std::string s;
  for (const auto& i : items) s += (s.empty() ? "" : ", ") + i;
  return s;
}

}  // namespace

YamlNode::YamlNode(const YamlReader* reader, YAML::Node node, std::string key)
    : reader_(reader), node_(std::move(node)), key_(std::move(key)) {
  if (node_.IsDefined()) reader_->Record(key_, node_.Mark());
}

void YamlNode::Fail(const std::string& message) const {
  throw InputError(key_.empty() ? "(document)" : key_, reader_->Locate(key_, message));
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

void YamlNode::AllowOnly(const std::set<std::string>& allowed) const {
  if (!node_.IsMap()) Fail("expected a map (key: value pairs)");
  for (const auto& kv : node_) {
    const std::string k = kv.first.as<std::string>();
    if (!allowed.count(k)) {
      YamlNode(reader_, kv.first, key_.empty() ? k : key_ + "." + k)
          .Fail("unknown key '" + k + "'; allowed here: " + Join(allowed));
    }
  }
}

std::string YamlNode::AsString() const {
  if (!node_.IsScalar()) Fail("expected a single value (a string)");
  return node_.Scalar();
}

double YamlNode::AsDouble() const {
  if (!node_.IsScalar()) Fail("expected a number");
  const std::string text = node_.Scalar();
  double value = 0.0;
  try {
    std::size_t used = 0;
    value = std::stod(text, &used);
    if (used != text.size()) throw std::invalid_argument(text);
  } catch (const std::exception&) {
    if (text == ".inf" || text == "-.inf" || text == ".nan" || text == ".NaN")
      Fail("value '" + text + "' is not finite; a finite number is required");
    Fail("expected a number, got '" + text + "'");
  }
  if (!std::isfinite(value)) Fail("value '" + text + "' is not finite; a finite number is required");
  return value;
}

double YamlNode::AsPositive() const {
  const double v = AsDouble();
  if (!(v > 0.0)) Fail("value " + node_.Scalar() + " must be > 0");
  return v;
}

double YamlNode::AsNonNegative() const {
  const double v = AsDouble();
  if (!(v >= 0.0)) Fail("value " + node_.Scalar() + " must be >= 0");
  return v;
}

int YamlNode::AsInt() const {
  const double v = AsDouble();
  if (v != std::floor(v) || std::abs(v) > 2e9) Fail("expected a whole number, got '" + node_.Scalar() + "'");
  return static_cast<int>(v);
}

bool YamlNode::AsBool() const {
  const std::string t = AsString();
  if (t == "true" || t == "yes" || t == "on") return true;
  if (t == "false" || t == "no" || t == "off") return false;
  Fail("expected true or false, got '" + t + "'");
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

YamlReader::YamlReader(YAML::Node root, std::string name) : root_(std::move(root)), name_(std::move(name)) {}

YamlReader YamlReader::FromFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open the file");
  std::stringstream text;
  text << in.rdbuf();
  return FromString(text.str(), path);
}

YamlReader YamlReader::FromString(const std::string& text, const std::string& name) {
  try {
    return YamlReader(YAML::Load(text), name);
  } catch (const YAML::Exception& e) {
    throw InputError(Position(name, e.mark) + ": invalid YAML: " + e.msg);
  }
}

YamlNode YamlReader::Root() const {
  if (!root_.IsMap()) throw InputError(name_ + ": the budget must be a YAML map (key: value pairs)");
  return YamlNode(this, root_, "");
}

void YamlReader::Record(const std::string& key, const YAML::Mark& mark) const {
  marks_.emplace(key, mark);
}

std::string YamlReader::Locate(const std::string& key, const std::string& message) const {
  std::string k = key;
  while (true) {
    const auto it = marks_.find(k);
    if (it != marks_.end()) return Position(name_, it->second) + ": " + (key.empty() ? "" : key + ": ") + message;
    const auto cut = k.find_last_of(".[");
    if (cut == std::string::npos) break;
    k = k.substr(0, cut);
  }
  return name_ + ": " + (key.empty() ? "" : key + ": ") + message;
}

}  // namespace deb::io
