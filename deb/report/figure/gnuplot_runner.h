// Internal: not part of the public API.
// Runs gnuplot, headless, on a script: the only code in deb that talks to
// gnuplot (started with posix_spawn, no shell between). gnuplot is an external program, so
// its absence, its errors and a run past the time limit are failures to
// write the report, reported as WriteError with gnuplot's own message; the
// caller writes into a temporary directory, so such a failure leaves no
// half-written report. gnuplot's messages go to a private mkdtemp directory.
//
// Every script is checked before it runs (CheckScript): user text reaches
// gnuplot only inside single-quoted strings made by Quote (deb/report/figure/plot.h),
// where gnuplot expands neither `backquotes` nor @macros.
#pragma once

#include <string>

namespace deb::report {

// Environment variable that overrides the gnuplot executable.
inline constexpr const char* kGnuplotVariable = "DEB_GNUPLOT";
// Environment variable with the seconds one gnuplot run may take
// (default limits::kGnuplotTimeoutSeconds); a gnuplot that hangs is stopped.
inline constexpr const char* kGnuplotTimeoutVariable = "DEB_GNUPLOT_TIMEOUT";

// The executable to run: `requested` if not empty, else $DEB_GNUPLOT if set
// and not empty, else "gnuplot" found on PATH; as an absolute path.
// @throws WriteError naming the executable, where the name came from and
//         how to fix it, if it is not an executable file.
std::string FindGnuplot(const std::string& requested);

// Runs `script` with `executable` (from FindGnuplot) in working directory
// `dir`, without init files (gnuplot -d). `what` names the job in messages,
// e.g. "plot z_velocity_cps".
// @throws WriteError with gnuplot's messages if it exits with an error or
//         runs longer than the limit; DEB_DEMAND fails for a script that
//         CheckScript refuses (a bug in deb, not bad input).
void RunGnuplot(const std::string& executable, const std::string& dir, const std::string& script,
                const std::string& what);

// The rule every gnuplot script deb writes obeys, whatever the user's text:
// no backquote (command substitution) and no '@' (macro) outside a
// single-quoted string, no double-quoted string holding either, no 'system'
// or '!' shell escape. Returns the first offence, or "" if there is none.
std::string ScriptOffence(const std::string& script);
// True if `script` holds the word inf or nan outside a string: a number deb
// computed that is not finite (gnuplot would stop at it, "undefined variable").
bool HasNonFiniteNumber(const std::string& script);
// DEB_DEMAND that ScriptOffence(script) is "".
void CheckScript(const std::string& script);
// Every .gp file deb leaves for a reader to replot is written by this: the
// script is checked as RunGnuplot checks what it runs, then written.
// @throws WriteError if the file cannot be written.
void WriteGnuplotScript(const std::string& path, const std::string& script);

}  // namespace deb::report
