// The physical dimension of a quantity: the powers of the seven SI base
// units (m, kg, s, A, K, mol, cd) it is made of. Angles (rad, deg) are
// dimensionless, as everywhere in deb (unit.h). Powers are held in halves so
// that the square root of a spectral density (m^2/Hz -> m/sqrt(Hz)) keeps a
// dimension; a power that is not a multiple of 1/2 is not representable.
#pragma once

#include <array>
#include <string>

namespace deb {

class Dimension {
 public:
  static constexpr int kBaseUnits = 7;
  // The base units' symbols, in the order of the powers.
  static const std::array<const char*, kBaseUnits>& Symbols();

  Dimension() = default;
  // base^power for base unit `base` (index into Symbols()).
  static Dimension Of(int base, int power);

  bool IsNone() const;  // dimensionless
  // Twice the power of base unit `base`.
  int HalfPowers(int base) const { return half_[base]; }

  Dimension operator*(const Dimension& other) const;
  Dimension operator/(const Dimension& other) const;
  // This dimension to the power halves / 2 (halves = 1: the square root).
  // False if a power would not be a multiple of 1/2.
  bool RaisedTo(int halves, Dimension* result) const;

  bool operator==(const Dimension& other) const { return half_ == other.half_; }
  bool operator!=(const Dimension& other) const { return !(*this == other); }

  // In base units for messages: "kg m-1 s-2", "m s-1/2", "1" if none.
  std::string Text() const;

 private:
  std::array<int, kBaseUnits> half_{};
};

}  // namespace deb
