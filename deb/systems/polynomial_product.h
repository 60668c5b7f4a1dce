// Internal: not part of the public API.
// The product of two polynomials given by their coefficients, in either
// order (highest or lowest power first): the product's coefficients come in
// the same order as the factors'. Both factors must be non-empty.
#pragma once

#include <vector>

namespace deb {

template <typename T>
std::vector<T> PolynomialProduct(const std::vector<T>& a, const std::vector<T>& b) {
  std::vector<T> c(a.size() + b.size() - 1, T(0));
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j) c[i + j] += a[i] * b[j];
  return c;
}

}  // namespace deb
