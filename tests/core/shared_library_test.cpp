// deb/core/shared_library.h: a library loaded at run time gives typed
// functions that work; a missing library or symbol is a failure text naming
// it, the first one kept.
#include "deb/core/shared_library.h"

#include <doctest/doctest.h>

#include <string>

namespace deb {

TEST_CASE("a shared library's function is resolved and called; a missing one is named") {
  SharedLibrary m("libm.so.6");
  REQUIRE(m.loaded());
  double (*cosine)(double) = nullptr;
  REQUIRE(m.Resolve("cos", cosine));
  CHECK(cosine(0.0) == 1.0);
  CHECK(m.failure().empty());
  CHECK(m.Has("sin"));
  CHECK_FALSE(m.Has("no_such_function_in_libm"));
  CHECK(m.failure().empty());  // Has records no failure
  void (*none)() = nullptr;
  CHECK_FALSE(m.Resolve("no_such_function_in_libm", none));
  CHECK(static_cast<bool>(none == nullptr));
  CHECK(m.failure() == "libm.so.6 has no symbol no_such_function_in_libm");
  CHECK_FALSE(m.Resolve("another_missing_one", none));
  CHECK(m.failure() == "libm.so.6 has no symbol no_such_function_in_libm");  // the first failure
}

TEST_CASE("a library that cannot be loaded says why, and resolves nothing") {
  SharedLibrary missing("libdeb-no-such-library.so.1");
  CHECK_FALSE(missing.loaded());
  CHECK(missing.failure().find("libdeb-no-such-library.so.1") != std::string::npos);
  double (*cosine)(double) = nullptr;
  CHECK_FALSE(missing.Resolve("cos", cosine));
  CHECK(static_cast<bool>(cosine == nullptr));
}

}  // namespace deb
