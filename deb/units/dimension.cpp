#include "deb/units/dimension.h"

#include <cstdlib>

namespace deb {

const std::array<const char*, Dimension::kBaseUnits>& Dimension::Symbols() {
  static const std::array<const char*, kBaseUnits> symbols{"m", "kg", "s", "A", "K", "mol", "cd"};
  return symbols;
}

Dimension Dimension::Of(int base, int power) {
  Dimension d;
  d.half_[base] = 2 * power;
  return d;
}

bool Dimension::IsNone() const {
  for (const int h : half_)
    if (h != 0) return false;
  return true;
}

Dimension Dimension::operator*(const Dimension& other) const {
  Dimension d;
  for (int k = 0; k < kBaseUnits; ++k) d.half_[k] = half_[k] + other.half_[k];
  return d;
}

Dimension Dimension::operator/(const Dimension& other) const {
  Dimension d;
  for (int k = 0; k < kBaseUnits; ++k) d.half_[k] = half_[k] - other.half_[k];
  return d;
}

bool Dimension::RaisedTo(int halves, Dimension* result) const {
  Dimension d;
  for (int k = 0; k < kBaseUnits; ++k) {
    // (h / 2) (halves / 2) = h halves / 4, in halves: h halves / 2.
    const long product = static_cast<long>(half_[k]) * halves;
    if (product % 2 != 0) return false;
    d.half_[k] = static_cast<int>(product / 2);
  }
  *result = d;
  return true;
}

std::string Dimension::Text() const {
  std::string text;
  for (int k = 0; k < kBaseUnits; ++k) {
    const int h = half_[k];
    if (h == 0) continue;
    if (!text.empty()) text += ' ';
    text += Symbols()[k];
    if (h == 2) continue;
    text += h % 2 == 0 ? std::to_string(h / 2) : std::to_string(h) + "/2";
  }
  return text.empty() ? "1" : text;
}

}  // namespace deb
