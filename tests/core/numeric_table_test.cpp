#include "deb/core/numeric_table.h"

#include <doctest/doctest.h>

#include <sstream>

#include "deb/core/error.h"

namespace deb {
namespace {

NumericTable Parse(const std::string& text, NumericTableOptions options = {}) {
  std::istringstream in(text);
  return ParseNumericTable(in, "t.csv", options);
}

std::string ErrorOf(const std::string& text, NumericTableOptions options = {}) {
  try {
    Parse(text, options);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no InputError)";
}

TEST_CASE("a table keeps its header, rows, cell positions and the metadata asked for") {
  NumericTableOptions o;
  o.metadata_keys = {"unit"};
  const NumericTable t = Parse("# Unit: um/s\n# note: ignored\nf, a,b\n\n1, 2, 3  # trailing\n4 ,5,6\n", o);
  CHECK(t.header == std::vector<std::string>{"f", "a", "b"});
  CHECK(t.header_line == 3);
  CHECK(t.header_columns == std::vector<int>{1, 4, 6});
  REQUIRE(t.rows.size() == 2);
  CHECK(t.rows[0].line == 5);
  CHECK(t.rows[1].values == std::vector<double>{4, 5, 6});
  CHECK(t.rows[1].columns == std::vector<int>{1, 4, 6});
  REQUIRE(t.metadata.count("unit") == 1);
  CHECK(t.metadata.at("unit").value == "um/s");
  CHECK(t.metadata.at("unit").column == 9);
  CHECK(t.metadata.count("note") == 0);
  CHECK(t.columns() == 3);
}

TEST_CASE("whitespace separates cells when a line has no comma, and unnamed columns get the prefix") {
  NumericTableOptions o;
  o.unnamed_prefix = "ch";
  const NumericTable t = Parse("1\t2   3\n+4 5e-1 6\n", o);
  CHECK(t.header.empty());
  CHECK(t.rows[1].values == std::vector<double>{4, 0.5, 6});
  CHECK(t.ColumnName(2) == "ch2");
}

TEST_CASE("bad cells, ragged rows and repeated metadata are errors at their position") {
  CHECK(ErrorOf("1, x\n").find("t.csv:1:4: column 'column 1': 'x' is not a number") == 0);
  CHECK(ErrorOf("inf, 1\n").find("t.csv:1:1: frequency: 'inf' is not finite") == 0);
  CHECK(ErrorOf("f, a\n1, 2\n3\n").find("t.csv:3:2: row has 1 cells; expected 2 as on line 1") == 0);
  CHECK(ErrorOf("f, , b\n").find("t.csv:1:4: empty column name") == 0);
  NumericTableOptions o;
  o.metadata_keys = {"unit"};
  CHECK(ErrorOf("# unit: m\n# unit: m\n", o).find("t.csv:2:9: '# unit:' is given twice") == 0);
  CHECK(ErrorOf("# unit:\n", o).find("has no value") != std::string::npos);
}

}  // namespace
}  // namespace deb
