// The result of contributor `name` on output `o`; the test stops, naming it,
// if there is none. The helper the suites that read one contributor share.
#pragma once

#include <doctest/doctest.h>

#include <string>

#include "deb/budget/result.h"

namespace deb::test {

inline const ContributorResult& ContributorOf(const OutputResult& o, const std::string& name) {
  for (const ContributorResult& c : o.contributors)
    if (c.name == name) return c;
  FAIL("no contributor " << name);
  return o.contributors.front();
}

}  // namespace deb::test
