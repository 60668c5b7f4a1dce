#include "deb/core/key_positions.h"

#include <doctest/doctest.h>

namespace deb {

TEST_CASE("an input error's text is formatted from its location") {
  CHECK(std::string(InputError("plain").what()) == "plain");
  CHECK(std::string(InputError("outputs[0].unit", "no such unit").what()) == "outputs[0].unit: no such unit");
  const InputError e(InputLocation{"b.yaml", 3, 7, "sources[0].unit"}, "no such unit");
  CHECK(std::string(e.what()) == "b.yaml:3:7: sources[0].unit: no such unit");
  CHECK(e.message() == "no such unit");
  CHECK(e.file() == "b.yaml");
  CHECK(e.line() == 3);
  CHECK(e.column() == 7);
  CHECK(e.key_path() == "sources[0].unit");
  CHECK(std::string(InputError(InputLocation{"b.yaml", 0, 0, ""}, "not a map").what()) == "b.yaml: not a map");
  CHECK(std::string(InputError(InputLocation{"b.yaml", 2, 1, ""}, "bad").what()) == "b.yaml:2:1: bad");
  CHECK_FALSE(InputError("plain").located());
  CHECK(InputError("k", "m").located());
}

TEST_CASE("a key path is located at itself or at its closest recorded parent") {
  KeyPositions p("b.yaml");
  p.Record("", 1, 1);
  p.Record("contributors", 2, 3);
  p.Record("contributors[0]", 3, 5);
  p.Record("contributors[0].path", 3, 30);
  p.Record("contributors[0].path", 9, 9);  // the first record stays
  const InputLocation at = p.Locate("contributors[0].path");
  CHECK(at.file == "b.yaml");
  CHECK(at.line == 3);
  CHECK(at.column == 30);
  CHECK(at.key_path == "contributors[0].path");
  CHECK(p.Locate("contributors[0].exact").column == 5);
  CHECK(p.Locate("contributors[4].path").line == 2);
  CHECK(p.Locate("grid.points").line == 0);  // no grid in the file: the file alone
  KeyPositions none("c.yaml");
  CHECK(none.Locate("grid").line == 0);
  CHECK(std::string(InputError(none.Locate("grid"), "bad").what()) == "c.yaml: grid: bad");
}

TEST_CASE("an error with a key path is located once, with an optional note; others stay as they are") {
  KeyPositions p("b.yaml");
  p.Record("outputs[0].unit", 12, 40);
  const InputError e = p.Located(InputError("outputs[0].unit", "kg cannot be formed from um"));
  CHECK(std::string(e.what()) == "b.yaml:12:40: outputs[0].unit: kg cannot be formed from um");
  CHECK(std::string(p.Located(e).what()) == std::string(e.what()));
  CHECK(std::string(p.Located(InputError("outputs[0].unit", "bad"), "sweep variant 2: x = 1").what()) ==
        "b.yaml:12:40: outputs[0].unit: sweep variant 2: x = 1: bad");
  CHECK(std::string(p.Located(InputError("spec.csv:3:1: not a number")).what()) == "spec.csv:3:1: not a number");
}

}  // namespace deb
