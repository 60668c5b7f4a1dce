#include "deb/formats/nastran_modes.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdint>
#include <cstring>

#include "deb/core/error.h"
#include "deb/core/input_file.h"
#include "deb/core/limits.h"
#include "deb/formats/nastran_reader.h"
#include "deb/formats/op4_file.h"

namespace deb::formats {

namespace {

const char* const kComponents[6] = {"T1", "T2", "T3", "R1", "R2", "R3"};

}  // namespace

NastranDof ParseNastranDof(const std::string& text) {
  const std::size_t colon = text.find(':');
  const std::string rule = "'" + Excerpt(text) + "' is not a Nastran DOF: write GRID:COMPONENT, e.g. 101:T3 (components T1 T2 T3 R1 R2 R3)";
  if (colon == std::string::npos || colon == 0) throw InputError(rule);
  NastranDof dof;
  const char* begin = text.data();
  const auto r = std::from_chars(begin, begin + colon, dof.grid);
  if (r.ec != std::errc() || r.ptr != begin + colon || dof.grid <= 0) throw InputError(rule);
  std::string c = text.substr(colon + 1);
  for (char& ch : c) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
  for (int k = 0; k < 6; ++k)
    if (c == kComponents[k]) dof.component = k + 1;
  if (dof.component == 0) throw InputError(rule);
  return dof;
}

std::string NastranDofText(const NastranDof& dof) {
  DEB_DEMAND(dof.component >= 1 && dof.component <= 6);
  return std::to_string(dof.grid) + ":" + kComponents[dof.component - 1];
}

std::string GridListText(std::vector<long long> grids) {
  std::sort(grids.begin(), grids.end());
  grids.erase(std::unique(grids.begin(), grids.end()), grids.end());
  std::string text = std::to_string(grids.size()) + " grid(s)";
  if (grids.empty()) return text;
  text += ": ";
  int ranges = 0;
  for (std::size_t i = 0; i < grids.size();) {
    std::size_t j = i;
    while (j + 1 < grids.size() && grids[j + 1] == grids[j] + 1) ++j;
    if (ranges == 8) return text + ", ...";
    if (ranges++ > 0) text += ", ";
    text += std::to_string(grids[i]);
    if (j > i) text += (j == i + 1 ? ", " : "-") + std::to_string(grids[j]);
    i = j + 1;
  }
  return text;
}

std::string MissingGridText(const NastranDof& dof, const std::string& table, const std::vector<long long>& grids) {
  return "grid " + std::to_string(dof.grid) + " (of " + NastranDofText(dof) + ") is not in " + table + ", which holds " +
         GridListText(grids) + " (the grids of the solver's DISP output request)";
}

NastranModeFile::NastranModeFile(const std::string& path) : path_(path) {
  const std::string format = NastranFormatOf(path);
  if (format == "OP2")
    reader_ = OpenOp2Modes(path);
  else if (format == "punch")
    reader_ = OpenPunchModes(path);
  else
    throw InputError(path + ": neither a Nastran OP2 file (Fortran records of 4- or 8-byte words) nor a punch file "
                            "(text starting with $ lines)");
  if (reader_->modes.empty()) throw InputError(path + ": the file holds no modes");
}

NastranModeFile::NastranModeFile(const Op4File& file, const Op4ModeMatrices& matrices)
    : path_(file.path()), reader_(OpenOp4Modes(file, matrices)) {
  if (reader_->modes.empty()) throw InputError(path_ + ": the file holds no modes");
}

NastranModeFile::~NastranModeFile() = default;

const std::string& NastranModeFile::format() const { return reader_->format; }
const std::string& NastranModeFile::shape_table() const { return reader_->table; }
const std::vector<NastranMode>& NastranModeFile::modes() const { return reader_->modes; }

Eigen::MatrixXd NastranModeFile::Shapes(const std::vector<NastranDof>& dofs, int count) const {
  DEB_DEMAND(count >= 0 && count <= static_cast<int>(reader_->modes.size()));
  for (const NastranDof& d : dofs) DEB_DEMAND(d.component >= 1 && d.component <= 6);
  return reader_->Shapes(dofs, count);
}

std::string NastranFormatOf(const std::string& path) {
  RequireInputFile(path, "Nastran file", limits::kMaxSolverFileBytes);
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw InputError(path + ": cannot be opened: " + std::strerror(errno));
  unsigned char head[512];
  const ssize_t n = ::pread(fd, head, sizeof(head), 0);
  ::close(fd);
  if (n < 0) throw InputError(path + ": cannot be read: " + std::strerror(errno));
  // OP2: a first record of one 4- or 8-byte word, its length marker repeated after it.
  if (n >= 12) {
    std::uint32_t first, after4, after8;
    std::memcpy(&first, head, 4);
    for (bool swap : {false, true}) {
      const std::uint32_t len = swap ? Swapped32(first) : first;
      if (len != 4 && len != 8) continue;
      if (static_cast<std::size_t>(n) < 8 + len) continue;
      std::memcpy(&after4, head + 4 + len, 4);
      after8 = swap ? Swapped32(after4) : after4;
      if (after8 == len) return "OP2";
    }
  }
  // Punch: text whose first non-blank character is '$'.
  for (ssize_t i = 0; i < n; ++i) {
    if (head[i] == ' ' || head[i] == '\t' || head[i] == '\r' || head[i] == '\n') continue;
    return head[i] == '$' ? "punch" : "";
  }
  return "";
}

}  // namespace deb::formats
