#include "deb/report/gnuplot_runner.h"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <gnuplot-iostream.h>
#include <mutex>
#include <sstream>

#include "deb/core/error.h"
#include "deb/report/plot.h"

namespace deb::report {
namespace fs = std::filesystem;
namespace {

std::string ShellQuote(const std::string& text) {
  std::string q = "'";
  for (char c : text) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

bool IsExecutableFile(const fs::path& p) {
  std::error_code ec;
  return fs::is_regular_file(p, ec) && ::access(p.c_str(), X_OK) == 0;
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
  throw InputError("cannot draw the report's plots: gnuplot executable '" + name + "' (" + origin +
                   ") is not an executable file. Install gnuplot (Debian: gnuplot-nox, see tools/install-deps), "
                   "set " + kGnuplotVariable + " to a gnuplot 5 executable, or write the report without plots (--no-plots)");
}

void RunGnuplot(const std::string& executable, const std::string& dir, const std::string& script,
                const std::string& what) {
  static std::atomic<int> counter{0};
  const fs::path stem = fs::temp_directory_path() / ("deb-gnuplot-" + std::to_string(::getpid()) + "-" +
                                                     std::to_string(counter++));
  const fs::path err_file = stem.string() + ".err", status_file = stem.string() + ".status";
  // The shell records gnuplot's status in a file: pclose() sees only the shell's.
  const std::string command = ShellQuote(executable) + " -d 2>" + ShellQuote(err_file.string()) + "; echo $? >" +
                              ShellQuote(status_file.string());
  bool written = false;
  {
    const IgnoreSigpipe guard;
    try {
      Gnuplot gp(command);
      gp << "cd " << Quote(dir) << "\n" << script << "\n";
      gp.flush();
      written = !gp.fail();
    } catch (const std::exception& e) {
      std::error_code ec;
      fs::remove(err_file, ec);
      fs::remove(status_file, ec);
      throw InputError("cannot draw " + what + ": cannot start gnuplot (" + executable + "): " + e.what());
    }
  }
  const std::string messages = ReadText(err_file), status_text = ReadText(status_file);
  std::error_code ec;
  fs::remove(err_file, ec);
  fs::remove(status_file, ec);
  int status = -1;
  try {
    status = std::stoi(status_text);
  } catch (const std::exception&) {
  }
  if (status != 0 || !written) {
    std::string why = status < 0 ? "did not report an exit status" : "exited with status " + std::to_string(status);
    if (status == 0) why = "stopped reading its commands";
    throw InputError("cannot draw " + what + ": gnuplot (" + executable + ") " + why +
                     (messages.empty() ? std::string() : ":" + Excerpt(messages)));
  }
}

}  // namespace deb::report
