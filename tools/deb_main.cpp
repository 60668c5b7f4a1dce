// deb: the command-line front end. Thin: parses arguments, calls the library,
// maps failures to documented exit codes, for every subcommand in one place
// (RunMapped below):
//
//   code  meaning                                   raised as
//   0     success
//   2     usage: unknown command or option, a      CLI11's ParseError, an
//         missing or malformed argument            unknown subcommand
//   3     invalid input: budget, data file, model,  deb::InputError, printed
//         parameters                                 "file:line:col: key.path: rule"
//   4     cannot write the output (report, CSV,     deb::WriteError
//         plots), gnuplot missing or failing
//   5     a requirement failed (run --strict; the   RunCommand's return value
//         report is written), or no design met      (kExitRequirement), also
//         every requirement (optimise)              OptimiseCommand's
//   6     compared figures moved beyond            deb::tools::FiguresMoved
//         compare --tolerance (reports written)
//   70    internal error (a bug)                    any other exception
#include <CLI/CLI.hpp>

#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include "deb/core/error.h"
#include "deb/core/input_file.h"
#include "deb/core/process_heap.h"
#include "deb/core/suggest.h"
#include "deb/systems/lapack.h"
#include "deb/version.h"
#include "tools/check_command.h"
#include "tools/compare_command.h"
#include "tools/model_command.h"
#include "tools/report_command.h"
#include "tools/run_command.h"
#include "tools/sensitivity_command.h"
#include "tools/spectrum_command.h"
#include "tools/sweep_command.h"
#include "tools/uncertainty_command.h"
#ifdef DEB_MPI
#include "deb/distributed/mpi_queue.h"
#endif
#include "tools/merge_command.h"
#include "tools/optimise_command.h"

namespace {

constexpr int kExitUsage = 2;
constexpr int kExitInput = 3;
constexpr int kExitWrite = 4;
constexpr int kExitMoved = 6;
constexpr int kExitInternal = 70;

// A command line that names no command deb has (CLI11 reports the rest).
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Parses the command line and runs the subcommand: its return value, or the
// exit code of what was thrown (the table above), the error printed as
// "deb: error: ..." (CLI11 prints its own usage errors, and --help).
template <typename F>
int RunMapped(CLI::App& app, F&& parse_and_run) {
  try {
    return parse_and_run();
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : kExitUsage;
  } catch (const UsageError& e) {
    std::fprintf(stderr, "deb: %s\n", e.what());
    return kExitUsage;
  } catch (const deb::InputError& e) {
    std::fprintf(stderr, "deb: error: %s\n", e.what());
    return kExitInput;
  } catch (const deb::WriteError& e) {
    std::fprintf(stderr, "deb: error: %s\n", e.what());
    return kExitWrite;
  } catch (const deb::tools::FiguresMoved& e) {
    std::fprintf(stderr, "deb: %s\n", e.what());
    return kExitMoved;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "deb: internal error: %s\n", e.what());
    return kExitInternal;
  } catch (...) {
    std::fprintf(stderr, "deb: internal error: an unknown exception\n");
    return kExitInternal;
  }
}

// Where OpenBLAS picked kernels older than the processor runs
// (deb::BetterBlasKernel), deb starts itself again with OPENBLAS_CORETYPE
// set, the only way to choose them: OpenBLAS reads it once, when it is
// loaded. The same program and arguments, before anything else has run (no
// thread, no MPI); the variable being set, the second start goes on. If the
// restart fails, this one goes on with OpenBLAS's kernels.
void RestartForBlasKernel(char** argv) {
  const std::optional<std::string> kernel = deb::BetterBlasKernel();
  if (!kernel) return;
  if (setenv("OPENBLAS_CORETYPE", kernel->c_str(), 1) != 0) return;
  execv("/proc/self/exe", argv);
  unsetenv("OPENBLAS_CORETYPE");  // still here: the restart failed
}

}  // namespace

int main(int argc, char** argv) {
  RestartForBlasKernel(argv);
  deb::UseOneBlasThreadPerCall();
  deb::KeepHeapForLargeBlocks();
#ifdef DEB_MPI
  // Started by mpirun: one MPI session for the run, ended at exit.
  const deb::MpiSession mpi(&argc, &argv);
#endif
  // A file-size limit (ulimit -f) makes a write fail (EFBIG): reported as a
  // write error, exit 4, with nothing left behind, instead of death by
  // SIGXFSZ halfway through a report.
  std::signal(SIGXFSZ, SIG_IGN);
  CLI::App app{"deb: frequency-domain dynamic error budgeting for precision machines"};
  const std::string blas = deb::BlasKernel();
  app.set_version_flag("--version", std::string("deb ") + DEB_VERSION +
                                        (blas.empty() ? std::string() : "\nBLAS: OpenBLAS, " + blas + " kernels"));
  app.require_subcommand(1);
  app.footer(
      "Exit codes: 0 success, 2 usage error, 3 invalid input (budget, data file, model), "
      "4 cannot write the report, 5 a requirement failed (run --strict) or no design met every requirement "
      "(optimise), 6 compared figures moved "
      "(compare --tolerance), 70 internal error.");

  // Registered in the order of `deb --help`.
  deb::tools::RunCommand run_command;
  CLI::App* run = run_command.Register(app);
  deb::tools::CheckCommand check_command;
  CLI::App* check = check_command.Register(app);
  deb::tools::ModelCommand model_command;
  CLI::App* model = model_command.Register(app);
  deb::tools::SpectrumCommand spectrum_command;
  CLI::App* spectrum = spectrum_command.Register(app);
  deb::tools::CompareCommand compare_command;
  CLI::App* compare = compare_command.Register(app);
  deb::tools::ReportCommand report_command;
  CLI::App* redraw = report_command.Register(app);
  deb::tools::SweepCommand sweep_command;
  CLI::App* sweep = sweep_command.Register(app);
  deb::tools::SensitivityCommand sensitivity_command;
  CLI::App* sensitivity = sensitivity_command.Register(app);
  deb::tools::UncertaintyCommand uncertainty_command;
  CLI::App* uncertainty = uncertainty_command.Register(app);
  deb::tools::OptimiseCommand optimise_command;
  CLI::App* optimise = optimise_command.Register(app);
  deb::tools::MergeCommand merge_command;
  CLI::App* merge = merge_command.Register(app);

  return RunMapped(app, [&] {
    // A first word that is no command: say so, and offer the nearest one
    // (CLI11 alone answers "A subcommand is required").
    if (argc > 1 && argv[1][0] != '-') {
      std::vector<std::string> names;
      std::string list;
      for (const CLI::App* sub : app.get_subcommands({})) {
        names.push_back(sub->get_name());
        list += (list.empty() ? "" : ", ") + sub->get_name();
      }
      if (std::find(names.begin(), names.end(), argv[1]) == names.end()) {
        const std::string near = deb::NearestName(argv[1], names);
        throw UsageError("unknown command '" + deb::Excerpt(argv[1]) + "'" +
                         (near.empty() ? "" : " (did you mean '" + near + "'?)") + "; the commands are " + list +
                         " (deb --help)");
      }
    }
    app.parse(argc, argv);
    if (*run) return run_command.Run();
    if (*check) return check_command.Run();
    if (*model) return model_command.Run();
    if (*spectrum) return spectrum_command.Run();
    if (*redraw) return report_command.Run();
    if (*compare) return compare_command.Run();
    if (*sweep) return sweep_command.Run();
    if (*sensitivity) return sensitivity_command.Run();
    if (*uncertainty) return uncertainty_command.Run();
    if (*optimise) return optimise_command.Run();
    if (*merge) return merge_command.Run();
    return kExitUsage;
  });
}
