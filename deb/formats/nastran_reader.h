// Internal: not part of the public API.
// What the two Nastran readers (nastran_op2.cpp, nastran_punch.cpp) give
// NastranModeFile (deb/formats/nastran_modes.h), and the helpers they share.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "deb/formats/nastran_modes.h"

namespace deb::formats {

class NastranModeFile::Reader {
 public:
  virtual ~Reader() = default;
  // As NastranModeFile::Shapes; `count` <= modes.size().
  virtual Eigen::MatrixXd Shapes(const std::vector<NastranDof>& dofs, int count) const = 0;

  std::string format;
  std::string table;
  std::vector<NastranMode> modes;
};

std::unique_ptr<NastranModeFile::Reader> OpenOp2Modes(const std::string& path);
std::unique_ptr<NastranModeFile::Reader> OpenPunchModes(const std::string& path);
std::unique_ptr<NastranModeFile::Reader> OpenOp4Modes(const Op4File& file, const Op4ModeMatrices& matrices);

// Sorted, distinct grid ids as a message quotes them: "12 grid(s): 1-12",
// "3 grid(s): 101, 102, 2001", at most a few ranges then "...".
std::string GridListText(std::vector<long long> grids);

// The message for a DOF whose grid is not in `table` (holding `grids`).
std::string MissingGridText(const NastranDof& dof, const std::string& table, const std::vector<long long>& grids);

// `v` with its bytes in the other order.
inline std::uint32_t Swapped32(std::uint32_t v) {
  return (v >> 24) | ((v >> 8) & 0xff00u) | ((v << 8) & 0xff0000u) | (v << 24);
}
inline std::uint64_t Swapped64(std::uint64_t v) {
  return (static_cast<std::uint64_t>(Swapped32(static_cast<std::uint32_t>(v))) << 32) |
         Swapped32(static_cast<std::uint32_t>(v >> 32));
}

// A mode table's count bound: modes of one file deb reads the eigenvalues of
// (a path keeps at most limits::kMaxModes of them).
inline constexpr long long kMaxFileModes = 1'000'000;

}  // namespace deb::formats
