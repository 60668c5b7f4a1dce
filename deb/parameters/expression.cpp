#include "deb/parameters/expression.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "deb/core/math_constants.h"
#include "deb/core/suggest.h"
#include "deb/units/unit.h"

namespace deb {

struct Expression::Node {
  enum class Kind { kNumber, kName, kNegate, kAdd, kSubtract, kMultiply, kDivide, kPower, kCall };
  Kind kind = Kind::kNumber;
  std::size_t offset = 0;  // where it starts in the text (an operator: the operator)
  Quantity number;         // kNumber
  std::string unit;        // kNumber: the unit as written
  std::string name;        // kName, kCall
  std::vector<std::shared_ptr<const Node>> args;
};

namespace {

using Node = Expression::Node;
using NodePtr = std::shared_ptr<const Node>;

// For messages: the expression, cut to kShown bytes around `offset`.
std::string Shown(const std::string& text) {
  constexpr std::size_t kShown = 60;
  if (text.size() <= kShown) return text;
  return text.substr(0, kShown) + "...";
}

std::string Message(const std::string& text, std::size_t offset, const std::string& what) {
  return "expression '" + Shown(text) + "', column " + std::to_string(offset + 1) + ": " + what;
}

bool IsLetter(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
}
bool IsDigit(char c) { return c >= '0' && c <= '9'; }
// A byte of a UTF-8 sequence (µ, °, ²): units may hold them.
bool IsHighByte(char c) { return static_cast<unsigned char>(c) >= 0x80; }

struct FunctionInfo {
  const char* name;
  int min_args, max_args;
};
constexpr FunctionInfo kFunctions[] = {{"sqrt", 1, 1}, {"exp", 1, 1},  {"log", 1, 1}, {"log10", 1, 1},
                                       {"sin", 1, 1},  {"cos", 1, 1},  {"tan", 1, 1}, {"abs", 1, 1},
                                       {"min", 2, 64}, {"max", 2, 64}};

const FunctionInfo* FindFunction(const std::string& name) {
  for (const FunctionInfo& f : kFunctions)
    if (name == f.name) return &f;
  return nullptr;
}

class Parser {
 public:
  explicit Parser(const std::string& text) : text_(text) {}

  NodePtr ParseAll() {
    NodePtr root = Sum();
    SkipSpace();
    if (pos_ < text_.size()) {
      if (text_[pos_] == ')') Fail(pos_, "')' without a matching '('");
      Fail(pos_, "unexpected '" + std::string(1, text_[pos_]) + "' (expected an operator + - * / ^ or the end)");
    }
    return root;
  }

  std::vector<std::pair<std::string, std::size_t>> names;

 private:
  [[noreturn]] void Fail(std::size_t offset, const std::string& what) const {
    throw ExpressionError(text_, offset, what);
  }

  void SkipSpace() {
    while (pos_ < text_.size() && (text_[pos_] == ' ' || text_[pos_] == '\t')) ++pos_;
  }

  // Guards the recursion: each nested parenthesis, function or unary sign.
  struct Depth {
    explicit Depth(Parser& p) : parser(p) {
      if (++parser.depth_ > kMaxExpressionDepth)
        parser.Fail(parser.pos_, "nested deeper than " + std::to_string(kMaxExpressionDepth) + " levels");
    }
    ~Depth() { --parser.depth_; }
    Parser& parser;
  };

  static NodePtr Make(Node::Kind kind, std::size_t offset, std::vector<NodePtr> args) {
    auto node = std::make_shared<Node>();
    node->kind = kind;
    node->offset = offset;
    node->args = std::move(args);
    return node;
  }

  NodePtr Sum() {
    NodePtr left = Product();
    for (;;) {
      SkipSpace();
      if (pos_ >= text_.size() || (text_[pos_] != '+' && text_[pos_] != '-')) return left;
      const std::size_t at = pos_;
      const Node::Kind kind = text_[pos_++] == '+' ? Node::Kind::kAdd : Node::Kind::kSubtract;
      left = Make(kind, at, {left, Product()});
    }
  }

  NodePtr Product() {
    NodePtr left = Unary();
    for (;;) {
      SkipSpace();
      if (pos_ >= text_.size() || (text_[pos_] != '*' && text_[pos_] != '/')) return left;
      const std::size_t at = pos_;
      const Node::Kind kind = text_[pos_++] == '*' ? Node::Kind::kMultiply : Node::Kind::kDivide;
      left = Make(kind, at, {left, Unary()});
    }
  }

  NodePtr Unary() {
    SkipSpace();
    if (pos_ < text_.size() && (text_[pos_] == '+' || text_[pos_] == '-')) {
      const Depth depth(*this);
      const std::size_t at = pos_;
      const bool negate = text_[pos_++] == '-';
      NodePtr operand = Unary();
      return negate ? Make(Node::Kind::kNegate, at, {operand}) : operand;
    }
    return Power();
  }

  NodePtr Power() {
    NodePtr base = Atom();
    SkipSpace();
    if (pos_ < text_.size() && text_[pos_] == '^') {
      const Depth depth(*this);
      const std::size_t at = pos_++;
      return Make(Node::Kind::kPower, at, {base, Unary()});
    }
    return base;
  }

  NodePtr Atom() {
    SkipSpace();
    if (pos_ >= text_.size()) Fail(pos_, "expected a number, a name or '(' but the expression ends");
    const char c = text_[pos_];
    if (c == '(') {
      const Depth depth(*this);
      const std::size_t open = pos_++;
      NodePtr inner = Sum();
      SkipSpace();
      if (pos_ >= text_.size() || text_[pos_] != ')') Fail(open, "'(' is not closed");
      ++pos_;
      return inner;
    }
    if (IsDigit(c) || (c == '.' && pos_ + 1 < text_.size() && IsDigit(text_[pos_ + 1]))) return Number();
    if (IsLetter(c)) return Name();
    Fail(pos_, "unexpected '" + std::string(1, c) + "' (expected a number, a name or '(')");
  }

  NodePtr Number() {
    const std::size_t start = pos_;
    while (pos_ < text_.size() && (IsDigit(text_[pos_]) || text_[pos_] == '.')) ++pos_;
    // An exponent: e or E, an optional sign, and at least one digit.
    if (pos_ < text_.size() && (text_[pos_] == 'e' || text_[pos_] == 'E')) {
      std::size_t p = pos_ + 1;
      if (p < text_.size() && (text_[p] == '+' || text_[p] == '-')) ++p;
      if (p < text_.size() && IsDigit(text_[p])) {
        while (p < text_.size() && IsDigit(text_[p])) ++p;
        pos_ = p;
      }
    }
    const std::string digits = text_.substr(start, pos_ - start);
    char* end = nullptr;
    const double value = std::strtod(digits.c_str(), &end);
    if (end != digits.c_str() + digits.size()) Fail(start, "'" + digits + "' is not a number");
    if (!std::isfinite(value)) Fail(start, "'" + digits + "' is beyond the range of numbers");
    auto node = std::make_shared<Node>();
    node->kind = Node::Kind::kNumber;
    node->offset = start;
    const std::size_t unit_start = UnitStart();
    node->unit = unit_start == std::string::npos ? "" : Unit(unit_start);
    try {
      node->number = node->unit.empty() ? Quantity{value, {}, false} : QuantityOf(value, node->unit);
    } catch (const InputError& e) {
      std::string hint;
      const std::size_t first_end = node->unit.find_first_of(" ./^()0123456789");
      const std::string first = node->unit.substr(0, first_end);
      if (first == "pi" || FindFunction(first)) hint = "; a unit follows its number: write '*' to multiply by " + first;
      else if (first_end != std::string::npos) hint = "; write '*' to multiply by a parameter";
      Fail(unit_start, e.message() + hint);
    }
    if (!std::isfinite(node->number.value)) Fail(start, "'" + digits + " " + node->unit + "' is beyond the range of numbers");
    return node;
  }

  // The offset of a unit after a number (its first letter), or npos.
  std::size_t UnitStart() const {
    std::size_t p = pos_;
    while (p < text_.size() && (text_[p] == ' ' || text_[p] == '\t')) ++p;
    if (p < text_.size() && (IsLetter(text_[p]) || IsHighByte(text_[p]))) return p;
    return std::string::npos;
  }

  // Reads the unit starting at `start` (see expression.h for where it ends).
  std::string Unit(std::size_t start) {
    std::size_t p = start, end = start;
    int open = 0;
    while (p < text_.size()) {
      const char c = text_[p];
      if (IsLetter(c) || IsDigit(c) || IsHighByte(c) || c == '.' || c == '^') {
        ++p;
      } else if (c == '/') {
        // "N/m" is a unit; "m / x" ends it before the '/'.
        if (p == start || text_[p - 1] == ' ' || text_[p - 1] == '\t' || p + 1 >= text_.size() ||
            text_[p + 1] == ' ' || text_[p + 1] == '\t')
          break;
        ++p;
      } else if (c == '-') {
        // A power: "s-2", "m^-1".
        if (p + 1 < text_.size() && IsDigit(text_[p + 1]) && (IsLetter(text_[p - 1]) || text_[p - 1] == '^')) ++p;
        else break;
      } else if (c == '(') {
        ++open;
        ++p;
      } else if (c == ')') {
        if (open == 0) break;
        --open;
        ++p;
      } else if (c == ' ' || c == '\t') {
        // A space multiplies units ("kg m2") if a unit factor follows.
        std::size_t q = p;
        while (q < text_.size() && (text_[q] == ' ' || text_[q] == '\t')) ++q;
        if (q < text_.size() && (IsLetter(text_[q]) || IsHighByte(text_[q]) || text_[q] == '('))
          p = q;
        else
          break;
        continue;
      } else {
        break;
      }
      // The unit may end after a name, a power or a closed group, not after
      // an operator or inside parentheses: "m/(2*x)" is m divided by (2*x).
      const char last = text_[p - 1];
      if (open == 0 && (IsLetter(last) || IsDigit(last) || IsHighByte(last) || last == ')')) end = p;
    }
    pos_ = end;
    return text_.substr(start, end - start);
  }

  NodePtr Name() {
    const std::size_t start = pos_;
    while (pos_ < text_.size() && (IsLetter(text_[pos_]) || IsDigit(text_[pos_]))) ++pos_;
    const std::string name = text_.substr(start, pos_ - start);
    std::size_t p = pos_;
    while (p < text_.size() && (text_[p] == ' ' || text_[p] == '\t')) ++p;
    const FunctionInfo* function = FindFunction(name);
    if (p < text_.size() && text_[p] == '(') {
      if (!function) {
        std::vector<std::string> all;
        for (const FunctionInfo& f : kFunctions) all.push_back(f.name);
        Fail(start, "unknown function '" + name + "'" + DidYouMean(name, all) +
                        " (functions: sqrt exp log log10 sin cos tan abs min max)");
      }
      const Depth depth(*this);
      pos_ = p + 1;
      std::vector<NodePtr> args{Sum()};
      for (;;) {
        SkipSpace();
        if (pos_ < text_.size() && text_[pos_] == ',') {
          ++pos_;
          args.push_back(Sum());
          continue;
        }
        if (pos_ < text_.size() && text_[pos_] == ')') {
          ++pos_;
          break;
        }
        Fail(p, "'(' of " + name + " is not closed");
      }
      const int n = static_cast<int>(args.size());
      if (n < function->min_args || n > function->max_args) {
        Fail(start, name + " takes " +
                        (function->min_args == function->max_args ? std::to_string(function->min_args)
                                                                  : "at least " + std::to_string(function->min_args)) +
                        " argument" + (function->max_args == 1 ? "" : "s") + ", not " + std::to_string(n));
      }
      auto node = std::make_shared<Node>();
      node->kind = Node::Kind::kCall;
      node->offset = start;
      node->name = name;
      node->args = std::move(args);
      return node;
    }
    if (function) Fail(start, "function " + name + " needs its argument in parentheses: " + name + "(...)");
    auto node = std::make_shared<Node>();
    node->kind = Node::Kind::kName;
    node->offset = start;
    node->name = name;
    if (name != "pi") {
      bool seen = false;
      for (const auto& known : names) seen = seen || known.first == name;
      if (!seen) names.emplace_back(name, start);
    }
    return node;
  }

  const std::string& text_;
  std::size_t pos_ = 0;
  int depth_ = 0;
};

// "unknown name 'x' (did you mean 'y'?)" at `offset` of `text`.
ExpressionError UnknownName(const std::string& text, std::size_t offset, const std::string& name,
                            const std::vector<std::string>& known) {
  std::vector<std::string> candidates = known;
  candidates.push_back("pi");
  return ExpressionError(text, offset, "unknown name '" + name + "'" + DidYouMean(name, candidates) +
                                           (known.empty() ? " (no parameters are defined)" : ""));
}

class Evaluator {
 public:
  Evaluator(const std::string& text, const Expression::Lookup& lookup, const std::vector<std::string>& known)
      : text_(text), lookup_(lookup), known_(known) {}

  Quantity Value(const Node& node) const {
    const Quantity q = Compute(node);
    if (!std::isfinite(q.value)) Fail(node.offset, "the result is not finite (beyond the range of numbers)");
    return q;
  }

 private:
  [[noreturn]] void Fail(std::size_t offset, const std::string& what) const {
    throw ExpressionError(text_, offset, what);
  }

  void RequireNone(const Node& at, const Quantity& q, const std::string& what) const {
    if (!q.dimension.IsNone())
      Fail(at.offset, what + " takes a dimensionless argument, not one in " + q.dimension.Text());
  }

  void RequireSame(const Node& at, const Quantity& a, const Quantity& b, const std::string& what) const {
    if (a.dimension != b.dimension)
      Fail(at.offset, "cannot " + what + " " + a.dimension.Text() + " and " + b.dimension.Text() +
                          " (" + Describe(a) + ", " + Describe(b) + ")");
  }

  Quantity Compute(const Node& node) const {
    using Kind = Node::Kind;
    switch (node.kind) {
      case Kind::kNumber:
        return node.number;
      case Kind::kName: {
        if (node.name == "pi") return {kPi, {}, false};
        const Quantity* q = lookup_ ? lookup_(node.name) : nullptr;
        if (!q) throw UnknownName(text_, node.offset, node.name, known_);
        return *q;
      }
      case Kind::kNegate: {
        Quantity q = Value(*node.args[0]);
        q.value = -q.value;
        return q;
      }
      case Kind::kAdd:
      case Kind::kSubtract: {
        const Quantity a = Value(*node.args[0]), b = Value(*node.args[1]);
        const bool add = node.kind == Kind::kAdd;
        RequireSame(node, a, b, add ? "add" : "subtract");
        return {add ? a.value + b.value : a.value - b.value, a.dimension, a.has_unit || b.has_unit};
      }
      case Kind::kMultiply:
        return Multiply(Value(*node.args[0]), Value(*node.args[1]));
      case Kind::kDivide: {
        const Quantity a = Value(*node.args[0]), b = Value(*node.args[1]);
        if (b.value == 0.0) Fail(node.offset, "division by zero");
        return {a.value / b.value, a.dimension / b.dimension, a.has_unit || b.has_unit};
      }
      case Kind::kPower:
        return Power(node, Value(*node.args[0]), Value(*node.args[1]));
      case Kind::kCall:
        return Call(node);
    }
    Fail(node.offset, "unknown operation");
  }

  static Quantity Multiply(const Quantity& a, const Quantity& b) {
    return {a.value * b.value, a.dimension * b.dimension, a.has_unit || b.has_unit};
  }

  Quantity Power(const Node& node, const Quantity& base, const Quantity& exponent) const {
    RequireNone(*node.args[1], exponent, "an exponent");
    if (base.dimension.IsNone()) {
      if (base.value < 0.0 && exponent.value != std::round(exponent.value))
        Fail(node.offset, "a negative number to a power that is not whole (" + Describe(base) + "^" +
                              Describe(exponent) + ")");
      if (base.value == 0.0 && exponent.value < 0.0) Fail(node.offset, "zero to a negative power");
      return {std::pow(base.value, exponent.value), {}, base.has_unit};
    }
    const double halves = 2.0 * exponent.value;
    Dimension d;
    if (halves != std::round(halves) || std::abs(halves) > 64.0 ||
        !base.dimension.RaisedTo(static_cast<int>(halves), &d))
      Fail(node.offset, "a quantity in " + base.dimension.Text() + " raised to " + Describe(exponent) +
                            " has no unit (powers of units must be multiples of 1/2)");
    if (base.value < 0.0 && exponent.value != std::round(exponent.value))
      Fail(node.offset, "a negative quantity to a power that is not whole");
    if (base.value == 0.0 && exponent.value < 0.0) Fail(node.offset, "zero to a negative power");
    return {std::pow(base.value, exponent.value), d, base.has_unit};
  }

  Quantity Call(const Node& node) const {
    std::vector<Quantity> a;
    for (const NodePtr& arg : node.args) a.push_back(Value(*arg));
    const std::string& f = node.name;
    if (f == "min" || f == "max") {
      Quantity best = a[0];
      for (std::size_t i = 1; i < a.size(); ++i) {
        RequireSame(*node.args[i], best, a[i], "compare");
        if (f == "min" ? a[i].value < best.value : a[i].value > best.value) best = a[i];
      }
      for (const Quantity& q : a) best.has_unit = best.has_unit || q.has_unit;
      return best;
    }
    if (f == "abs") return {std::abs(a[0].value), a[0].dimension, a[0].has_unit};
    if (f == "sqrt") {
      if (a[0].value < 0.0) Fail(node.offset, "sqrt of a negative number (" + Describe(a[0]) + ")");
      Dimension d;
      if (!a[0].dimension.RaisedTo(1, &d))
        Fail(node.offset, "sqrt of a quantity in " + a[0].dimension.Text() + " has no unit (powers of units must be multiples of 1/2)");
      return {std::sqrt(a[0].value), d, a[0].has_unit};
    }
    RequireNone(node, a[0], f);
    const double x = a[0].value;
    if ((f == "log" || f == "log10") && !(x > 0.0))
      Fail(node.offset, f + " of a number that is not positive (" + Describe(a[0]) + ")");
    if (f == "exp") return {std::exp(x), {}, false};
    if (f == "log") return {std::log(x), {}, false};
    if (f == "log10") return {std::log10(x), {}, false};
    if (f == "sin") return {std::sin(x), {}, false};
    if (f == "cos") return {std::cos(x), {}, false};
    return {std::tan(x), {}, false};
  }

  const std::string& text_;
  const Expression::Lookup& lookup_;
  const std::vector<std::string>& known_;
};

}  // namespace

ExpressionError::ExpressionError(const std::string& text, std::size_t offset, const std::string& what)
    : InputError(Message(text, offset, what)), column_(static_cast<int>(offset) + 1), reason_(what) {}

ExpressionError ExpressionError::At(const std::string& key_path) const {
  return ExpressionError(InputLocation{"", 0, 0, key_path}, message(), column_, reason_);
}

Expression Expression::Parse(const std::string& text) {
  if (text.size() > kMaxExpressionBytes)
    throw ExpressionError(text, 0, "longer than " + std::to_string(kMaxExpressionBytes) + " bytes (" +
                                       std::to_string(text.size()) + ")");
  for (std::size_t i = 0; i < text.size(); ++i)
    if (static_cast<unsigned char>(text[i]) < 0x20 && text[i] != '\t')
      throw ExpressionError(text, i, "a control character");
  Parser parser(text);
  Expression e;
  e.text_ = text;
  e.root_ = parser.ParseAll();
  e.names_ = std::move(parser.names);
  return e;
}

Quantity Expression::Evaluate(const Lookup& lookup, const std::vector<std::string>& known_names) const {
  DEB_DEMAND(root_ != nullptr);
  return Evaluator(text_, lookup, known_names).Value(*root_);
}

void Expression::RequireKnownNames(const std::vector<std::string>& known_names) const {
  for (const auto& used : names_)
    if (std::find(known_names.begin(), known_names.end(), used.first) == known_names.end())
      throw UnknownName(text_, used.second, used.first, known_names);
}

bool Expression::IsLiteral() const {
  if (!root_) return false;
  const Node* n = root_.get();
  if (n->kind == Node::Kind::kNegate) n = n->args[0].get();
  return n->kind == Node::Kind::kNumber;
}

std::string Expression::LiteralUnit() const {
  if (!IsLiteral()) return "";
  const Node* n = root_.get();
  if (n->kind == Node::Kind::kNegate) n = n->args[0].get();
  return n->unit;
}

}  // namespace deb
