// Runs gnuplot, headless, on a script: the only code in deb that talks to
// gnuplot (through gnuplot-iostream). gnuplot is an external program, so
// its absence and its errors are failures to write the report, reported as
// InputError with gnuplot's own message; the caller writes into a temporary
// directory, so such a failure leaves no half-written report.
#pragma once

#include <string>

namespace deb::report {

// Environment variable that overrides the gnuplot executable.
inline constexpr const char* kGnuplotVariable = "DEB_GNUPLOT";

// The executable to run: `requested` if not empty, else $DEB_GNUPLOT if set
// and not empty, else "gnuplot" found on PATH; as an absolute path.
// @throws InputError naming the executable, where the name came from and
//         how to fix it, if it is not an executable file.
std::string FindGnuplot(const std::string& requested);

// Runs `script` with `executable` (from FindGnuplot) in working directory
// `dir`, without init files (gnuplot -d). `what` names the job in messages,
// e.g. "plot z_velocity_cps".
// @throws InputError with gnuplot's messages if it exits with an error.
void RunGnuplot(const std::string& executable, const std::string& dir, const std::string& script,
                const std::string& what);

}  // namespace deb::report
