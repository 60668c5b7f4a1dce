// The two tables a finite-element modal analysis exports, in deb's numeric
// table format (core/numeric_table.h):
//
//   modes (header required; columns f_hz and zeta, an optional `mode` number
//   that is not read; one row per mode):
//     mode, f_hz, zeta
//     1,    42.0, 0.02
//
//   shapes (header required: a name for the DOF column, then one column per
//   mode, any names, in the order of the mode table; one row per DOF: its name,
//   then the mass-normalised shape value in each mode):
//     dof, mode1, mode2
//     F1,  0.31,  -0.12
//
// Errors quote file:line:column and the rule.
#pragma once

#include <Eigen/Dense>
#include <iosfwd>
#include <string>
#include <vector>

namespace deb {

struct ModeTable {
  std::vector<double> f_hz, zeta;
};

struct ShapeTable {
  std::vector<std::string> dofs;  // one per row
  Eigen::MatrixXd values;         // dofs x modes
};

// @throws InputError for a missing header, a missing, repeated or unknown
//   column, no rows, more than limits::kMaxModes rows, a frequency or
//   damping breaking ModeFrequencyProblem/ModeDampingProblem (modal_model.h).
ModeTable ReadModeTable(const std::string& path);
ModeTable ParseModeTable(std::istream& in, const std::string& name);

// `expected_modes` (>= 0) is the mode count the columns must match, which
// `modes_from` names in the message ("the mode table frame_modes.csv");
// -1 accepts any count.
// @throws InputError for a missing header, a mode count other than expected,
//   more than limits::kMaxModes columns, no rows, more than
//   limits::kMaxChannels rows, an empty or repeated DOF name, a cell that is
//   not a finite number.
ShapeTable ReadShapeTable(const std::string& path, int expected_modes = -1, const std::string& modes_from = "");
ShapeTable ParseShapeTable(std::istream& in, const std::string& name, int expected_modes = -1,
                           const std::string& modes_from = "");

}  // namespace deb
