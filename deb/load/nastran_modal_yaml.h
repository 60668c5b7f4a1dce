// Internal: not part of the public API.
// YAML -> a modal model from a Nastran file (deb/formats/nastran_modes.h):
// the keys of a `type: modal` path whose `file` is an OP2, punch or OP4 file.
//   file: FILE                     .op2, .pch or .op4, told apart by content
//   matrices: {phi: P, lambda: L, mass: M}   (OP4 only) the matrices of the
//                                  eigenvectors (a row per DOF, a column per mode),
//                                  the eigenvalues omega^2 and (optional: else the
//                                  modes are mass-normalised) the generalised masses
//   rows: [GRID | GRID:COMP, ...]  (OP4 only) the DOF of each of phi's rows, in
//                                  order: a grid id stands for its 6 rows T1..R3
//   inputs:  [GRID:COMP, ...]      or {name: GRID:COMP, ...}; components T1 T2 T3 R1 R2 R3
//   outputs: [GRID:COMP, ...]      (the list form names each channel by its DOF)
//   modes: {max_hz: F} | {count: N}   which modes (default: all); residual: static as for other modal paths
//   damping: z | [z per mode kept] | {f_hz: [...], zeta: [...]}  (linear in f between the points,
//                                  the end values beyond them)
//   length_unit: U                 the model's length unit (mm, m, in, ...)
//   force_unit: U                  the model's force unit (default N: m-kg-s and mm-t-s)
//   rigid_modes: keep | exclude    modes below kRigidModeHz (default keep: force -> displacement 1/(-w^2 m))
// The eigenvectors are mass-normalised by the file's generalised masses (a
// punch file has none: its eigenvectors are taken as they are). Rotations
// are in rad and moments in force_unit length_unit; the path's input_unit(s)
// and output_unit(s) are converted to from these (ModalFileUnits).
#pragma once

#include <string>
#include <vector>

#include "deb/load/yaml_reader.h"
#include "deb/systems/modal_model.h"

namespace deb::load {

// The keys above that only a Nastran file allows.
extern const char* const kNastranModalKeys[7];

// Below this frequency a mode is a rigid-body mode: the solver's numerical
// zeros of a free structure fall between 1e-5 and 1e-2 Hz.
inline constexpr double kRigidModeHz = 0.01;

// The units a modal model's shapes are in per DOF when its file states them:
// "in", "rad" (outputs), "lbf", "lbf in" (inputs).
struct ModalFileUnits {
  std::vector<std::string> inputs, outputs;
};

// @throws InputError located at the key for every rule: a DOF that is not
//   GRID:COMPONENT, not in the file or given twice, a bad selection or
//   damping, a unit UDUNITS-2 cannot parse, a negative eigenvalue above
//   kRigidModeHz (an unstable model), more than limits::kMaxModes modes
//   kept; and every error of the file's reader, located at `file`.
ModalModel ParseNastranModal(const YamlNode& node, const std::string& path, ModalFileUnits& units);

}  // namespace deb::load
