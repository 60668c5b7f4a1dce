#include "deb/core/output_dir.h"

#include <fcntl.h>
#include <signal.h>
#include <stdio.h>  // renameat2 (glibc >= 2.28)
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <vector>

#include "deb/core/error.h"

namespace deb {
namespace fs = std::filesystem;
namespace {

std::string Reason(int error) { return std::strerror(error); }

[[noreturn]] void Fail(const std::string& what, const std::error_code& ec) {
  throw WriteError(what + ": " + ec.message());
}

// Only the marker makes a directory deb's: a summary.json is a common name,
// and another program's would make its directory deb's to replace.
bool HasMarker(const fs::path& dir) {
  std::error_code ec;
  return fs::is_regular_file(dir / kOutputMarker, ec);
}

bool IsEmptyDirectory(const fs::path& dir) {
  std::error_code ec;
  return fs::is_directory(dir, ec) && fs::is_empty(dir, ec);
}

// ".NAME.tmp-PID" or ".NAME.tmp-PID.old" beside the target: the PID, else -1.
long TemporaryPid(const std::string& entry, const std::string& prefix, bool* old) {
  if (entry.compare(0, prefix.size(), prefix) != 0) return -1;
  std::string rest = entry.substr(prefix.size());
  *old = rest.size() > 4 && rest.compare(rest.size() - 4, 4, ".old") == 0;
  if (*old) rest.resize(rest.size() - 4);
  return PidOf(rest);
}

// Removes what killed runs left beside `target`; puts back a report that a
// killed two-rename replacement had moved aside while the target is missing.
void CleanStaleTemporaries(const fs::path& parent, const fs::path& target) {
  const std::string prefix = "." + target.filename().string() + ".tmp-";
  std::error_code ec;
  std::vector<fs::path> stale_old, stale_new;
  for (fs::directory_iterator it(parent, ec), end; !ec && it != end; it.increment(ec)) {
    bool old = false;
    const long pid = TemporaryPid(it->path().filename().string(), prefix, &old);
    if (!IsDeadProcess(pid)) continue;
    if (!it->is_directory(ec) || it->is_symlink(ec)) continue;
    // Only what deb wrote: a marked directory, or an empty one (a run killed
    // between creating its directory and writing the marker into it).
    if (!HasMarker(it->path()) && (old || !IsEmptyDirectory(it->path()))) continue;
    (old ? stale_old : stale_new).push_back(it->path());
  }
  for (const fs::path& p : stale_old) {
    if (!fs::exists(fs::symlink_status(target, ec))) fs::rename(p, target, ec);  // the old report comes back
    if (fs::exists(p, ec)) fs::remove_all(p, ec);
  }
  for (const fs::path& p : stale_new) fs::remove_all(p, ec);
}

// Swaps two paths in one step. False (errno set) where the file system or
// kernel cannot exchange.
bool Exchange(const fs::path& a, const fs::path& b) {
#ifdef RENAME_EXCHANGE
  return ::renameat2(AT_FDCWD, a.c_str(), AT_FDCWD, b.c_str(), RENAME_EXCHANGE) == 0;
#else
  (void)a;
  (void)b;
  errno = ENOSYS;
  return false;
#endif
}

// The directories create_directories(dir) would create, outermost first.
std::vector<fs::path> MissingAncestors(fs::path dir) {
  std::vector<fs::path> missing;
  std::error_code ec;
  while (!dir.empty() && !fs::exists(fs::symlink_status(dir, ec))) {
    missing.insert(missing.begin(), dir);
    if (dir == dir.parent_path()) break;
    dir = dir.parent_path();
  }
  return missing;
}

// The directory that out_dir names: a symbolic link is followed to its target.
fs::path ResolveTarget(const std::string& out_dir) {
  fs::path target = fs::absolute(out_dir).lexically_normal();
  if (target.filename().empty()) target = target.parent_path();  // "reports/x/" -> "reports/x"
  std::error_code ec;
  for (int hops = 0; fs::is_symlink(target, ec); ++hops) {
    if (hops == 40) throw WriteError("cannot write " + out_dir + ": too many levels of symbolic links");
    const fs::path link = fs::read_symlink(target, ec);
    if (ec) Fail("cannot follow the symbolic link " + target.string(), ec);
    target = (link.is_absolute() ? link : target.parent_path() / link).lexically_normal();
  }
  if (target == target.root_path() || target.filename() == "." || target.filename() == "..")
    throw WriteError("cannot write the output at " + target.string() + ": it is not a directory deb can replace");
  return target;
}

}  // namespace

long PidOf(const std::string& text) {
  if (text.empty() || text.size() > 10 || text.find_first_not_of("0123456789") != std::string::npos) return -1;
  return std::stol(text);
}

bool IsDeadProcess(long pid) {
  return pid > 0 && pid != ::getpid() && ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH;
}

namespace {

// What a failed write leaves: the partial file, if it is one (never a
// device or anything else the path may name, such as /dev/full).
void RemovePartialFile(const std::string& path) {
  std::error_code ec;
  if (fs::is_regular_file(fs::symlink_status(path, ec))) fs::remove(path, ec);
}

}  // namespace

void WriteTextFileFrom(const std::string& path, const std::function<void(const TextSink&)>& produce) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) throw WriteError("cannot write " + path + ": " + Reason(errno));
  int write_error = 0;
  try {
    produce([&](const std::string& piece) {
      if (write_error == 0 && std::fwrite(piece.data(), 1, piece.size(), f) != piece.size()) write_error = errno;
    });
  } catch (...) {
    std::fclose(f);
    RemovePartialFile(path);
    throw;
  }
  const int close_error = std::fclose(f) == 0 ? 0 : errno;
  if (write_error || close_error) {
    RemovePartialFile(path);
    throw WriteError("cannot write " + path + ": " + Reason(write_error ? write_error : close_error));
  }
}

void WriteTextFile(const std::string& path, const std::string& text) {
  WriteTextFileFrom(path, [&text](const TextSink& put) { put(text); });
}

void ReplaceDirectory(const std::string& out_dir, const std::function<void(const std::string&)>& fill,
                      const ReplaceOptions& options) {
  const fs::path target = ResolveTarget(out_dir);
  const fs::path parent = target.parent_path();
  std::error_code ec;
  const fs::file_status status = fs::symlink_status(target, ec);
  const bool exists = fs::exists(status);
  if (exists && !options.force) {
    if (!fs::is_directory(status))
      throw WriteError("refusing to replace " + target.string() + ": it is " +
                       (fs::is_regular_file(status) ? "a regular file" : "not a directory") +
                       ", not a report written by deb; choose another --out, or pass --force to replace it");
    if (!HasMarker(target) && !IsEmptyDirectory(target))
      throw WriteError("refusing to replace " + target.string() +
                       ": it is a directory deb did not write (it has no " + kOutputMarker +
                       " file); choose another --out, or pass --force to replace it and everything in it");
  }
  const std::vector<fs::path> created = MissingAncestors(parent);
  const auto remove_created = [&] {
    std::error_code ignored;
    for (auto it = created.rbegin(); it != created.rend(); ++it) fs::remove(*it, ignored);  // only if empty
  };
  fs::create_directories(parent, ec);
  if (ec) Fail("cannot create directory " + parent.string(), ec);
  CleanStaleTemporaries(parent, target);

  const std::string stem = "." + target.filename().string() + ".tmp-" + std::to_string(::getpid());
  const fs::path tmp = parent / stem, old = parent / (stem + ".old");
  fs::remove_all(tmp, ec);
  if (!fs::create_directory(tmp, ec) || ec) {
    const std::error_code why = ec;
    remove_created();
    Fail("cannot create directory " + tmp.string(), why);
  }
  try {
    WriteTextFile((tmp / kOutputMarker).string(), "written by deb; deb replaces this directory on its next run\n");
    fill(tmp.string());
  } catch (...) {
    fs::remove_all(tmp, ec);
    remove_created();
    throw;
  }
  const bool target_exists = fs::exists(fs::symlink_status(target, ec));
  if (target_exists && Exchange(tmp, target)) {
    fs::remove_all(tmp, ec);  // now the previous content
    return;
  }
  if (target_exists) {
    // No exchange on this file system: move the old content aside first. A
    // kill between the renames leaves it in `old`, which the next run restores.
    if (::rename(target.c_str(), old.c_str()) != 0) {
      const int why = errno;
      fs::remove_all(tmp, ec);
      throw WriteError("cannot replace " + target.string() + ": " + Reason(why));
    }
  }
  if (::rename(tmp.c_str(), target.c_str()) != 0) {
    const int why = errno;
    if (target_exists) ::rename(old.c_str(), target.c_str());
    fs::remove_all(tmp, ec);
    remove_created();
    throw WriteError("cannot move the output into " + target.string() + ": " + Reason(why));
  }
  if (target_exists) fs::remove_all(old, ec);
}

}  // namespace deb
