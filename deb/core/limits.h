// The bounds deb puts on every size that input can ask for, so that a typo or
// a hostile file ends in a located error instead of exhausting memory or time.
// Each is far above what a real budget needs; docs/cli.md lists them.
#pragma once

#include <cstddef>
#include <cstdint>

namespace deb::limits {

// Frequencies of one grid (any type: auto, log, linear, explicit).
inline constexpr std::size_t kMaxGridPoints = 5'000'000;
// Density settings of the automatic grid (points per decade, per resonance).
inline constexpr double kMaxPointsPerDecade = 100'000;
inline constexpr double kMaxPointsPerResonance = 100'000;
// Frequencies a grid may reach, in Hz: beyond them (2 pi f)^2 and the powers
// of s in a transfer function leave the range of a double.
inline constexpr double kMinGridHz = 1e-12;
inline constexpr double kMaxGridHz = 1e15;
// Norm of a path's state matrix after balancing, in rad/s: beyond it the
// squared distances of a frequency response and eps |A|, the uncertainty of
// its poles, leave the range of a double (poles at 1e150 rad/s made every
// frequency "coincide with a pole").
inline constexpr double kMaxStateMatrixNorm = 1e100;
// Channels of one source, inputs or outputs of one path.
inline constexpr int kMaxChannels = 10'000;
// Modes of one modal path (type: modal), evaluated in modal form (memory
// and time linear in the modes; the exact covariance is O(modes^2)).
inline constexpr int kMaxModes = 5'000;
// States of a dense realisation deb forms from a modal path (joined with
// other paths, or under an output weighting for its exact variance): the
// O(n^3) reductions of 2000 states take seconds, beyond that minutes.
inline constexpr int kMaxDenseStates = 2'000;
// States of a diagram beyond kMaxDenseStates, kept as its parts (a loop
// around a large modal plant: its modes' 2x2 blocks, the controller's few
// states and a low-rank coupling): its poles and exact variance cost
// O(n^2 (m + p + r)) time and O(n (m + p + r)) memory
// (deb/systems/coupled_spectrum.h). A loop around the largest modal path
// (kMaxModes) fits: a PID loop around 5000 modes (10 004 states, 20 x 20)
// took 22 s and 464 MB, around 3000 modes 9.2 s and 367 MB.
inline constexpr int kMaxCoupledStates = 12'000;
// States of a state_space path, or a transfer function's realisation
// (the order of its denominator), checked from the sizes given before any
// O(n^3) work: a dense model's frequency response, poles and exact
// variance. On the block-diagonal form (deb/systems/real_block_diagonal.h)
// a rotated finite-element model of 2000 states runs in about 20 s
// (bench/bench_dense --fe 1000); before it, 2000 states took 36 minutes.
inline constexpr int kMaxStates = 2'000;
// Values of one variable of a MATLAB .mat file (deb/formats/mat_file.h), or
// of one matrix of a Nastran .op4 file (deb/formats/op4_file.h), checked
// from its header before its data is read: a mode-shape matrix of the most
// modes at the most channels (400 MB of doubles).
inline constexpr std::size_t kMaxMatElements =
    static_cast<std::size_t>(kMaxModes) * static_cast<std::size_t>(kMaxChannels);
// Lines of one tonal source.
inline constexpr std::size_t kMaxTones = 10'000;
// Variants of one sweep, values of one swept parameter.
inline constexpr std::size_t kMaxSweepVariants = 100'000;
// YAML nodes a sweep key path with [*] may visit (aliases can make a short
// file name a huge tree).
inline constexpr std::size_t kMaxKeyPathVisits = 1'000'000;
// `--set KEY.PATH=VALUE` options on one command line.
inline constexpr std::size_t kMaxOverrides = 1000;
// Files read on the user's behalf.
inline constexpr std::uintmax_t kMaxBudgetFileBytes = 64ull << 20;  // 64 MiB
inline constexpr std::uintmax_t kMaxTextFileBytes = 1ull << 30;     // 1 GiB: spectra, FRF, CSV recordings, summaries
inline constexpr std::uintmax_t kMaxRawFileBytes = 8ull << 30;      // 8 GiB: raw binary recordings
inline constexpr std::uintmax_t kMaxMatFileBytes = 2ull << 30;      // 2 GiB: MATLAB .mat files (models, FE results)
// Nastran result files (OP2, punch): read as a stream, keeping only the
// eigenvalues and the named grids' rows, so a large model's file costs a pass,
// not its size in memory.
inline constexpr std::uintmax_t kMaxSolverFileBytes = 64ull << 30;  // 64 GiB
inline constexpr std::size_t kMaxMatVariables = 100'000;            // variables of one .mat file
inline constexpr std::uintmax_t kMaxOp4FileBytes = 2ull << 30;      // 2 GiB: Nastran OUTPUT4 (.op4) files
inline constexpr std::size_t kMaxOp4Matrices = 100'000;             // matrices of one .op4 file
inline constexpr std::size_t kMaxLineBytes = 4u << 20;              // 4 MiB: one line of a text table
// Datasets of one universal file (deb/formats/uff58_file.h), and the points
// of all its datasets 58 together (as complex values with their abscissae,
// 1.2 GB in memory; a test of 1000 FRFs of 6400 lines has 6.4 million).
inline constexpr std::size_t kMaxUffDatasets = 100'000;
inline constexpr std::size_t kMaxUffFilePoints = 50'000'000;
// Seconds one gnuplot run may take before it is stopped (DEB_GNUPLOT_TIMEOUT overrides).
inline constexpr int kGnuplotTimeoutSeconds = 300;

}  // namespace deb::limits
