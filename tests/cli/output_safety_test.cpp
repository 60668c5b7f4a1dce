// What deb does to the place it writes: a run killed at any moment leaves a
// complete report at the target (the old one or the new one), the next run
// removes what the killed one left, a report set aside by a killed run is
// put back, and nothing deb did not write is replaced without --force.
#include <doctest/doctest.h>
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "tests/support/cli_harness.h"

extern char** environ;

namespace fs = std::filesystem;

namespace {

using deb::test::ExampleBudget;
using deb::test::TempDir;

// Starts deb with `args` (stdout and stderr to /dev/null); its PID.
pid_t Spawn(const std::vector<std::string>& args) {
  std::vector<std::string> all = {DEB_BINARY};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, DEB_BINARY, &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  REQUIRE(rc == 0);
  return pid;
}

int Wait(pid_t pid) {
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
}

int RunDeb(const std::vector<std::string>& args) { return Wait(Spawn(args)); }

// Relative paths of every file under dir, sorted.
std::set<std::string> Files(const fs::path& dir) {
  std::set<std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) out.insert(fs::relative(e.path(), dir).string());
  return out;
}

// Entries beside the target that a run leaves while it works.
std::vector<std::string> Temporaries(const fs::path& parent, const std::string& name) {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(parent)) {
    const std::string n = e.path().filename().string();
    if (n.rfind("." + name + ".tmp-", 0) == 0) out.push_back(n);
  }
  return out;
}

// gnuplot's private directories of the given (killed) processes.
std::vector<std::string> GnuplotLeftovers(const std::set<pid_t>& pids) {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(fs::temp_directory_path())) {
    const std::string n = e.path().filename().string();
    for (pid_t p : pids)
      if (n.rfind("deb-gnuplot-" + std::to_string(p) + "-", 0) == 0) out.push_back(n);
  }
  return out;
}

// The image files in dir (not below it).
std::set<std::string> PlotsIn(const fs::path& dir) {
  std::set<std::string> out;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().extension() == ".png" || e.path().extension() == ".pdf") out.insert(e.path().filename().string());
  return out;
}

// A PID that no process has now: a child that has exited and been reaped.
pid_t DeadPid() {
  const pid_t pid = ::fork();
  if (pid == 0) ::_exit(0);
  ::waitpid(pid, nullptr, 0);
  return pid;
}

}  // namespace

TEST_CASE("SIGKILL at random moments while a report replaces a complete one leaves a complete report") {
  const fs::path dir = TempDir("kill");
  const fs::path target = dir / "rep";
  const std::vector<std::string> args = {"run", ExampleBudget("single_axis_isolator.yaml"), "--out", target.string(),
                                         "--format", "png,pdf", "--threads", "2"};
  const auto t0 = std::chrono::steady_clock::now();
  REQUIRE(RunDeb(args) == 0);
  const double full_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const std::set<std::string> complete = Files(target);
  REQUIRE(complete.count("summary.json") == 1);
  REQUIRE(complete.count("report.pdf") == 1);
  REQUIRE(complete.count(".deb-output") == 1);

  // Moments spread over a whole run, until 22 runs have been killed (runs
  // that finish first count too: they replace the report as well). A run
  // that finishes first shortens the span the moments are drawn from: the
  // first run, timed on a busy machine, may have taken longer than the rest.
  const std::set<std::string> plots_here = PlotsIn(fs::current_path());
  std::mt19937 random(12345);
  constexpr int kKills = 22;
  int killed = 0, finished = 0;
  std::set<pid_t> killed_pids;
  double span_s = full_s;
  for (int k = 0; killed < kKills && k < 3 * kKills; ++k) {
    const auto spawned = std::chrono::steady_clock::now();
    const pid_t pid = Spawn(args);
    std::this_thread::sleep_for(
        std::chrono::duration<double>(std::uniform_real_distribution<double>(0.0, span_s)(random)));
    ::kill(pid, SIGKILL);
    const int status = Wait(pid);
    if (status == -SIGKILL) {
      ++killed;
      killed_pids.insert(pid);
    } else {
      ++finished;
      span_s = std::min(span_s, std::chrono::duration<double>(std::chrono::steady_clock::now() - spawned).count());
    }
    CAPTURE(k);
    CAPTURE(status);
    REQUIRE(fs::is_directory(target));
    CHECK(Files(target) == complete);  // the old report or the new one, never a part
  }
  MESSAGE(killed << " runs killed, " << finished << " finished first (a full run: " << full_s << " s)");
  CHECK(killed == kKills);
  REQUIRE(RunDeb(args) == 0);
  CHECK(Files(target) == complete);
  CHECK(Temporaries(dir, "rep").empty());
  CHECK(PlotsIn(fs::current_path()) == plots_here);  // no gnuplot of a killed run drew here
  CHECK(GnuplotLeftovers(killed_pids).empty());
  fs::remove_all(dir);
}

TEST_CASE("a report that a killed run had set aside comes back; a live run's temporaries are left alone") {
  const fs::path dir = TempDir("recover");
  const fs::path target = dir / "rep";
  REQUIRE(RunDeb({"run", ExampleBudget("single_axis_isolator.yaml"), "--out", target.string(), "--no-plots"}) == 0);
  const std::set<std::string> complete = Files(target);
  // The window of a two-rename replacement: the old report moved aside, the new not yet in place.
  const fs::path aside = dir / (".rep.tmp-" + std::to_string(DeadPid()) + ".old");
  fs::rename(target, aside);
  const fs::path partial = dir / (".rep.tmp-" + std::to_string(DeadPid()));
  fs::create_directory(partial);
  std::ofstream(partial / ".deb-output") << "x";
  const fs::path live = dir / (".rep.tmp-" + std::to_string(DeadPid()));  // looks stale, but holds no marker
  fs::create_directory(live);
  std::ofstream(live / "keep") << "x";
  // A run killed between creating its directory and writing the marker: an empty directory, removed.
  const fs::path empty = dir / (".rep.tmp-" + std::to_string(DeadPid()));
  fs::create_directory(empty);
  // A run that fails while writing (no gnuplot) still cleans up and restores.
  ::setenv("DEB_GNUPLOT", "/nonexistent", 1);
  CHECK(RunDeb({"run", ExampleBudget("single_axis_isolator.yaml"), "--out", target.string()}) == 4);
  ::unsetenv("DEB_GNUPLOT");
  CHECK(Files(target) == complete);
  CHECK(!fs::exists(aside));
  CHECK(!fs::exists(partial));
  CHECK(fs::exists(live / "keep"));  // no marker: not deb's to remove
  CHECK(!fs::exists(empty));
  fs::remove_all(dir);
}

TEST_CASE("only what deb wrote is replaced; --force replaces anything; a symbolic link is written through") {
  const fs::path dir = TempDir("refuse");
  const std::string budget = ExampleBudget("single_axis_isolator.yaml");
  fs::create_directory(dir / "mydata");
  std::ofstream(dir / "mydata" / "thesis.tex") << "years of work";
  std::ofstream(dir / "existing.txt") << "notes";
  CHECK(RunDeb({"run", budget, "--out", (dir / "mydata").string(), "--no-plots"}) == 4);
  CHECK(RunDeb({"run", budget, "--out", (dir / "existing.txt").string(), "--no-plots"}) == 4);
  CHECK(fs::exists(dir / "mydata" / "thesis.tex"));
  CHECK(fs::is_regular_file(dir / "existing.txt"));
  CHECK(Temporaries(dir, "mydata").empty());
  // Another program's summary.json does not make a directory deb's (nor does deb report's redraw).
  std::ofstream(dir / "mydata" / "summary.json") << "{\"score\": 1}";
  CHECK(RunDeb({"run", budget, "--out", (dir / "mydata").string(), "--no-plots"}) == 4);
  CHECK(fs::exists(dir / "mydata" / "thesis.tex"));
  CHECK(Temporaries(dir, "mydata").empty());

  fs::create_directory(dir / "empty");  // an empty directory holds nothing to lose
  CHECK(RunDeb({"run", budget, "--out", (dir / "empty").string(), "--no-plots"}) == 0);
  CHECK(fs::exists(dir / "empty" / "summary.json"));
  CHECK(RunDeb({"run", budget, "--out", (dir / "empty").string(), "--no-plots"}) == 0);  // deb's now

  CHECK(RunDeb({"run", budget, "--out", (dir / "mydata").string(), "--no-plots", "--force"}) == 0);
  CHECK(!fs::exists(dir / "mydata" / "thesis.tex"));
  // A directory holding deb's result.h5 and another program's summary.json: deb report refuses to redraw into it.
  fs::create_directory(dir / "got");
  fs::copy_file(dir / "mydata" / "result.h5", dir / "got" / "result.h5");
  std::ofstream(dir / "got" / "summary.json") << "{}";
  std::ofstream(dir / "got" / "notes.txt") << "mine";
  CHECK(RunDeb({"report", (dir / "got").string(), "--no-plots"}) == 4);
  CHECK(fs::exists(dir / "got" / "notes.txt"));
  CHECK(fs::exists(dir / "mydata" / "summary.json"));

  fs::create_directory(dir / "elsewhere");
  fs::create_directory(dir / "reports");
  fs::create_directory_symlink("../elsewhere", dir / "reports" / "link");
  CHECK(RunDeb({"run", budget, "--out", (dir / "reports" / "link").string(), "--no-plots"}) == 0);
  CHECK(fs::is_symlink(dir / "reports" / "link"));
  CHECK(fs::exists(dir / "elsewhere" / "summary.json"));
  CHECK(RunDeb({"run", budget, "--out", (dir / "reports" / "link").string(), "--no-plots"}) == 0);
  CHECK(fs::is_symlink(dir / "reports" / "link"));
  fs::remove_all(dir);
}

TEST_CASE("with SOURCE_DATE_EPOCH two runs give byte-identical report directories") {
  const fs::path dir = TempDir("reproducible");
  ::setenv("SOURCE_DATE_EPOCH", "1700000000", 1);
  for (const char* out : {"a", "b"})
    REQUIRE(RunDeb({"run", ExampleBudget("single_axis_isolator.yaml"), "--out", (dir / out).string(), "--format",
                    "png,pdf,svg"}) == 0);
  ::unsetenv("SOURCE_DATE_EPOCH");
  const std::set<std::string> files = Files(dir / "a");
  REQUIRE(files == Files(dir / "b"));
  const auto bytes = [](const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  };
  for (const std::string& f : files) {
    CAPTURE(f);
    CHECK(bytes(dir / "a" / f) == bytes(dir / "b" / f));
  }
  // The date of SOURCE_DATE_EPOCH (the PDF date's prefix "D:" is optional; cairo 1.16 omits it).
  const std::string pdf = bytes(dir / "a" / "report.pdf");
  CHECK((pdf.find("/CreationDate (D:20231114221320Z)") != std::string::npos ||
         pdf.find("/CreationDate (20231114221320Z)") != std::string::npos));
  fs::remove_all(dir);
}
