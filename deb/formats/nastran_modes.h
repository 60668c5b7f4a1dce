// Real normal modes from Nastran result files (SOL 103), for modal paths:
// the eigenvalue table and the eigenvectors at the grid components a budget
// names, as the solver wrote them (not normalised: see generalized_mass).
//
// Two formats, told apart by content, not by the file's name:
//  - OP2 (PARAM,POST,-1 or -2): Fortran unformatted records, either byte
//    order, 32- or 64-bit words. Its data blocks are found by name wherever
//    they are: LAMA (mode number, eigenvalue, rad/s, cycles, generalised
//    mass and stiffness per mode) and OUGV1 (eigenvectors in the grids'
//    global, displacement coordinates), or BOUGV1 (in the basic system)
//    when there is no OUGV1. The file is streamed: every block is skipped
//    but these two, and of the eigenvectors only the rows of the named grids
//    are kept, so a file of gigabytes costs a pass over its bytes, not its
//    size in memory.
//  - punch (DISP(PUNCH)=...): the `$EIGENVECTOR` blocks of real output, one
//    per mode, with its `$EIGENVALUE = ... MODE = ...` line; each grid is a
//    line of T1 T2 T3 and a `-CONT-` line of R1 R2 R3. A punch file holds no
//    generalised masses (generalized_mass is NaN): its eigenvectors are
//    what the solver normalised them to (EIGRL NORM=MASS is the default).
//
//  - OP4 matrices (OUTPUT4; deb/formats/op4_file.h reads the file): the
//    eigenvectors as a matrix of one column per mode (PHIG: a row per DOF
//    of the g-set), the eigenvalues omega^2 as a column, a row or a
//    diagonal matrix (LAMA, or KHH of mass-normalised modes), optionally
//    the generalised masses the same way (MHH). An OP4 file does not name
//    its rows: the budget gives the DOF of each row (Op4ModeMatrices).
//    Modes are sorted by frequency when the file's order is not.
//
// Complex eigenvectors (a damped or fluid-structure eigenproblem), SORT2
// tables and several subcases are refused: deb reads one set of real modes.
// Every rule broken is an InputError naming the file and the byte offset
// (OP2) or line (punch), the table or block, and what the file holds where
// something asked for is missing.
#pragma once

#include <Eigen/Dense>
#include <memory>
#include <string>
#include <vector>

namespace deb::formats {

// A degree of freedom: grid (or scalar point) id and component 1..6
// (T1 T2 T3 R1 R2 R3; a scalar point has only component 1).
struct NastranDof {
  long long grid = 0;
  int component = 0;
};

// "101:T3" -> {101, 3}; components T1..T3, R1..R3 (any case).
// @throws InputError (not located) naming the rule.
NastranDof ParseNastranDof(const std::string& text);
// {101, 3} -> "101:T3".
std::string NastranDofText(const NastranDof& dof);

// One row of the eigenvalue table.
struct NastranMode {
  long long number = 0;              // Nastran's mode number
  double eigenvalue = 0.0;           // omega^2 [(rad/s)^2]; about 0 (either sign) for a rigid-body mode
  double f_hz = 0.0;                 // the table's cycles column (punch: sqrt(|eigenvalue|) / 2 pi)
  double generalized_mass = 0.0;     // phi^T M phi in the model's units; NaN when the file has none
  double generalized_stiffness = 0.0;
};

class Op4File;

// Which matrices of an OP4 file hold the modes, and the DOF of each of the
// eigenvectors' rows.
struct Op4ModeMatrices {
  std::string phi;     // eigenvectors: a row per DOF, a column per mode
  std::string lambda;  // eigenvalues omega^2 [(rad/s)^2], one per mode
  std::string mass;    // generalised masses, one per mode; "" when the modes are mass-normalised
  std::vector<NastranDof> rows;  // phi's rows, in order
};

class NastranModeFile {
 public:
  // Opens the file and reads its eigenvalue table (and, for punch, which
  // grids each mode has).
  // @throws InputError "<path>: ..." if it is neither format, is
  //   truncated or damaged, holds no modes or no eigenvectors, complex
  //   eigenvectors, SORT2 output or several subcases.
  explicit NastranModeFile(const std::string& path);
  // The modes of OP4 matrices (format() "OP4, text", ...).
  // @throws InputError "<path>: ..." naming a matrix the file lacks (and
  //   those it holds), a complex one, shapes that disagree (`rows` count
  //   against phi's rows, an eigenvalue or mass count against phi's
  //   columns, a square lambda or mass that is not diagonal), a DOF given
  //   twice in `rows`, a generalised mass that is not > 0.
  NastranModeFile(const Op4File& file, const Op4ModeMatrices& matrices);
  ~NastranModeFile();
  NastranModeFile(const NastranModeFile&) = delete;
  NastranModeFile& operator=(const NastranModeFile&) = delete;

  const std::string& path() const { return path_; }
  // "OP2, little-endian, 32-bit words", "punch", "OP4, text".
  const std::string& format() const;
  // The table the eigenvectors come from: "OUGV1", "BOUGV1", "$EIGENVECTOR",
  // "matrix PHIG".
  const std::string& shape_table() const;
  // In the file's order (ascending frequency, as the solver writes them).
  const std::vector<NastranMode>& modes() const;

  // The eigenvectors of the first `count` modes (columns) at `dofs` (rows),
  // as in the file.
  // @throws InputError "<path>: ..." naming a grid that is not in the
  //   eigenvector table (and the grids it holds), a component a scalar point
  //   does not have, a mode whose eigenvector is missing, a value that is not
  //   finite, or damage found while reading.
  Eigen::MatrixXd Shapes(const std::vector<NastranDof>& dofs, int count) const;

  class Reader;

 private:
  std::string path_;
  std::unique_ptr<Reader> reader_;
};

// "OP2", "punch" or "" (neither), from the first bytes of the file at `path`.
// @throws InputError if it cannot be read.
std::string NastranFormatOf(const std::string& path);

}  // namespace deb::formats
