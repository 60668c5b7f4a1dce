// The punch reader of NastranModeFile (deb/formats/nastran_modes.h).
//
// A punch file is 80-column text: 72 columns of data and a sequence number.
// Each result block opens with $ lines: $TITLE, $SUBTITLE, $LABEL, the
// block's kind ($EIGENVECTOR, $DISPLACEMENTS, ...), its form ($REAL OUTPUT,
// $REAL-IMAGINARY OUTPUT, $MAGNITUDE-PHASE OUTPUT), $SUBCASE ID = n and, for
// a mode, $EIGENVALUE = value  MODE = n. Then one line per point:
//   grid id, point type (G grid, S scalar, ...), T1 T2 T3 (a scalar point: its one value)
//   -CONT-  R1 R2 R3                                   (grids only)
// Only $EIGENVECTOR blocks are read; the others are skipped.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <sstream>

#include "deb/core/error.h"
#include "deb/core/input_file.h"
#include "deb/core/limits.h"
#include "deb/core/math_constants.h"
#include "deb/core/number_text.h"
#include "deb/formats/nastran_reader.h"

namespace deb::formats {
namespace {

struct PunchPoint {
  int type = 1;  // 1 grid (six values), else one value
  double values[6] = {0, 0, 0, 0, 0, 0};
};

std::vector<std::string> Fields(const std::string& line) {
  std::istringstream in(line.substr(0, std::min<std::size_t>(line.size(), 72)));
  std::vector<std::string> fields;
  for (std::string f; in >> f;) fields.push_back(f);
  return fields;
}

class PunchModes final : public NastranModeFile::Reader {
 public:
  explicit PunchModes(const std::string& path) : path_(path) {
    format = "punch";
    table = "$EIGENVECTOR";
    const std::string text = ReadInputFile(path, "Nastran punch file", limits::kMaxTextFileBytes);
    TextLines lines(text, path);
    std::string line, kind;
    bool real = true, in_mode = false;
    long long subcase = 0, first_subcase = -1;
    std::map<long long, PunchPoint>* points = nullptr;
    PunchPoint* pending = nullptr;  // a grid whose -CONT- line comes next
    int pending_line = 0;
    const auto fail = [&](const std::string& rule) {
      throw InputError(path + ":" + std::to_string(lines.line_number()) + ": " + rule);
    };
    const auto number = [&](const std::string& field, const char* what) {
      double v = 0.0;
      const char* b = field.data();
      const char* e = b + field.size();
      if (b != e && *b == '+') ++b;
      const auto r = std::from_chars(b, e, v);
      if (r.ec != std::errc() || r.ptr != e || !std::isfinite(v))
        fail(std::string(what) + " '" + Excerpt(field) + "' is not a finite number");
      return v;
    };
    while (lines.Next(line)) {
      const std::string body = line.substr(0, std::min<std::size_t>(line.size(), 72));
      if (!body.empty() && body[0] == '$') {
        if (pending) fail("a $ line where the -CONT- line of the grid on line " + std::to_string(pending_line) +
                          " belongs");
        const std::vector<std::string> f = Fields(body);
        const std::string head = f.empty() ? "$" : f[0];
        if (head.rfind("$TITLE", 0) == 0 || head.rfind("$SUBTITLE", 0) == 0 || head.rfind("$LABEL", 0) == 0) {
          in_mode = false;
          points = nullptr;
          continue;
        }
        if (head == "$REAL" || head == "$REAL-IMAGINARY" || head == "$MAGNITUDE-PHASE") {
          real = head == "$REAL";
          if (kind == "$EIGENVECTOR" && !real)
            fail("complex eigenvectors (" + body.substr(0, body.find_last_not_of(' ') + 1) +
                 ", a complex eigenvalue analysis): deb reads real normal modes (SOL 103)");
          continue;
        }
        if (head == "$SUBCASE") {
          const std::size_t eq = body.find('=');
          if (eq == std::string::npos) fail("$SUBCASE without '= n'");
          const std::vector<std::string> v = Fields(body.substr(eq + 1));
          if (v.empty()) fail("$SUBCASE without a number");
          const auto r = std::from_chars(v[0].data(), v[0].data() + v[0].size(), subcase);
          if (r.ec != std::errc() || r.ptr != v[0].data() + v[0].size())
            fail("subcase '" + Excerpt(v[0]) + "' is not an integer");
          continue;
        }
        if (head == "$EIGENVALUE") {
          if (kind != "$EIGENVECTOR") continue;
          // $EIGENVALUE =  8.2327770E+06  MODE =     1
          const std::size_t eq = body.find('='), mode_at = body.find("MODE");
          if (eq == std::string::npos || mode_at == std::string::npos || mode_at < eq)
            fail("expected '$EIGENVALUE = value  MODE = n'");
          const std::vector<std::string> v = Fields(body.substr(eq + 1, mode_at - eq - 1));
          const std::size_t eq2 = body.find('=', mode_at);
          const std::vector<std::string> n = Fields(eq2 == std::string::npos ? "" : body.substr(eq2 + 1));
          if (v.size() != 1 || n.size() != 1) fail("expected '$EIGENVALUE = value  MODE = n'");
          NastranMode m;
          m.eigenvalue = number(v[0], "the eigenvalue");
          const double mode_number = number(n[0], "the mode number");
          if (mode_number != std::floor(mode_number) || mode_number < 1 || mode_number > 1e15)
            fail("mode number " + n[0] + " is not a positive integer");
          m.number = static_cast<long long>(mode_number);
          m.f_hz = std::sqrt(std::abs(m.eigenvalue)) / kTwoPi;
          m.generalized_mass = std::nan("");
          m.generalized_stiffness = std::nan("");
          if (first_subcase < 0) first_subcase = subcase;
          if (subcase != first_subcase)
            fail("subcase " + std::to_string(subcase) + " after subcase " + std::to_string(first_subcase) +
                 ": deb reads the modes of one subcase");
          if (!modes.empty() && m.number <= modes.back().number)
            fail("mode " + std::to_string(m.number) + " after mode " + std::to_string(modes.back().number) +
                 ": mode numbers must increase");
          if (modes.size() >= static_cast<std::size_t>(kMaxFileModes))
            fail("more than " + std::to_string(kMaxFileModes) + " modes");
          modes.push_back(m);
          lines_.push_back(lines.line_number());
          points_.emplace_back();
          points = &points_.back();
          in_mode = true;
          continue;
        }
        // Any other $ line names the block's kind ($EIGENVECTOR, $DISPLACEMENTS, ...).
        kind = head;
        in_mode = false;
        points = nullptr;
        continue;
      }
      if (!in_mode) continue;
      const std::vector<std::string> f = Fields(body);
      if (f.empty()) continue;
      if (f[0] == "-CONT-") {
        if (!pending) fail("a -CONT- line without a grid line before it");
        if (f.size() != 4) fail("a -CONT- line of a grid holds R1 R2 R3: 3 values, found " + std::to_string(f.size() - 1));
        for (int c = 0; c < 3; ++c) pending->values[3 + c] = number(f[static_cast<std::size_t>(1 + c)], "a value");
        pending = nullptr;
        continue;
      }
      if (pending) fail("expected the -CONT- line (R1 R2 R3) of the grid on line " + std::to_string(pending_line));
      if (f.size() < 3) fail("expected a point's line: id, type, values");
      long long id = 0;
      const auto r = std::from_chars(f[0].data(), f[0].data() + f[0].size(), id);
      if (r.ec != std::errc() || r.ptr != f[0].data() + f[0].size() || id <= 0)
        fail("point id '" + Excerpt(f[0]) + "' is not a positive integer");
      PunchPoint p;
      p.type = f[1] == "G" ? 1 : 2;
      const std::size_t want = p.type == 1 ? 3 : 1;
      if (f.size() != 2 + want)
        fail("a " + std::string(p.type == 1 ? "grid's line holds T1 T2 T3" : "scalar point's line holds its value") +
             ": " + std::to_string(want) + " value(s), found " + std::to_string(f.size() - 2));
      for (std::size_t c = 0; c < want; ++c) p.values[c] = number(f[2 + c], "a value");
      auto [it, fresh] = points->emplace(id, p);
      if (!fresh) fail("point " + std::to_string(id) + " a second time in mode " + std::to_string(modes.back().number));
      if (p.type == 1) {
        pending = &it->second;
        pending_line = lines.line_number();
      }
    }
    if (pending) throw InputError(path + ":" + std::to_string(pending_line) + ": the file ends before this grid's -CONT- line");
    if (modes.empty())
      throw InputError(path + ": no $EIGENVECTOR block with real output: not the punched eigenvectors of a normal "
                              "modes run (DISP(PUNCH)=... in SOL 103)?");
  }

  Eigen::MatrixXd Shapes(const std::vector<NastranDof>& dofs, int count) const override {
    Eigen::MatrixXd phi(static_cast<Eigen::Index>(dofs.size()), count);
    for (int k = 0; k < count; ++k) {
      const auto& points = points_[static_cast<std::size_t>(k)];
      for (std::size_t i = 0; i < dofs.size(); ++i) {
        const auto it = points.find(dofs[i].grid);
        const std::string at = path_ + ":" + std::to_string(lines_[static_cast<std::size_t>(k)]) + ": mode " +
                               std::to_string(modes[static_cast<std::size_t>(k)].number) + ": ";
        if (it == points.end()) {
          std::vector<long long> grids;
          for (const auto& [id, p] : points) grids.push_back(id);
          throw InputError(at + MissingGridText(dofs[i], table, grids));
        }
        if (it->second.type != 1 && dofs[i].component != 1)
          throw InputError(at + NastranDofText(dofs[i]) + ": point " + std::to_string(dofs[i].grid) +
                           " is a scalar point, with one component: T1");
        phi(static_cast<Eigen::Index>(i), k) = it->second.values[dofs[i].component - 1];
      }
    }
    return phi;
  }

 private:
  std::string path_;
  std::vector<int> lines_;                             // each mode's $EIGENVALUE line
  std::vector<std::map<long long, PunchPoint>> points_;  // each mode's points
};

}  // namespace

std::unique_ptr<NastranModeFile::Reader> OpenPunchModes(const std::string& path) {
  return std::make_unique<PunchModes>(path);
}

}  // namespace deb::formats
