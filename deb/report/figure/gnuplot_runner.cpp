#include "deb/report/figure/gnuplot_runner.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <sstream>
#include <thread>

#include "deb/core/error.h"
#include "deb/core/limits.h"
#include "deb/core/output_dir.h"
#include "deb/report/figure/plot.h"

namespace deb::report {
namespace fs = std::filesystem;
namespace {

bool IsExecutableFile(const fs::path& p) {
  std::error_code ec;
  return fs::is_regular_file(p, ec) && ::access(p.c_str(), X_OK) == 0;
}

// Seconds one gnuplot may run: $DEB_GNUPLOT_TIMEOUT if a whole number > 0.
int TimeoutSeconds() {
  const char* env = std::getenv(kGnuplotTimeoutVariable);
  if (!env || !*env) return limits::kGnuplotTimeoutSeconds;
  char* end = nullptr;
  const long v = std::strtol(env, &end, 10);
  if (*end != '\0' || v < 1 || v > 86400)
    throw WriteError(std::string("cannot draw the report's plots: ") + kGnuplotTimeoutVariable + "='" + env +
                     "' is not a whole number of seconds in [1, 86400]");
  return static_cast<int>(v);
}

// Removes the private directories of gnuplot runs whose deb process has
// died (killed while plotting), and files of the older naming
// "deb-gnuplot-PID-N.err|status". Only this user's entries; once per process.
void CleanStaleTemporaries(const fs::path& tmp) {
  static std::once_flag once;
  std::call_once(once, [&] {
    const std::string prefix = "deb-gnuplot-";
    std::error_code ec;
    for (fs::directory_iterator it(tmp, ec), end; !ec && it != end; it.increment(ec)) {
      const std::string name = it->path().filename().string();
      if (name.compare(0, prefix.size(), prefix) != 0) continue;
      const std::size_t dash = name.find('-', prefix.size());
      const long pid = PidOf(name.substr(prefix.size(), dash == std::string::npos ? 0 : dash - prefix.size()));
      if (!IsDeadProcess(pid)) continue;
      struct stat st {};
      if (::lstat(it->path().c_str(), &st) != 0 || st.st_uid != ::getuid()) continue;
      std::error_code ignored;
      fs::remove_all(it->path(), ignored);
    }
  });
}

// A directory only this user can enter, for gnuplot's messages and status.
fs::path PrivateDirectory() {
  const fs::path tmp = fs::temp_directory_path();
  CleanStaleTemporaries(tmp);
  std::string pattern = (tmp / ("deb-gnuplot-" + std::to_string(::getpid()) + "-XXXXXX")).string();
  if (!::mkdtemp(pattern.data()))
    throw WriteError("cannot draw the report's plots: cannot create a temporary directory in " + tmp.string() +
                     ": " + std::strerror(errno));
  return pattern;
}

std::string ReadText(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The first lines of gnuplot's messages, blank lines dropped.
std::string Excerpt(const std::string& text, int max_lines = 8) {
  std::istringstream in(text);
  std::string line, out;
  int lines = 0;
  while (std::getline(in, line)) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    if (lines++ == max_lines) {
      out += "\n  ...";
      break;
    }
    out += "\n  " + line;
  }
  return out;
}

// Writing to a gnuplot that has exited raises SIGPIPE; while any gnuplot
// runs it is ignored, so that the write fails and the exit status tells the
// story. Counted, because several gnuplots may run at once.
class IgnoreSigpipe {
 public:
  IgnoreSigpipe() {
    const std::lock_guard<std::mutex> lock(Mutex());
    if (Count()++ > 0) return;
    struct sigaction ignore {};
    ignore.sa_handler = SIG_IGN;
    sigemptyset(&ignore.sa_mask);
    ::sigaction(SIGPIPE, &ignore, &Previous());
  }
  ~IgnoreSigpipe() {
    const std::lock_guard<std::mutex> lock(Mutex());
    if (--Count() == 0) ::sigaction(SIGPIPE, &Previous(), nullptr);
  }
  IgnoreSigpipe(const IgnoreSigpipe&) = delete;
  IgnoreSigpipe& operator=(const IgnoreSigpipe&) = delete;

 private:
  static std::mutex& Mutex() {
    static std::mutex m;
    return m;
  }
  static int& Count() {
    static int n = 0;
    return n;
  }
  static struct sigaction& Previous() {
    static struct sigaction previous {};
    return previous;
  }
};

}  // namespace

std::string FindGnuplot(const std::string& requested) {
  std::string name = requested, origin = "as requested";
  if (name.empty()) {
    const char* env = std::getenv(kGnuplotVariable);
    if (env && *env) {
      name = env;
      origin = std::string("from ") + kGnuplotVariable;
    } else {
      name = "gnuplot";
      origin = "searched on PATH";
    }
  }
  if (name.find('/') != std::string::npos) {
    if (IsExecutableFile(name)) return fs::absolute(name).string();
  } else if (const char* path = std::getenv("PATH")) {
    std::istringstream dirs(path);
    std::string dir;
    while (std::getline(dirs, dir, ':')) {
      const fs::path candidate = fs::path(dir.empty() ? "." : dir) / name;
      if (IsExecutableFile(candidate)) return fs::absolute(candidate).string();
    }
  }
throw WriteError("cannot draw the report's plots: gnuplot executable '" + name + "' (" + origin +
                   ") is not an executable file. Install gnuplot (Debian: gnuplot-nox, see tools/install-deps), "
                   "set " + kGnuplotVariable + " to a gnuplot 5 executable, or write the report without plots (--no-plots)");
}

namespace {

using Clock = std::chrono::steady_clock;

// Writes all of `text` to the pipe `fd` (non-blocking) before `deadline`.
// False if gnuplot closed its end (it exited: EPIPE, with SIGPIPE ignored)
// or did not read it all in time.
bool WriteAll(int fd, const std::string& text, Clock::time_point deadline) {
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n > 0) {
      done += static_cast<std::size_t>(n);
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && errno != EAGAIN) return false;
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
    if (left <= 0) return false;
    pollfd p{fd, POLLOUT, 0};
    ::poll(&p, 1, static_cast<int>(std::min<long long>(left, 1000)));
  }
  return true;
}

// How gnuplot ended: its exit status (a signal's number + 128), or -1.
struct GnuplotEnd {
  int status = -1;
  bool timed_out = false;
};

// Reaps `pid`; past `deadline` stops it (SIGTERM, SIGKILL 5 s later).
GnuplotEnd WaitFor(pid_t pid, Clock::time_point deadline) {
  GnuplotEnd end;
  auto nap = std::chrono::microseconds(100);
  bool terminated = false;
  for (;;) {
    int wstatus = 0;
    const pid_t r = ::waitpid(pid, &wstatus, WNOHANG);
    if (r == pid) {
      end.status = WIFEXITED(wstatus) ? WEXITSTATUS(wstatus) : WIFSIGNALED(wstatus) ? 128 + WTERMSIG(wstatus) : -1;
      return end;
    }
    if (r < 0 && errno != EINTR) return end;
    const auto now = Clock::now();
    if (now >= deadline) {
      end.timed_out = true;
      ::kill(pid, terminated ? SIGKILL : SIGTERM);
      deadline = now + std::chrono::seconds(terminated ? 3600 : 5);
      terminated = true;
    }
    std::this_thread::sleep_for(nap);
    nap = std::min(nap * 2, std::chrono::microseconds(10000));
  }
}

// Closes a file descriptor when it goes out of scope.
class Descriptor {
 public:
  explicit Descriptor(int fd = -1) : fd_(fd) {}
  ~Descriptor() { Close(); }
  Descriptor(const Descriptor&) = delete;
  Descriptor& operator=(const Descriptor&) = delete;
  int get() const { return fd_; }
  void Close() {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
  }

 private:
  int fd_;
};

}  // namespace

void RunGnuplot(const std::string& executable, const std::string& dir, const std::string& script,
                const std::string& what) {
  CheckScript(script);
  if (HasNonFiniteNumber(script))
    throw WriteError("cannot draw " + what + ": its script holds a number that is not finite (inf or nan); "
                     "the data it would show has no finite axis range");
  const int timeout_s = TimeoutSeconds();
  const fs::path private_dir = PrivateDirectory();
  const fs::path err_file = private_dir / "err";
  const auto remove_private = [&] {
    std::error_code ec;
    fs::remove_all(private_dir, ec);
  };
  // gnuplot is started directly (no shell): `executable -d` (no init
  // files), in `dir` or not at all (a `cd` inside the script would leave it
  // drawing into the caller's directory if `dir` were gone: a run killed
  // while its gnuplots still read their scripts), the script on its
  // standard input, its messages into the private directory, SIGPIPE at
  // its default whatever deb does with it.
  int ends[2];
  if (::pipe2(ends, O_CLOEXEC) != 0) {
    remove_private();
    throw WriteError("cannot draw " + what + ": cannot make a pipe to gnuplot: " + std::strerror(errno));
  }
  Descriptor read_end(ends[0]), write_end(ends[1]);
  posix_spawn_file_actions_t actions;
  posix_spawnattr_t attributes;
  ::posix_spawn_file_actions_init(&actions);
  ::posix_spawnattr_init(&attributes);
  const std::string work_dir = dir.empty() ? "." : dir;
  ::posix_spawn_file_actions_adddup2(&actions, read_end.get(), 0);
  ::posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  ::posix_spawn_file_actions_addopen(&actions, 2, err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  ::posix_spawn_file_actions_addchdir_np(&actions, work_dir.c_str());
  sigset_t defaults, none;
  sigemptyset(&defaults);
  sigaddset(&defaults, SIGPIPE);
  sigemptyset(&none);
  ::posix_spawnattr_setsigdefault(&attributes, &defaults);
  ::posix_spawnattr_setsigmask(&attributes, &none);
  ::posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGDEF | POSIX_SPAWN_SETSIGMASK);
  std::string program = executable, flag = "-d";
  char* argv[] = {program.data(), flag.data(), nullptr};
  pid_t pid = -1;
  const int spawned = ::posix_spawn(&pid, executable.c_str(), &actions, &attributes, argv, environ);
  ::posix_spawn_file_actions_destroy(&actions);
  ::posix_spawnattr_destroy(&attributes);
  read_end.Close();
  if (spawned != 0) {
    remove_private();
    throw WriteError("cannot draw " + what + ": cannot start gnuplot (" + executable + ") in " + work_dir + ": " +
                     std::strerror(spawned));
  }
  const Clock::time_point deadline = Clock::now() + std::chrono::seconds(timeout_s);
  bool written = false;
  {
    const IgnoreSigpipe guard;
    ::fcntl(write_end.get(), F_SETFL, ::fcntl(write_end.get(), F_GETFL) | O_NONBLOCK);
    written = WriteAll(write_end.get(), script + "\n", deadline);
    write_end.Close();
  }
  const GnuplotEnd end = WaitFor(pid, deadline);
  const std::string messages = ReadText(err_file);
  remove_private();
  if (end.status != 0 || end.timed_out || !written) {
    std::string why = end.status < 0 ? "did not report an exit status" : "exited with status " + std::to_string(end.status);
    if (end.status == 0) why = "stopped reading its commands";
    if (end.timed_out)
      why = "did not finish within " + std::to_string(timeout_s) + " s and was stopped (" + kGnuplotTimeoutVariable +
            " sets the limit)";
    throw WriteError("cannot draw " + what + ": gnuplot (" + executable + ") " + why +
                     (messages.empty() ? std::string() : ":" + Excerpt(messages)));
  }
}

}  // namespace deb::report

namespace deb::report {

namespace {

// Words after which gnuplot reads a string as a file name, where a leading
// '|' or '<' is a pipe to a shell or a command to read from.
bool TakesFileName(const std::string& word) {
  for (const char* w : {"output", "load", "call", "save", "cd", "print", "table", "plot", "splot", "replot"})
    if (word == w) return true;
  return false;
}

}  // namespace

std::string ScriptOffence(const std::string& script) {
  bool command_start = true;  // at the start of a command: '!' would run a shell
  std::string command;        // the command's first word
  std::string word;           // the last bare word
  std::string current;        // the bare word being read
  char last = ' ';            // the last character outside strings and blanks
  int parentheses = 0;
  // A string at a file name's place: after a word that takes one, or after a
  // comma between the data sources of a plot.
  const auto at_file_name = [&] {
    return TakesFileName(word) || (last == ',' && parentheses == 0 && (command == "plot" || command == "splot"));
  };
  for (std::size_t i = 0; i < script.size(); ++i) {
    const char c = script[i];
    if (std::isalnum(static_cast<unsigned char>(c)) || c == '_') {
      current += c;
    } else if (!current.empty()) {
      word = current;
      if (command.empty()) command = word;
      current.clear();
    }
    if (c == '\'' || c == '"') {
      const char first = i + 1 < script.size() ? script[i + 1] : '\0';
      if ((first == '|' || first == '<') && at_file_name())
        return std::string("a file name starting with '") + first + "' (a pipe)";
    }
    if (c == '\'') {  // single-quoted: nothing is expanded; '' stands for '
      for (++i; i < script.size(); ++i) {
        if (script[i] == '\n') return "a line break inside a single-quoted string";
        if (script[i] != '\'') continue;
        if (i + 1 < script.size() && script[i + 1] == '\'') {
          ++i;
          continue;
        }
        break;
      }
      if (i >= script.size()) return "an unterminated single-quoted string";
      command_start = false;
      word.clear();
      last = '\'';
      continue;
    }
    if (c == '"') {  // double-quoted: gnuplot expands `...` here
      for (++i; i < script.size() && script[i] != '"'; ++i) {
        if (script[i] == '\\') ++i;
        else if (script[i] == '`') return "a backquote inside a double-quoted string";
        else if (script[i] == '\n') return "a line break inside a double-quoted string";
      }
      if (i >= script.size()) return "an unterminated double-quoted string";
      command_start = false;
      word.clear();
      last = '"';
      continue;
    }
    if (c == '`') return "a backquote outside a single-quoted string";
    if (c == '@') return "an '@' (macro) outside a single-quoted string";
    if (c == '!' && command_start) return "a '!' shell command";
    if (script.compare(i, 6, "system") == 0) return "a call of system";
    if (c == '(') ++parentheses;
    if (c == ')' && parentheses > 0) --parentheses;
    if (c == '\n' || c == ';') {
      command_start = true;
      command.clear();
      word.clear();
      parentheses = 0;
    } else if (c != ' ' && c != '\t') {
      command_start = false;
    }
    if (c != ' ' && c != '\t') last = c;
  }
  return "";
}

bool HasNonFiniteNumber(const std::string& script) {
  std::string word;
  bool quoted = false;
  char quote = 0;
  for (std::size_t i = 0; i <= script.size(); ++i) {
    const char c = i < script.size() ? script[i] : '\n';
    if (quoted) {
      if (c == '\\' && quote == '"') ++i;
      else if (c == quote) quoted = false;
      continue;
    }
    if (std::isalnum(static_cast<unsigned char>(c)) || c == '_') {
      word += c;
      continue;
    }
    if (word == "inf" || word == "nan") return true;
    word.clear();
    if (c == '\'' || c == '"') {
      quoted = true;
      quote = c;
    }
  }
  return false;
}

void WriteGnuplotScript(const std::string& path, const std::string& script) {
  CheckScript(script);
  if (HasNonFiniteNumber(script))
    throw WriteError("cannot write " + path + ": the plot's script holds a number that is not finite (inf or nan)");
  WriteTextFile(path, script);
}

void CheckScript(const std::string& script) {
  const std::string offence = ScriptOffence(script);
  if (!offence.empty()) {
    std::fprintf(stderr, "deb: internal error: a gnuplot script holds %s\n", offence.c_str());
    DEB_DEMAND(offence.empty());
  }
}

}  // namespace deb::report
