// Internal: not part of the public API.
// --timeout of the studies that mpirun spreads over ranks (deb sweep,
// uncertainty, optimise): how long a rank may hold its work before rank 0
// ends the run (DistributeBlocks).
#pragma once

#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdlib>
#include <string>

namespace deb::tools {

// `held` says what a rank holds: "a block of variants", "one start".
inline CLI::Option* AddMpiTimeoutOption(CLI::App* app, double* seconds, const std::string& held) {
  return app
      ->add_option("--timeout", *seconds,
                   "Under mpirun: end the run when a rank holds " + held +
                       " longer than this many seconds (default 0: no limit)")
      ->check(CLI::Validator(
          [](std::string& text) -> std::string {
            char* end = nullptr;
            const double s = std::strtod(text.c_str(), &end);
            if (text.empty() || end == nullptr || *end != '\0' || !std::isfinite(s) || s < 0.0)
              return "'" + text + "': give seconds, a finite number >= 0 (0: no limit)";
            return "";
          },
          "SECONDS"));
}

}  // namespace deb::tools
