// The names an enum has in a budget or on the command line, in one table per
// enum: ToString writes from it and ParseEnum reads from it, and ParseEnum's
// error lists the allowed names from it, so the list cannot drift from what
// is accepted.
//
// Each enum declares, next to itself (found by argument-dependent lookup):
//   inline constexpr EnumName<Detrend> kDetrendNames[] = {
//       {Detrend::kNone, "none"}, {Detrend::kMean, "mean"}, ...};
//   constexpr EnumNames<Detrend> NamesOf(Detrend) { return kDetrendNames; }
// The first non-alias name of a value is the one written; aliases are
// accepted and listed after the names ("(or f32, f64)").
#pragma once

#include <cstddef>
#include <string>
#include <type_traits>
#include <utility>

#include "deb/core/error.h"

namespace deb {

// Marks a name accepted on input but never written: {kHann, "hanning", kAlias}.
inline constexpr bool kAlias = true;

template <typename T>
struct EnumName {
  T value;
  const char* name;
  bool alias = false;
};

// kIgnore: "VC-D" also matches "vc-d" (ASCII letters only).
enum class NameCase { kExact, kIgnore };

template <typename T>
class EnumNames {
 public:
  template <std::size_t N>
  constexpr EnumNames(const EnumName<T> (&names)[N], NameCase name_case = NameCase::kExact)
      : begin_(names), end_(names + N), name_case_(name_case) {}

  constexpr const EnumName<T>* begin() const { return begin_; }
  constexpr const EnumName<T>* end() const { return end_; }
  constexpr NameCase name_case() const { return name_case_; }

 private:
  const EnumName<T>* begin_;
  const EnumName<T>* end_;
  NameCase name_case_;
};

namespace enum_names {

// Whether `text` is `name` under the table's letter case.
bool Matches(const std::string& text, const char* name, NameCase name_case);

// "unknown <what> '<text>'; allowed: <allowed>", with key_path if not empty.
[[noreturn]] void ThrowUnknown(const std::string& what, const std::string& text, const std::string& allowed,
                               const std::string& key_path);

}  // namespace enum_names

// Enables a template for enums that have a name table.
template <typename T>
using IfNamedEnum = std::enable_if_t<std::is_enum_v<T>, decltype(NamesOf(std::declval<T>()))>;

// The table of T.
template <typename T, typename = IfNamedEnum<T>>
constexpr EnumNames<T> NameTableOf() {
  return NamesOf(T{});
}

// The name written for `value`: its first non-alias name.
template <typename T, typename = IfNamedEnum<T>>
std::string ToString(T value) {
  for (const EnumName<T>& n : NamesOf(value)) {
    if (!n.alias && n.value == value) return n.name;
  }
  DEB_DEMAND(false);  // a value without a name: its table is incomplete
  return {};
}

// "a, b, c" or, with aliases, "a, b, c (or x, y)".
template <typename T, typename = IfNamedEnum<T>>
std::string AllowedNames() {
  std::string names;
  std::string aliases;
  for (const EnumName<T>& n : NameTableOf<T>()) {
    std::string& list = n.alias ? aliases : names;
    list += (list.empty() ? "" : ", ") + std::string(n.name);
  }
  return aliases.empty() ? names : names + " (or " + aliases + ")";
}

// The value named by `text`. `what` names the setting in the message
// ("window"); key_path, if given, locates it in the budget.
// @throws InputError "unknown <what> '<text>'; allowed: <AllowedNames<T>()>".
template <typename T, typename = IfNamedEnum<T>>
T ParseEnum(const std::string& text, const std::string& what, const std::string& key_path = "") {
  const EnumNames<T> table = NameTableOf<T>();
  for (const EnumName<T>& n : table) {
    if (enum_names::Matches(text, n.name, table.name_case())) return n.value;
  }
  enum_names::ThrowUnknown(what, text, AllowedNames<T>(), key_path);
}

}  // namespace deb
