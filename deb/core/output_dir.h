// The directories deb writes (a run's report, compare/sweep/sensitivity
// results), and the one rule for replacing them: deb replaces only what deb
// wrote. A directory deb writes holds the marker file kOutputMarker; a target
// that is missing, an empty directory, or a directory holding the marker is
// replaced; anything else — a regular file, a directory of someone's files,
// even one holding a file named summary.json — is refused with a WriteError unless the
// caller passes force (the CLI's --force).
//
// The new content is written into a temporary sibling ".NAME.tmp-PID" and
// swapped with the target in one step (renameat2 RENAME_EXCHANGE), so the
// target always holds a complete report, old or new. Where the file system
// cannot exchange, two renames are used and a report left aside by a killed
// run (".NAME.tmp-PID.old") is put back by the next one. Temporaries of dead
// processes beside the target are removed at the start of every write.
// A symbolic link at the target is written through: its target directory is
// replaced and the link stays.
#pragma once

#include <functional>
#include <string>

namespace deb {

inline constexpr const char* kOutputMarker = ".deb-output";

struct ReplaceOptions {
  bool force = false;  // replace a target deb did not write (--force)
};

// Lets fill(tmp_dir) write into a fresh temporary directory, then makes it
// out_dir. If fill throws, the temporary directory (and any parent directory
// this call created) is removed and out_dir is left as it was.
// @throws WriteError if out_dir is not deb's to replace, or cannot be written
//         (with the system's reason); what fill throws, unchanged.
void ReplaceDirectory(const std::string& out_dir, const std::function<void(const std::string&)>& fill,
                      const ReplaceOptions& options = {});

// Temporaries deb names after its PID ("...-PID-...", ".NAME.tmp-PID") are
// removed by a later run only once that process is gone.
// The PID that `text` spells (1 to 10 digits, nothing else), or -1.
long PidOf(const std::string& text);
// True if `pid` is no process now (and not this one): what it left may go.
// A process this user may not signal counts as alive.
bool IsDeadProcess(long pid);

// Writes `text` to `path`: open, write, close, and check each.
// @throws WriteError "cannot write PATH: <reason>" (e.g. No space left on
//   device), the partial file removed if it is a regular file (a device
//   such as /dev/full is left alone).
void WriteTextFile(const std::string& path, const std::string& text);

// Writes the text `produce` hands to its sink, piece by piece, to `path`: a
// large table (an uncertainty study's samples.csv) without holding it whole.
// @throws WriteError as WriteTextFile (the file removed); what produce throws.
using TextSink = std::function<void(const std::string& piece)>;
void WriteTextFileFrom(const std::string& path, const std::function<void(const TextSink&)>& produce);

}  // namespace deb
