#include "deb/systems/modal_csv.h"

#include <map>

#include "deb/core/error.h"
#include "deb/core/limits.h"
#include "deb/core/numeric_table.h"
#include "deb/systems/modal_model.h"

namespace deb {
namespace {

void RequireHeader(const NumericTable& t, const std::string& what) {
  if (!t.header.empty()) return;
  t.Fail(t.rows.empty() ? 1 : t.rows.front().line, 1, "a " + what + " needs a header row: " +
         (what == "mode table" ? "f_hz, zeta (and optionally mode)" : "a name for the DOF column, then one name per mode"));
}

ModeTable ModesFrom(const NumericTable& t) {
  RequireHeader(t, "mode table");
  std::map<std::string, std::size_t> column;
  for (std::size_t c = 0; c < t.header.size(); ++c) {
    const std::string& name = t.header[c];
    if (name != "f_hz" && name != "zeta" && name != "mode")
      t.Fail(t.header_line, t.header_columns[c],
             "unknown column '" + name + "'; a mode table has the columns f_hz, zeta and optionally mode");
    if (!column.emplace(name, c).second)
      t.Fail(t.header_line, t.header_columns[c], "column '" + name + "' is given twice");
  }
  for (const char* need : {"f_hz", "zeta"})
    if (!column.count(need))
      t.Fail(t.header_line, 1, std::string("missing column '") + need + "'; a mode table has the columns f_hz and zeta");
  if (t.rows.empty()) t.Fail(t.header_line, 1, "the mode table has no rows; give one row per mode");
  if (t.rows.size() > static_cast<std::size_t>(limits::kMaxModes))
    t.Fail(t.rows[limits::kMaxModes].line, 1,
           std::to_string(t.rows.size()) + " modes; at most " + std::to_string(limits::kMaxModes) + " are allowed");
  const std::size_t cf = column.at("f_hz"), cz = column.at("zeta");
  ModeTable m;
  for (const NumericTable::Row& row : t.rows) {
    const double f = row.values[cf], z = row.values[cz];
    if (const std::string p = ModeFrequencyProblem(f); !p.empty()) t.Fail(row.line, row.columns[cf], p);
    if (const std::string p = ModeDampingProblem(f, z); !p.empty()) t.Fail(row.line, row.columns[cz], p);
    m.f_hz.push_back(f);
    m.zeta.push_back(z);
  }
  return m;
}

NumericTableOptions ModeOptions() {
  NumericTableOptions o;
  o.first_column = "first column";
  return o;
}

NumericTableOptions ShapeOptions() {
  NumericTableOptions o;
  o.names_in_first_column = true;
  o.first_column = "DOF name";
  return o;
}

ShapeTable ShapesFrom(const NumericTable& t, int expected_modes, const std::string& modes_from) {
  RequireHeader(t, "shape table");
  const int modes = static_cast<int>(t.header.size()) - 1;
  if (modes > limits::kMaxModes)
    t.Fail(t.header_line, t.header_columns[limits::kMaxModes + 1],
           std::to_string(modes) + " mode columns; at most " + std::to_string(limits::kMaxModes) + " are allowed");
  if (modes == 0) t.Fail(t.header_line, 1, "no mode columns: after the DOF column, give one column per mode");
  if (expected_modes >= 0 && modes != expected_modes) {
    const int column = modes > expected_modes ? t.header_columns[expected_modes + 1] : t.header_columns.front();
    t.Fail(t.header_line, column,
           std::to_string(modes) + " mode column(s), but " + modes_from + " has " + std::to_string(expected_modes) +
               " mode(s); give one column per mode, in its order");
  }
  if (t.rows.empty()) t.Fail(t.header_line, 1, "the shape table has no rows; give one row per DOF");
  if (t.rows.size() > static_cast<std::size_t>(limits::kMaxChannels))
    t.Fail(t.rows[limits::kMaxChannels].line, 1,
           std::to_string(t.rows.size()) + " DOFs; at most " + std::to_string(limits::kMaxChannels) + " are allowed");
  ShapeTable s;
  s.values.resize(static_cast<Eigen::Index>(t.rows.size()), modes);
  std::map<std::string, int> line_of;
  for (std::size_t r = 0; r < t.rows.size(); ++r) {
    const NumericTable::Row& row = t.rows[r];
    const auto [it, fresh] = line_of.emplace(row.name, row.line);
    if (!fresh)
      t.Fail(row.line, row.columns[0],
             "DOF '" + row.name + "' is given twice (also on line " + std::to_string(it->second) + ")");
    s.dofs.push_back(row.name);
    for (int k = 0; k < modes; ++k) s.values(static_cast<Eigen::Index>(r), k) = row.values[k + 1];
  }
  return s;
}

}  // namespace

ModeTable ReadModeTable(const std::string& path) {
  return ModesFrom(ReadNumericTable(path, ModeOptions(), "mode table"));
}

ModeTable ParseModeTable(std::istream& in, const std::string& name) {
  return ModesFrom(ParseNumericTable(in, name, ModeOptions()));
}

ShapeTable ReadShapeTable(const std::string& path, int expected_modes, const std::string& modes_from) {
  return ShapesFrom(ReadNumericTable(path, ShapeOptions(), "shape table"), expected_modes, modes_from);
}

ShapeTable ParseShapeTable(std::istream& in, const std::string& name, int expected_modes,
                           const std::string& modes_from) {
  return ShapesFrom(ParseNumericTable(in, name, ShapeOptions()), expected_modes, modes_from);
}

}  // namespace deb
