#include "deb/core/suggest.h"

#include <doctest/doctest.h>

namespace deb {

TEST_CASE("edit distance counts insertions, deletions and substitutions") {
  CHECK(EditDistance("", "") == 0);
  CHECK(EditDistance("run", "run") == 0);
  CHECK(EditDistance("runn", "run") == 1);
  CHECK(EditDistance("rnu", "run") == 2);  // a transposition is two edits
  CHECK(EditDistance("kitten", "sitting") == 3);
  CHECK(EditDistance("", "abc") == 3);
  CHECK(EditDistance("abc", "") == 3);
}

TEST_CASE("the nearest name is offered for a likely typo only") {
  const std::vector<std::string> commands = {"run", "check", "model", "spectrum", "compare", "sweep", "sensitivity"};
  CHECK(NearestName("runn", commands) == "run");
  CHECK(NearestName("chek", commands) == "check");
  CHECK(NearestName("sensitivty", commands) == "sensitivity");
  CHECK(NearestName("swep", commands) == "sweep");
  CHECK(NearestName("run", commands) == "");      // not a typo
  CHECK(NearestName("plot", commands) == "");     // nothing near
  CHECK(NearestName("x", commands) == "");        // one letter is no evidence
  CHECK(NearestName("modal", commands) == "model");
  CHECK(NearestName("deploy", commands) == "");
}

}  // namespace deb

namespace deb {

TEST_CASE("did-you-mean text names the nearest candidate, or is empty") {
  const std::vector<std::string> keys = {"name", "source", "path", "exact", "description"};
  CHECK(DidYouMean("sorce", keys) == " (did you mean 'source'?)");
  CHECK(DidYouMean("colour", keys) == "");
  CHECK(DidYouMean("source", keys) == "");
}

}  // namespace deb
