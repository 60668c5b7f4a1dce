// deb as a C++ library: every public header. An application links the CMake
// target deb::deb (find_package(deb CONFIG REQUIRED)) and includes this file,
// or only the headers it needs; each stands on its own.
//
// Public: the headers included below, and deb/version.h. They expose std and
// Eigen types only, whatever deb links (yaml-cpp, FFTW, UDUNITS-2, LAPACK,
// matio, gnuplot, Nettle stay inside the libraries).
// Internal: a header whose first line is
//   // Internal: not part of the public API.
// It may change or go without notice and is not installed. No public header
// includes an internal one; deb/CMakeLists.txt checks that this list names
// every public header.
#pragma once

#include "deb/version.h"

// Errors (InputError, WriteError), names of enums, frequency grids, integration, the size
// limits on input, the rule for replacing output directories.
#include "deb/core/enum_names.h"
#include "deb/core/error.h"
#include "deb/core/extrapolation.h"
#include "deb/core/frequency_grid.h"
#include "deb/core/frequency_interval.h"
#include "deb/core/integrate.h"
#include "deb/core/key_positions.h"
#include "deb/core/limits.h"
#include "deb/core/output_dir.h"
#include "deb/core/rounding_zero.h"
#include "deb/core/study_shard.h"

#include "deb/units/dimension.h"
#include "deb/units/quantity.h"
#include "deb/units/unit.h"

// Named parameters and expressions with units.
#include "deb/parameters/expression.h"
#include "deb/parameters/parameter_set.h"

// Sources: S_u(f) of flat, VC, measured, multi-channel spectra.
#include "deb/spectra/band_rms.h"
#include "deb/spectra/building_criteria.h"
#include "deb/spectra/channel_set.h"
#include "deb/spectra/converted_spectrum.h"
#include "deb/spectra/flat_spectrum.h"
#include "deb/spectra/measured_spectrum.h"
#include "deb/spectra/peterson_noise_model.h"
#include "deb/spectra/scaled_spectrum.h"
#include "deb/spectra/spectrum.h"
#include "deb/spectra/band_table.h"
#include "deb/spectra/spectrum_csv.h"
#include "deb/spectra/tabulated_csd.h"
#include "deb/spectra/third_octave.h"
#include "deb/spectra/tone_spectrum.h"
#include "deb/spectra/vc_curve.h"

// Recordings and spectral estimates from them.
#include "deb/signal/chi_square.h"
#include "deb/signal/frf_estimate.h"
#include "deb/signal/recording.h"
#include "deb/signal/self_noise.h"
#include "deb/signal/spectral_estimate.h"
#include "deb/signal/time_series.h"
#include "deb/signal/time_series_file.h"
#include "deb/signal/welch.h"
#include "deb/signal/window.h"

// Paths: state space, transfer functions, modal and measured models.
#include "deb/systems/axis_cancellation.h"
#include "deb/systems/frequency_model.h"
#include "deb/systems/control_blocks.h"
#include "deb/systems/frequency_response.h"
#include "deb/systems/frf_csv.h"
#include "deb/systems/irrational_block.h"
#include "deb/systems/interconnect.h"
#include "deb/systems/loop_margins.h"
#include "deb/systems/lyapunov.h"
#include "deb/systems/measured_response.h"
#include "deb/systems/modal_csv.h"
#include "deb/systems/modal_model.h"
#include "deb/systems/modes.h"
#include "deb/systems/state_space.h"
#include "deb/systems/transfer_function.h"

#include "deb/models/isolation_model.h"
#include "deb/models/isolation_system.h"
#include "deb/models/lumped_masses.h"

// A budget, its evaluation (Evaluate, BudgetResult) and what is built on it.
#include "deb/budget/allocation.h"
#include "deb/budget/budget.h"
#include "deb/budget/budget_outline.h"
#include "deb/budget/comparison.h"
#include "deb/budget/engine.h"
#include "deb/budget/failure_guidance.h"
#include "deb/budget/groups.h"
#include "deb/budget/isolation_paths.h"
#include "deb/budget/loop_analysis.h"
#include "deb/budget/output_covariance.h"
#include "deb/budget/output_metric.h"
#include "deb/budget/path.h"
#include "deb/budget/path_analysis.h"
#include "deb/budget/path_composition.h"
#include "deb/budget/result.h"
#include "deb/budget/sensitivity.h"
#include "deb/budget/source.h"
#include "deb/budget/sweep.h"
#include "deb/budget/sweep_ranking.h"

// Uncertainty studies: parameters' distributions, sample designs, statistics.
#include "deb/uncertainty/distribution.h"
#include "deb/uncertainty/sample_design.h"
#include "deb/uncertainty/sample_statistics.h"
#include "deb/uncertainty/uncertainty_study.h"

// Design optimisation: parameters within bounds chosen by NLopt.
#include "deb/optimise/optimiser.h"

// Budget files in (LoadBudgetFile), result directories out
// (WriteResultDirectory: summary.json and a CSV per output).
#include "deb/load/budget_yaml.h"
#include "deb/results/comparison_files.h"
#include "deb/formats/mat_file.h"
#include "deb/formats/nastran_modes.h"
#include "deb/formats/uff58_file.h"
#include "deb/formats/op4_file.h"
#include "deb/results/result_exports.h"
#include "deb/results/result_mat.h"
#include "deb/results/result_writer.h"
#include "deb/results/result_xlsx.h"
#include "deb/results/study_part.h"
#include "deb/results/uncertainty_files.h"
#include "deb/results/optimise_files.h"
#include "deb/load/uncertainty_yaml.h"
#include "deb/load/optimise_yaml.h"
#include "deb/load/sweep_yaml.h"

// The report of `deb run` (WriteReportDirectory; gnuplot draws the plots).
#include "deb/report/budget/report_writer.h"
#include "deb/report/figure/report_options.h"
