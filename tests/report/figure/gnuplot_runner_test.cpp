#include "deb/report/figure/gnuplot_runner.h"

#include <doctest/doctest.h>

#include <sys/stat.h>

#include "deb/core/error.h"
#include "deb/report/figure/plot.h"
#include "tests/support/cli_harness.h"

namespace deb::report {
namespace {

using namespace deb::test;

// A stand-in for gnuplot that reads its commands and fails like gnuplot does.
fs::path FailingGnuplot(const fs::path& dir) {
  const fs::path exe = WriteFile(dir / "fake-gnuplot",
                                 "#!/bin/sh\ncat > /dev/null\n"
                                 "echo '\"z_velocity_cps.gp\" line 12: undefined variable: nonsense' >&2\nexit 1\n");
  ::chmod(exe.c_str(), 0755);
  return exe;
}

}  // namespace

TEST_CASE("a missing gnuplot executable is an error that names it and how to fix it") {
  CHECK_THROWS_WITH_AS(FindGnuplot("/nonexistent/gnuplot"),
                       doctest::Contains("gnuplot executable '/nonexistent/gnuplot'"), WriteError);
  CHECK_THROWS_WITH_AS(FindGnuplot("/nonexistent/gnuplot"), doctest::Contains("DEB_GNUPLOT"), WriteError);
  CHECK_THROWS_WITH_AS(FindGnuplot("no-such-gnuplot-anywhere"), doctest::Contains("(as requested)"), WriteError);
}

TEST_CASE("without a request or DEB_GNUPLOT, gnuplot is searched on PATH") {
  const std::string path = std::getenv("PATH") ? std::getenv("PATH") : "";
  ::unsetenv(kGnuplotVariable);
  ::setenv("PATH", TempDir("empty_path").c_str(), 1);
  CHECK_THROWS_WITH_AS(FindGnuplot(""), doctest::Contains("'gnuplot' (searched on PATH)"), WriteError);
  ::setenv("PATH", path.c_str(), 1);
  CHECK(fs::path(FindGnuplot("")).filename() == "gnuplot");
}

TEST_CASE("the gnuplot executable comes from the request, then DEB_GNUPLOT, then PATH") {
  const fs::path dir = TempDir("find");
  const fs::path exe = FailingGnuplot(dir);
  CHECK(FindGnuplot(exe.string()) == exe.string());
  ::setenv(kGnuplotVariable, exe.c_str(), 1);
  CHECK(FindGnuplot("") == exe.string());
  ::setenv(kGnuplotVariable, "/nonexistent/gnuplot", 1);
  CHECK_THROWS_WITH_AS(FindGnuplot(""), doctest::Contains("from DEB_GNUPLOT"), WriteError);
  ::unsetenv(kGnuplotVariable);
  CHECK(fs::path(FindGnuplot("")).filename() == "gnuplot");
}

TEST_CASE("a gnuplot error is a WriteError that quotes gnuplot and names the plot") {
  const fs::path dir = TempDir("error");
  const std::string gnuplot = FindGnuplot("");
  CHECK_THROWS_WITH_AS(RunGnuplot(gnuplot, dir.string(), "plot no_such_function(x)\n", "plot broken"),
                       doctest::Contains("undefined function"), WriteError);
  CHECK_THROWS_WITH_AS(RunGnuplot(gnuplot, dir.string(), "plot no_such_function(x)\n", "plot broken"),
                       doctest::Contains("cannot draw plot broken"), WriteError);
  // Nothing of the failed run is left in the temporary directory.
  CHECK(CountWithPrefix(fs::temp_directory_path(), "deb-gnuplot-" + std::to_string(::getpid()) + "-") == 0);
}

TEST_CASE("a working script runs in the given directory") {
  const fs::path dir = TempDir("ok");
  RunGnuplot(FindGnuplot(""), dir.string(),
             "set terminal pngcairo size 100,80\nset output 'x.png'\nplot sin(x) notitle\nunset output\n", "plot x");
  CHECK(fs::file_size(dir / "x.png") > 0);
}

TEST_CASE("deb run without gnuplot exits with 4, says why and leaves no report directory behind") {
  const fs::path parent = TempDir("cli_missing");
  const Command r = RunDeb("run " + ExampleBudget() + " --out " + (parent / "rep").string(),
                           "DEB_GNUPLOT=/nonexistent/gnuplot");
  CHECK(r.exit_code == 4);
  CHECK(r.err.find("gnuplot executable '/nonexistent/gnuplot'") != std::string::npos);
  CHECK_FALSE(fs::exists(parent / "rep"));
  CHECK(CountWithPrefix(parent, ".rep") == 0);
}

TEST_CASE("deb run with a failing gnuplot exits with 4, quotes gnuplot and keeps an older report intact") {
  const fs::path parent = TempDir("cli_error");
  const fs::path out = parent / "rep";
  REQUIRE(RunDeb("run -q " + ExampleBudget() + " --out " + out.string() + " --no-plots").exit_code == 0);
  const std::string before = ReadAll(out / "summary.json");
  const Command r = RunDeb("run " + ExampleBudget() + " --out " + out.string(),
                           "DEB_GNUPLOT=" + FailingGnuplot(parent).string());
  CHECK(r.exit_code == 4);
  CHECK(r.err.find("undefined variable: nonsense") != std::string::npos);
  CHECK(r.err.find("exited with status 1") != std::string::npos);
  CHECK(ReadAll(out / "summary.json") == before);
  CHECK_FALSE(fs::exists(out / "plots" / "overview.png"));
  CHECK(CountWithPrefix(parent, ".rep") == 0);
}

TEST_CASE("deb run --no-plots needs no gnuplot") {
  const fs::path parent = TempDir("cli_noplots");
  const Command r = RunDeb("run -q " + ExampleBudget() + " --out " + (parent / "rep").string() + " --no-plots",
                           "DEB_GNUPLOT=/nonexistent/gnuplot");
  CHECK(r.exit_code == 0);
  CHECK(fs::is_regular_file(parent / "rep" / "index.html"));
  CHECK(fs::is_regular_file(parent / "rep" / "report.md"));
}

TEST_CASE("deb run rejects an unknown or repeated plot format as a usage error") {
  const fs::path parent = TempDir("cli_format");
  CHECK(RunDeb("run " + ExampleBudget() + " --out " + (parent / "a").string() + " --format png,gif").exit_code == 2);
  CHECK(RunDeb("run " + ExampleBudget() + " --out " + (parent / "b").string() + " --format png,png").exit_code == 2);
  const Command r = RunDeb("run -q " + ExampleBudget() + " --out " + (parent / "c").string() + " --format pdf");
  CHECK(r.exit_code == 0);
  CHECK(PdfPages(parent / "c" / "report.pdf") > 1);
  CHECK_FALSE(fs::exists(parent / "c" / "plots" / "overview.png"));
}

TEST_CASE("deb run writes no progress to stderr when stderr is not a terminal") {
  const fs::path parent = TempDir("cli_quiet");
  const Command r = RunDeb("run " + ExampleBudget() + " --out " + (parent / "rep").string());
  CHECK(r.exit_code == 0);
  CHECK(r.err.find("drawing") == std::string::npos);
}

}  // namespace deb::report

namespace deb::report {

TEST_CASE("a script may carry user text only in single quotes: backquotes, macros and shell escapes are refused") {
  CHECK(ScriptOffence("set title 'a`touch x`b @m $HOME'\nplot sin(x) title 'it''s'\n").empty());
  CHECK(ScriptOffence("set title ('one'.\"\\n\".'two')\n").empty());
  CHECK(ScriptOffence("set title \"a`touch x`\"\n") == "a backquote inside a double-quoted string");
  CHECK(ScriptOffence("print `touch x`\n") == "a backquote outside a single-quoted string");
  CHECK(ScriptOffence("t = 'x'\n@t\n") == "an '@' (macro) outside a single-quoted string");
  CHECK(ScriptOffence("!touch x\n") == "a '!' shell command");
  CHECK(ScriptOffence("set xrange [0:1]; !touch x\n") == "a '!' shell command");
  CHECK(ScriptOffence("x = system('touch x')\n") == "a call of system");
  CHECK(ScriptOffence("set title 'a\nb'\n") == "a line break inside a single-quoted string");
  CHECK(ScriptOffence("set title 'a\n") == "a line break inside a single-quoted string");
  CHECK(ScriptOffence("if (a != b) print 1\n").empty());
  // What Quote makes of hostile text always passes.
  CHECK(ScriptOffence("set title " + Quote("`rm -rf ~` @x ' \n!ls system('x')") + "\n").empty());
  CHECK(ScriptOffence("set title " + QuoteLines("`a`\n@b") + "\n").empty());
}

TEST_CASE("a file name that gnuplot would take for a pipe or a command is refused; QuoteFile makes it a file") {
  CHECK(ScriptOffence("set output '|id > x'\n") == "a file name starting with '|' (a pipe)");
  CHECK(ScriptOffence("load '<cat /etc/passwd'\n") == "a file name starting with '<' (a pipe)");
  CHECK(ScriptOffence("plot '<ls' using 1:2\n") == "a file name starting with '<' (a pipe)");
  CHECK(ScriptOffence("plot 'a.csv' using 1:2 title 'x', \"|id\" using 1:2\n") ==
        "a file name starting with '|' (a pipe)");
  CHECK(ScriptOffence("set print '|id'\n") == "a file name starting with '|' (a pipe)");
  // Text that is no file name may start so: a title, a label, a tic label.
  CHECK(ScriptOffence("set title '<1 nm'\nset label 1 '|x|' at 1,1\nset xtics ('<1' 1, '|2' 2)\n").empty());
  CHECK(ScriptOffence("plot 'a.csv' using 1:2 title '<3 Hz', 'b.csv' using 1:2 title '|b|'\n").empty());
  for (const std::string name : {"|cd ..; id > x; echo y.png", "<id", "!id", "|"}) {
    CHECK(ScriptOffence("set output " + QuoteFile(name) + "\nload " + QuoteFile(name + ".gp") + "\nplot " +
                        QuoteFile(name + ".csv") + " using 1:2, " + QuoteFile(name) + " using 1:3\n")
              .empty());
    CHECK(QuoteFile(name).rfind("'./", 0) == 0);
  }
  CHECK(QuoteFile("/abs/a.png") == "'/abs/a.png'");
  CHECK(QuoteFile("it's.png") == "'it''s.png'");
}

TEST_CASE("deb spectrum with an output name that starts with a pipe writes that file and runs nothing") {
  const fs::path dir = TempDir("pipe_name");
  // The plots are drawn in a directory below dir: "cd .." would reach dir.
  const std::string name = "|cd ..; touch ran.txt; echo y.csv";
  const Command r = RunDebIn(dir, "spectrum reference nlnm -o '" + name + "'");
  CHECK_MESSAGE(r.exit_code == 0, r.err);
  CHECK_FALSE(fs::exists(dir / "ran.txt"));
  CHECK(fs::exists(dir / name));
  fs::remove_all(dir);
}

TEST_CASE("a non-finite number in a script is a write error, not gnuplot's 'undefined variable'") {
  CHECK(HasNonFiniteNumber("set xrange [inf:10]\n"));
  CHECK(HasNonFiniteNumber("set yrange [1:-nan]\n"));
  CHECK_FALSE(HasNonFiniteNumber("plot 'a.csv' using 1:(column(2) > 0 ? column(2) : NaN) title 'inf nan'\n"));
  CHECK_FALSE(HasNonFiniteNumber("set format y '%g'; info = 1\n"));
  const fs::path dir = TempDir("nonfinite");
  CHECK_THROWS_WITH_AS(RunGnuplot(FindGnuplot(""), dir.string(), "set xrange [inf:1]\n", "plot x"),
                       doctest::Contains("not finite"), WriteError);
}

}  // namespace deb::report
