// Mode and shape tables of a finite-element modal analysis: what they hold,
// and every bad table as an error at its file:line:column.
#include "deb/systems/modal_csv.h"

#include <doctest/doctest.h>

#include <sstream>

#include "deb/core/error.h"
#include "deb/core/numeric_table.h"
#include "test_util.h"

namespace deb {
namespace {

using testing::MessageOf;

ModeTable Modes(const std::string& text) {
  std::istringstream in(text);
  return ParseModeTable(in, "modes.csv");
}

ShapeTable Shapes(const std::string& text, int expected = 2) {
  std::istringstream in(text);
  return ParseShapeTable(in, "phi.csv", expected, "the mode table 'modes.csv'");
}

std::string ModesError(const std::string& text) {
  return MessageOf([&] { Modes(text); });
}
std::string ShapesError(const std::string& text, int expected = 2) {
  return MessageOf([&] { Shapes(text, expected); });
}

TEST_CASE("a mode table gives f_hz and zeta per row, columns by name, in any order") {
  const ModeTable m = Modes("# from the FE model\nmode, zeta, f_hz\n1, 0.02, 42\n2, 0.05, 0\n");
  CHECK(m.f_hz == std::vector<double>{42.0, 0.0});
  CHECK(m.zeta == std::vector<double>{0.02, 0.05});
}

TEST_CASE("a shape table gives a name and one value per mode in each row") {
  const ShapeTable s = Shapes("dof, m1, m2\nF1, 0.3, -0.1\nF 2 , 1e-3, 2\n");
  CHECK(s.dofs == std::vector<std::string>{"F1", "F 2"});
  CHECK(s.values.rows() == 2);
  CHECK(s.values(0, 1) == -0.1);
  CHECK(s.values(1, 0) == 1e-3);
}

TEST_CASE("bad mode tables are errors at their cell") {
  CHECK(ModesError("42, 0.02\n") == "modes.csv:1:1: a mode table needs a header row: f_hz, zeta (and optionally mode)");
  CHECK(ModesError("f_hz, damping\n1, 0.1\n") ==
        "modes.csv:1:7: unknown column 'damping'; a mode table has the columns f_hz, zeta and optionally mode");
  CHECK(ModesError("f_hz, zeta, f_hz\n1, 0.1, 1\n") == "modes.csv:1:13: column 'f_hz' is given twice");
  CHECK(ModesError("f_hz\n1\n") == "modes.csv:1:1: missing column 'zeta'; a mode table has the columns f_hz and zeta");
  CHECK(ModesError("f_hz, zeta\n") == "modes.csv:1:1: the mode table has no rows; give one row per mode");
  CHECK(ModesError("f_hz, zeta\n1, 0.1\n-3, 0.1\n") ==
        "modes.csv:3:1: natural frequency -3 Hz is negative; it must be >= 0 (0: a rigid-body mode)");
  CHECK(ModesError("f_hz, zeta\n1, 0\n") ==
        "modes.csv:2:4: damping ratio 0 of a mode at 1 Hz must be > 0 (an undamped mode has an infinite variance "
        "under white forcing)");
  CHECK(testing::Contains(ModesError("f_hz, zeta\n1, 1.5\n"), "modes.csv:2:4: damping ratio 1.5 is >= 1"));
  CHECK(ModesError("f_hz, zeta\n1, inf\n") == "modes.csv:2:4: column 'zeta': 'inf' is not finite; values must be finite");
  CHECK(ModesError("f_hz, zeta\nx, 0.1\n") == "modes.csv:2:1: first column: 'x' is not a number");
}

TEST_CASE("bad shape tables are errors at their cell") {
  CHECK(ShapesError("dof, a, b, c\nF1, 1, 2, 3\n") ==
        "phi.csv:1:12: 3 mode column(s), but the mode table 'modes.csv' has 2 mode(s); give one column per mode, in "
        "its order");
  CHECK(ShapesError("dof, a\nF1, 1\n") ==
        "phi.csv:1:1: 1 mode column(s), but the mode table 'modes.csv' has 2 mode(s); give one column per mode, in "
        "its order");
  CHECK(ShapesError("dof\nF1\n") == "phi.csv:1:1: no mode columns: after the DOF column, give one column per mode");
  CHECK(ShapesError("dof, a, b\n") == "phi.csv:1:1: the shape table has no rows; give one row per DOF");
  CHECK(ShapesError("dof, a, b\nF1, 1, 2\nF2, 3, 4\nF1, 5, 6\n") ==
        "phi.csv:4:1: DOF 'F1' is given twice (also on line 2)");
  CHECK(ShapesError("dof, a, b\n, 1, 2\n") == "phi.csv:2:1: DOF name: empty cell; every row starts with a name");
  CHECK(ShapesError("dof, a, b\nF1, 1, x\n") == "phi.csv:2:8: column 'b': 'x' is not a number");
  CHECK(ShapesError("dof, a, b\nF1, 1, nan\n") == "phi.csv:2:8: column 'b': 'nan' is not finite; values must be finite");
  CHECK(ShapesError("dof, a, b\nF1, 1\n") == "phi.csv:2:6: row has 2 cells; expected 3 as on line 1");
  CHECK(Shapes("dof, a\nF1, 1\n", -1).values.cols() == 1);  // any count when none is expected
}

TEST_CASE("names_in_first_column: the first cell is a name, the header is always the first line") {
  NumericTableOptions o;
  o.names_in_first_column = true;
  std::istringstream in("1, 2\nx 3, 4\n");  // a numeric first line is still the header
  const NumericTable t = ParseNumericTable(in, "t.csv", o);
  CHECK(t.header == std::vector<std::string>{"1", "2"});
  REQUIRE(t.rows.size() == 1);
  CHECK(t.rows[0].name == "x 3");
  CHECK(t.rows[0].values == std::vector<double>{0.0, 4.0});
  CHECK(t.rows[0].columns == std::vector<int>{1, 6});
}

}  // namespace
}  // namespace deb
