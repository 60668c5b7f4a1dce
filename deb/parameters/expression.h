// Arithmetic with units, as a budget writes it wherever a number goes:
//   2100 kg        5.2e4 N/m        sqrt(4*k_iso/m)/(2*pi)        0.5 um
// The grammar (docs/budget_reference.md, "Parameters and expressions"):
//   sum     = product { ("+" | "-") product }
//   product = unary { ("*" | "/") unary }
//   unary   = ("+" | "-") unary | power
//   power   = atom [ "^" unary ]               (right-associative; -2^2 = -4)
//   atom    = number [unit] | name | function "(" sum { "," sum } ")" | "(" sum ")"
// A unit follows its number, with or without a space, in UDUNITS-2 syntax
// (unit.h): "210 mm", "6e4N/m", "50 N/(m/s)", "1 kg m2". It runs to the
// first "+", "*", ",", unbalanced ")" or to a "/" with a space before or
// after it, so "2 m / x" is (2 m) / x; a "-" belongs to it only as a power
// ("m s-2"). Inside a unit, multiply with a space or a dot, not "*".
// Names are parameters (resolved by the caller), the constant pi, and the
// functions sqrt exp log log10 sin cos tan abs min max. A number without a
// unit is dimensionless; "2 m" is two metres, "2*m" two times parameter m.
//
// Units are checked as the expression is evaluated: only quantities of one
// dimension add, compare (min, max) or take abs; exp, log, log10, sin, cos,
// tan and exponents take dimensionless arguments; sqrt and ^ keep powers
// that are multiples of 1/2. Values are held in coherent SI units
// (quantity.h).
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "deb/core/error.h"
#include "deb/units/quantity.h"

namespace deb {

// An expression that cannot be parsed or evaluated: the message names the
// expression and the column (1-based, in bytes) where it goes wrong; column()
// lets a loader locate it inside its file.
class ExpressionError : public InputError {
 public:
  ExpressionError(const std::string& text, std::size_t offset, const std::string& what);
  // The same error, located at `key_path` (a budget's parameter or field).
  ExpressionError At(const std::string& key_path) const;
  // 1-based byte column inside the expression's text.
  int column_in_text() const { return column_; }
  // The rule broken, without the expression (for a caller that shows it
  // itself).
  const std::string& reason() const { return reason_; }

 private:
  ExpressionError(InputLocation where, const std::string& message, int column, std::string reason)
      : InputError(std::move(where), message), column_(column), reason_(std::move(reason)) {}
  int column_ = 0;
  std::string reason_;
};

// Limits on what one expression may cost: text length and nesting depth.
inline constexpr std::size_t kMaxExpressionBytes = 4096;
inline constexpr int kMaxExpressionDepth = 64;

class Expression {
 public:
  // @throws ExpressionError on a syntax error, an unknown unit, a text
  // longer than kMaxExpressionBytes or nested deeper than
  // kMaxExpressionDepth.
  static Expression Parse(const std::string& text);

  // A parameter's value by name, or nullptr if there is none by that name.
  using Lookup = std::function<const Quantity*(const std::string& name)>;
  // @throws ExpressionError for an unknown name (with the nearest of
  // `known_names` suggested), a unit mismatch, a division by zero, a
  // function outside its domain or a result that is not finite.
  Quantity Evaluate(const Lookup& lookup, const std::vector<std::string>& known_names = {}) const;

  // @throws ExpressionError, as Evaluate would, at the first name it refers
  // to that is not in `known_names`.
  void RequireKnownNames(const std::vector<std::string>& known_names) const;

  // The parameter names it refers to (not pi or functions), each once, in
  // order of first use; with the byte offset of that use.
  const std::vector<std::pair<std::string, std::size_t>>& names() const { return names_; }
  const std::string& text() const { return text_; }
  // A number, possibly with a unit, and nothing else ("2100 kg", "0.02").
  bool IsLiteral() const;
  // The unit written after a literal's number ("kg"; "" if none or not a
  // literal).
  std::string LiteralUnit() const;

  struct Node;

 private:
  std::string text_;
  std::shared_ptr<const Node> root_;
  std::vector<std::pair<std::string, std::size_t>> names_;
};

}  // namespace deb
