#include "deb/units/unit.h"

#include <udunits2.h>

#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <mutex>
#include <optional>
#include <unordered_map>
#include <vector>

#include "deb/core/error.h"
#include "deb/core/math_constants.h"

namespace deb {
namespace {

// Time-derivative orders ConvertUnit tries, the plain scale first.
constexpr int kDerivativeOrders[] = {0, -1, 1, -2, 2};
constexpr const char* kDatabasePackage = "libudunits2-data";
constexpr const char* kExamples = "examples: um/s, m/s^2, m s-2, nm, urad, N, 1";

struct UnitFree {
  void operator()(ut_unit* unit) const { ut_free(unit); }
};
using UnitPtr = std::unique_ptr<ut_unit, UnitFree>;

struct ConverterFree {
  void operator()(cv_converter* converter) const { cv_free(converter); }
};
using ConverterPtr = std::unique_ptr<cv_converter, ConverterFree>;

bool IsSpace(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v';
}

// A single symbol such as "nm" or "µm" needs no parentheses when raised to a
// power or multiplied; "um/s", "m2" or "kg m2" do.
bool IsSimpleSymbol(const std::string& unit) {
  if (unit.empty()) return false;
  for (const char c : unit) {
    const auto u = static_cast<unsigned char>(c);
    const bool ascii_letter = (u >= 'a' && u <= 'z') || (u >= 'A' && u <= 'Z');
    if (!ascii_letter && c != '_' && u < 0x80) return false;
  }
  return true;
}

std::string Factor(const std::string& display) {
  return IsSimpleSymbol(display) ? display : "(" + display + ")";
}

// Messages UDUNITS-2 prints while reading its database; kept only to explain
// a failed load. Written under std::call_once, so no other lock is needed.
std::string& LoadMessages() {
  static std::string messages;
  return messages;
}

int CaptureLoadMessage(const char* format, va_list args) {
  char buffer[512];
  const int n = std::vsnprintf(buffer, sizeof buffer, format, args);
  std::string& messages = LoadMessages();
  if (!messages.empty()) messages += "; ";
  messages += buffer;
  return n;
}

ut_system* LoadSystem() {
  LoadMessages().clear();
  ut_set_error_message_handler(CaptureLoadMessage);
  ut_system* system = ut_read_xml(nullptr);
  const ut_status status = ut_get_status();
  ut_set_error_message_handler(ut_ignore);
  if (system != nullptr) {
    LoadMessages().clear();  // harmless "overrides prefixed-unit" notes
    return system;
  }
  std::string where;
  const char* env = std::getenv("UDUNITS2_XML_PATH");
  if (status == UT_OPEN_ENV && env != nullptr) {
    where = "UDUNITS2_XML_PATH='" + std::string(env) + "' cannot be opened";
  } else if (status == UT_PARSE) {
    where = "the database file cannot be parsed";
  } else {
    where = "the default database file cannot be opened";
  }
  std::string message = "cannot load the UDUNITS-2 unit database: " + where;
  if (!LoadMessages().empty()) message += " (" + LoadMessages() + ")";
  message += ". It is /usr/share/xml/udunits/udunits2.xml, installed by the Debian package " +
             std::string(kDatabasePackage) +
             "; set UDUNITS2_XML_PATH to use another copy of udunits2.xml";
  throw InputError(message);
}

// The unit system, loaded once and kept for the process lifetime. If loading
// throws, the next call tries again.
ut_system* System() {
  static std::once_flag once;
  static ut_system* system = nullptr;
  std::call_once(once, [] { system = LoadSystem(); });
  return system;
}

// UDUNITS-2's parser keeps global state and its status is process-wide: every
// call into the library happens under this lock.
std::mutex& LibraryMutex() {
  static std::mutex mutex;
  return mutex;
}

// Results of the functions below, by their arguments (as DisplayUnit writes
// them): a budget asks the same few questions many times (every variant of a
// sweep converts the same units), and every call into UDUNITS-2 holds the
// one library lock, so threads evaluating variants queued on it. Only
// successes are kept (a failure ends the run with its message); at most
// kMaxEntries per function, so hostile input cannot grow it without bound.
template <class Value>
class Memo {
 public:
  std::optional<Value> Find(const std::string& key) {
    const std::lock_guard<std::mutex> lock(mutex_);
    const auto it = values_.find(key);
    if (it == values_.end()) return std::nullopt;
    return it->second;
  }
  void Store(const std::string& key, const Value& value) {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (values_.size() < kMaxEntries) values_.emplace(key, value);
  }

 private:
  static constexpr std::size_t kMaxEntries = 4096;
  std::mutex mutex_;
  std::unordered_map<std::string, Value> values_;
};

std::string MemoKey(const std::string& a, const std::string& b = {}) { return DisplayUnit(a) + '\n' + DisplayUnit(b); }

// Caller holds LibraryMutex().
UnitPtr Parse(ut_system* system, const std::string& unit) {
  const std::string text = DisplayUnit(unit);
  // Version 2.2.28 returns NULL on a syntax error without setting the status.
  ut_set_status(UT_SUCCESS);
  UnitPtr parsed(ut_parse(system, text.c_str(), UT_UTF8));
  if (parsed) return parsed;
  const std::string reason = ut_get_status() == UT_UNKNOWN
                                 ? "a name or prefix in it is not in the UDUNITS-2 database"
                                 : "it is not valid UDUNITS-2 unit syntax";
  throw InputError("unknown unit '" + unit + "': " + reason + " (" + kExamples + ")");
}

// Caller holds LibraryMutex(). Empty string when UDUNITS-2 cannot format it.
std::string Format(const ut_unit* unit) {
  std::vector<char> buffer(128);
  for (;;) {
    const int n = ut_format(unit, buffer.data(), buffer.size(), UT_ASCII | UT_DEFINITION);
    if (n < 0) return {};
    if (static_cast<std::size_t>(n) < buffer.size()) return std::string(buffer.data(), n);
    buffer.resize(buffer.size() * 2);
  }
}

std::string DefinitionForMessage(const ut_unit* unit) {
  const std::string definition = Format(unit);
  return definition.empty() ? "not expressible in ASCII" : definition;
}

enum class Relation { kNone, kNonLinear, kScale };

// Whether values in `from` map to `to` as y = scale x (+ offset, dropped).
// ut_are_convertible() also accepts reciprocal units (m and 1/m, s and Hz,
// converted by y = 1/x); those are different quantities here.
// Caller holds LibraryMutex().
Relation ScaleBetween(ut_unit* from, ut_unit* to, double* scale) {
  if (!ut_are_convertible(from, to)) return Relation::kNone;
  const ConverterPtr converter(ut_get_converter(from, to));
  if (!converter) return Relation::kNone;
  const double y0 = cv_convert_double(converter.get(), 0.0);
  const double y1 = cv_convert_double(converter.get(), 1.0);
  const double y2 = cv_convert_double(converter.get(), 2.0);
  constexpr double kTol = 1e-9;
  if (std::isfinite(y1) && y1 != 0.0 && std::abs(y1 - 2.0 * y2) <= kTol * std::abs(y1)) {
    return Relation::kNone;  // y = k / x
  }
  if (!std::isfinite(y0) || !std::isfinite(y1) || !std::isfinite(y2)) return Relation::kNonLinear;
  if (std::abs(y2 - 2.0 * y1 + y0) > kTol * (std::abs(y0) + std::abs(y1) + std::abs(y2))) {
    return Relation::kNonLinear;
  }
  // With an offset (degC -> K), a large argument keeps the slope's rounding
  // error at machine precision.
  constexpr double kProbe = 1e6;
  const double s = y0 == 0.0 ? y1 : (cv_convert_double(converter.get(), kProbe) - y0) / kProbe;
  if (!std::isfinite(s) || s == 0.0) return Relation::kNonLinear;
  *scale = s;
  return Relation::kScale;
}

std::string GramHint(const std::string& from, const std::string& to) {
  if (from != "g" && to != "g") return {};
  return "; note that 'g' is the gram in UDUNITS-2, standard free-fall acceleration is "
         "'gravity' (9.80665 m/s^2)";
}

}  // namespace

double UnitConversion::PsdFactor(double f_hz) const {
  DEB_DEMAND(std::isfinite(f_hz) && f_hz > 0.0);
  const double omega = 2.0 * kPi * f_hz;
  return scale * scale * std::pow(omega, 2 * derivative_order);
}

std::complex<double> UnitConversion::ResponseFactor(double f_hz) const {
  DEB_DEMAND(std::isfinite(f_hz) && f_hz > 0.0);
  const std::complex<double> j_omega(0.0, 2.0 * kPi * f_hz);
  std::complex<double> factor = scale;
  for (int k = 0; k < derivative_order; ++k) factor *= j_omega;
  for (int k = 0; k > derivative_order; --k) factor /= j_omega;
  return factor;
}

std::string UnitConversion::Describe() const {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "scale %.10g", scale);
  std::string text = buffer;
  const int n = std::abs(derivative_order);
  if (n == 0) return text;
  text += derivative_order < 0 ? ", integrated " : ", differentiated ";
  text += n == 1 ? "once" : n == 2 ? "twice" : std::to_string(n) + " times";
  return text + " in time";
}

void ValidateUnit(const std::string& unit) {
  static Memo<bool> valid;
  const std::string key = MemoKey(unit);
  if (valid.Find(key)) return;
  ut_system* system = System();
  {
    const std::lock_guard<std::mutex> lock(LibraryMutex());
    Parse(system, unit);
  }
  valid.Store(key, true);
}

namespace {

UnitConversion ConvertUnitUncached(const std::string& from, const std::string& to) {
  ut_system* system = System();
  const std::lock_guard<std::mutex> lock(LibraryMutex());
  const UnitPtr from_unit = Parse(system, from);
  const UnitPtr to_unit = Parse(system, to);
  const UnitPtr second(ut_get_unit_by_name(system, "second"));
  DEB_DEMAND(second != nullptr);
  const std::string from_text = DisplayUnit(from);
  const std::string to_text = DisplayUnit(to);

  // to = scale * from * s^-n.
  bool non_linear = false;
  for (const int n : kDerivativeOrders) {
    UnitPtr candidate;
    if (n != 0) {
      const UnitPtr time_power(ut_raise(second.get(), -n));
      if (time_power) candidate.reset(ut_multiply(from_unit.get(), time_power.get()));
      if (!candidate) continue;  // e.g. a logarithmic unit cannot be multiplied
    }
    ut_unit* source = n == 0 ? from_unit.get() : candidate.get();
    double scale = 1.0;
    const Relation relation = ScaleBetween(source, to_unit.get(), &scale);
    if (relation == Relation::kScale) return UnitConversion{scale, n};
    non_linear = non_linear || relation == Relation::kNonLinear;
  }
  if (non_linear) {
    throw InputError("cannot convert '" + from_text + "' to '" + to_text +
                     "': UDUNITS-2 relates them non-linearly (e.g. a logarithmic unit); deb "
                     "needs a linear scale");
  }
  throw InputError("cannot convert '" + from_text + "' to '" + to_text +
                   "': not the same quantity, nor related by up to two time derivatives ('" +
                   from_text + "' is " + DefinitionForMessage(from_unit.get()) + ", '" + to_text +
                   "' is " + DefinitionForMessage(to_unit.get()) + ")" +
                   GramHint(from_text, to_text));
}

}  // namespace

UnitConversion ConvertUnit(const std::string& from, const std::string& to) {
  static Memo<UnitConversion> conversions;
  const std::string key = MemoKey(from, to);
  if (const auto known = conversions.Find(key)) return *known;
  const UnitConversion conversion = ConvertUnitUncached(from, to);
  conversions.Store(key, conversion);
  return conversion;
}

bool UnitsCommensurate(const std::string& a, const std::string& b) {
  static Memo<bool> answers;
  const std::string key = MemoKey(a, b);
  if (const auto known = answers.Find(key)) return *known;
  ut_system* system = System();
  bool commensurate = false;
  {
    const std::lock_guard<std::mutex> lock(LibraryMutex());
    const UnitPtr a_unit = Parse(system, a);
    const UnitPtr b_unit = Parse(system, b);
    double scale = 1.0;
    commensurate = ScaleBetween(a_unit.get(), b_unit.get(), &scale) == Relation::kScale;
  }
  answers.Store(key, commensurate);
  return commensurate;
}

std::string DisplayUnit(const std::string& unit) {
  std::string text;
  bool pending_space = false;
  for (const char c : unit) {
    if (IsSpace(c)) {
      pending_space = !text.empty();
      continue;
    }
    if (pending_space) text += ' ';
    pending_space = false;
    text += c;
  }
  if (text.empty() || text == "-") return "1";
  return text;
}

std::string UnitDefinition(const std::string& unit) {
  static Memo<std::string> definitions;
  const std::string key = MemoKey(unit);
  if (auto known = definitions.Find(key)) return *known;
  ut_system* system = System();
  std::string definition;
  {
    const std::lock_guard<std::mutex> lock(LibraryMutex());
    const UnitPtr parsed = Parse(system, unit);
    definition = Format(parsed.get());
  }
  if (definition.empty()) {
    throw InputError("unit '" + unit + "': UDUNITS-2 cannot write its definition in ASCII");
  }
  definitions.Store(key, definition);
  return definition;
}

namespace {

// Collects a unit's scale and base-unit powers while UDUNITS-2 walks its
// structure (ut_accept_visitor): a Galilean unit is a scale (and an offset,
// dropped) on an underlying unit, a product unit basic units raised to
// powers, a basic unit a base unit or a dimensionless named one (rad).
struct SiWalk {
  double scale = 1.0;
  Dimension dimension;
  std::string failure;  // why the unit has no SI form
  int power = 1;        // of the unit being visited, within its product

  static ut_status Basic(const ut_unit* unit, void* arg) {
    auto* walk = static_cast<SiWalk*>(arg);
    if (ut_is_dimensionless(unit)) return UT_SUCCESS;
    const char* symbol = ut_get_symbol(unit, UT_ASCII);
    if (!symbol) symbol = ut_get_name(unit, UT_ASCII);
    const auto& symbols = Dimension::Symbols();
    for (int k = 0; k < Dimension::kBaseUnits; ++k) {
      if (symbol && std::string(symbol) == symbols[k]) {
        walk->dimension = walk->dimension * Dimension::Of(k, walk->power);
        return UT_SUCCESS;
      }
    }
    walk->failure = std::string("its base unit '") + (symbol ? symbol : "?") + "' is not an SI base unit";
    return UT_VISIT_ERROR;
  }
  static ut_status Product(const ut_unit*, int count, const ut_unit* const* units, const int* powers,
                           void* arg) {
    auto* walk = static_cast<SiWalk*>(arg);
    const int outer = walk->power;
    for (int i = 0; i < count; ++i) {
      walk->power = outer * powers[i];
      const ut_status status = Basic(units[i], arg);
      if (status != UT_SUCCESS) return status;
    }
    walk->power = outer;
    return UT_SUCCESS;
  }
  static ut_status Galilean(const ut_unit*, double scale, const ut_unit* underlying, double, void* arg);
  static ut_status Timestamp(const ut_unit*, const ut_unit*, double, void* arg) {
    static_cast<SiWalk*>(arg)->failure = "it is a time stamp";
    return UT_VISIT_ERROR;
  }
  static ut_status Logarithmic(const ut_unit*, double, const ut_unit*, void* arg) {
    static_cast<SiWalk*>(arg)->failure = "it is logarithmic";
    return UT_VISIT_ERROR;
  }
  static const ut_visitor& Visitor() {
    static const ut_visitor visitor{Basic, Product, Galilean, Timestamp, Logarithmic};
    return visitor;
  }
};

ut_status SiWalk::Galilean(const ut_unit*, double scale, const ut_unit* underlying, double, void* arg) {
  auto* walk = static_cast<SiWalk*>(arg);
  walk->scale *= std::pow(scale, walk->power);
  return ut_accept_visitor(underlying, &Visitor(), arg);
}

SiBaseUnits InSiBaseUnitsUncached(const std::string& unit) {
  ut_system* system = System();
  const std::lock_guard<std::mutex> lock(LibraryMutex());
  const UnitPtr parsed = Parse(system, unit);
  SiWalk walk;
  if (ut_accept_visitor(parsed.get(), &SiWalk::Visitor(), &walk) != UT_SUCCESS || !std::isfinite(walk.scale) ||
      walk.scale == 0.0) {
    throw InputError("unit '" + unit + "' has no value in SI base units" +
                     (walk.failure.empty() ? std::string() : ": " + walk.failure));
  }
  return {walk.scale, walk.dimension};
}

}  // namespace

SiBaseUnits InSiBaseUnits(const std::string& unit) {
  static Memo<SiBaseUnits> known_units;
  const std::string key = MemoKey(unit);
  if (auto known = known_units.Find(key)) return *known;
  const SiBaseUnits si = InSiBaseUnitsUncached(unit);
  known_units.Store(key, si);
  return si;
}

std::string PsdUnitLabel(const std::string& unit) {
  const std::string display = DisplayUnit(unit);
  if (display == "1") return "1/Hz";
  return Factor(display) + "^2/Hz";
}

std::string AsdUnitLabel(const std::string& unit) {
  const std::string display = DisplayUnit(unit);
  if (display == "1") return "1/sqrt(Hz)";
  return Factor(display) + "/sqrt(Hz)";
}

namespace {

std::string UnitProductUncached(const std::string& a, const std::string& b) {
  ut_system* system = System();
  const std::lock_guard<std::mutex> lock(LibraryMutex());
  Parse(system, a);
  Parse(system, b);
  const std::string a_text = DisplayUnit(a);
  const std::string b_text = DisplayUnit(b);
  if (a_text == "1") return b_text;
  if (b_text == "1") return a_text;
  const std::string product = Factor(a_text) + " " + Factor(b_text);
  ut_set_status(UT_SUCCESS);
  const UnitPtr parsed(ut_parse(system, product.c_str(), UT_UTF8));
  if (!parsed) {
    throw InputError("cannot multiply units '" + a_text + "' and '" + b_text +
                     "': UDUNITS-2 does not accept the product '" + product + "'");
  }
  return product;
}


}  // namespace

std::string UnitProduct(const std::string& a, const std::string& b) {
  static Memo<std::string> products;
  const std::string key = MemoKey(a, b);
  if (auto known = products.Find(key)) return *known;
  const std::string product = UnitProductUncached(a, b);
  products.Store(key, product);
  return product;
}

}  // namespace deb
