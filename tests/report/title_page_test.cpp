#include "deb/report/title_page.h"
#include "deb/version.h"

#include <doctest/doctest.h>

namespace deb::report {
namespace {

Table Rows(int n) {
  Table t;
  t.title = "Contributors";
  t.header = {"contributor", "RMS"};
  t.numeric = {false, true};
  for (int i = 0; i < n; ++i) t.rows.push_back({"c" + std::to_string(i), "1.0"});
  return t;
}

int Count(const std::string& s, const std::string& what) {
  int n = 0;
  for (auto p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++n;
  return n;
}

}  // namespace

TEST_CASE("words wrap at spaces within the width") {
  CHECK(Wrap("one two three four", 9) == std::vector<std::string>{"one two", "three", "four"});
  CHECK(Wrap("", 10).empty());
}

TEST_CASE("a short budget has one title page holding facts, conventions and tables") {
  ReportFacts f;
  f.items = {{"budget", "b"}, {"SHA-256", "abc"}};
  f.conventions = {"PSDs are one-sided."};
  const TitlePages p = MakeTitlePages("b", "A description.", f, {Rows(3)}, {"a warning"});
  CHECK(p.pages == 1);
  CHECK(Count(p.script, "\nplot ") == 1);
  CHECK(p.script.find("'Dynamic error budget: b'") != std::string::npos);
  CHECK(p.script.find("SHA-256  abc") != std::string::npos);
  CHECK(p.script.find("'- a warning'") != std::string::npos);
  CHECK(p.script.find("noenhanced") != std::string::npos);
}

TEST_CASE("a long table continues on further pages with its heading and column header repeated") {
  const TitlePages p = MakeTitlePages("b", "", {}, {Rows(100)}, {});
  CHECK(p.pages == 3);
  CHECK(Count(p.script, "\nplot ") == 3);
  CHECK(Count(p.script, "'Contributors (continued)'") == 2);
  CHECK(Count(p.script, "'contributor  RMS'") == 3);
  CHECK(p.script.find("'c99" + std::string(10, ' ') + "1.0'") != std::string::npos);
}

TEST_CASE("a cell the table shortens is printed in full below it") {
  Table t;
  t.title = "Contributors";
  t.header = {"contributor", "note"};
  t.numeric = {false, false};
  const std::string name = "a_contributor_with_a_very_long_descriptive_name";
  t.rows = {{name, "short"}};
  const TitlePages p = MakeTitlePages("b", "", {}, {t}, {});
  CHECK(p.script.find("…") != std::string::npos);  // the table's cell
  CHECK(p.script.find("'  * " + name + ": contributor: " + name + "'") != std::string::npos);
}

TEST_CASE("every page's footer names deb, the budget, the file's digest and the page among all") {
  CHECK(PageFooter("b", "0123456789abcdef", 3, 40) ==
        "deb " + std::string(DEB_VERSION) + " · b · SHA-256 0123456789ab · page 3/40");
  CHECK(PageFooter("b", "", 1, 2) == "deb " + std::string(DEB_VERSION) + " · b · page 1/2");
  const TitlePages p = MakeTitlePages("b", "", {}, {Rows(100)}, {}, 47, "feedbeef");  // 3 title pages + 47
  CHECK(p.script.find("'deb " + std::string(DEB_VERSION) + " · b · SHA-256 feedbeef · page 3/50'") != std::string::npos);
}

}  // namespace deb::report
