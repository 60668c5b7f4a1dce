// Internal: not part of the public API.
// YAML -> a modal model (deb/systems/modal_model.h): the keys of a path entry
// of `type: modal` that describe the modes, each part from a file (numeric
// tables, deb/systems/modal_csv.h) or inline:
//   modes: FILE                  | frequencies_hz: [...] and damping: z | [...]
//   input_shapes: FILE           | input_shapes: {DOF: [value per mode], ...}
//   output_shapes: FILE          | output_shapes: {DOF: [...], ...}
// or all of them from one MATLAB file (deb/formats/mat_file.h) instead:
//   file: MAT-FILE               variables f_hz (vector), zeta (vector or one
//                                value), phi_in (inputs x modes), phi_out
//                                (outputs x modes), optional input_names and
//                                output_names (default u1.., y1..)
//   output_quantity: displacement | velocity | acceleration   (default displacement)
//   max_frequency_hz: F          (optional: keep the modes at or below F)
//   residual: static | none      (with max_frequency_hz: the dropped modes' static compliance as a feedthrough)
// or from a Nastran file (OP2, punch or OP4 matrices:
// deb/load/nastran_modal_yaml.h lists its keys).
// Units are the caller's (path_yaml.cpp): output_unit names the displacement
// unit, and ModalOutputUnit gives the path's output unit from it.
#pragma once

#include <string>

#include "deb/load/nastran_modal_yaml.h"
#include "deb/load/yaml_reader.h"
#include "deb/systems/modal_model.h"

namespace deb::load {

// The keys above (besides the common ones of every path).
extern const char* const kModalKeys[16];

// @throws InputError located at the key (and, for a file, at its
//   file:line:col, or the MAT-file variable and index) for every rule of
//   ModalModel::Validate and modal_csv.h, a shape count other than the mode
//   count, `file` together with another source of modes or shapes, an unknown
//   output_quantity, a max_frequency_hz that leaves no mode.
// `units` gets the units of the shapes when the file states them (a Nastran
// file: deb/load/nastran_modal_yaml.h), for the caller to convert.
ModalModel ParseModalModel(const YamlNode& node, const std::string& base_dir, ModalFileUnits& units);

// The unit of the path's output when `displacement_unit` is differentiated
// for `q`: "um" -> "um" | "um/s" | "um/s^2"; a compound unit is
// parenthesised ("(mm rad)/s").
// @throws InputError if UDUNITS-2 cannot parse displacement_unit or the result.
std::string ModalOutputUnit(const std::string& displacement_unit, ModalQuantity q);

}  // namespace deb::load
