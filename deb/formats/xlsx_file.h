// Internal: not part of the public API.
// Excel workbooks (.xlsx) written through libxlsxwriter: sheets of numbers
// (stored as numbers, full double precision) and text, a bold header row
// kept in view, column widths, FAIL in red. Rows of a sheet are written
// in order (the workbook holds one row per sheet in memory; the rest waits
// in temporary files beside the target). This is the one module that uses
// libxlsxwriter.
#pragma once

#include <memory>
#include <string>
#include <vector>

namespace deb::formats {

enum class XlsxStyle { kPlain, kHeader, kPass, kFail };

// `name` + `suffix` as a sheet name Excel accepts: the characters [ ] : * ? / \ (backslash)
// replaced by '_', a leading or trailing apostrophe too, `name` shortened
// (whole UTF-8 characters) so that the whole fits Excel's 31 characters,
// and made unique among `taken` (letter case ignored, as Excel does) by a
// number "~2", "~3", ... before the suffix. The result is added to `taken`.
std::string XlsxSheetName(const std::string& name, const std::string& suffix, std::vector<std::string>& taken);

class XlsxWorkbook {
 public:
  // A new workbook to be written to `path` by Close().
  // @throws WriteError "<path>: ..." if the workbook cannot be made.
  explicit XlsxWorkbook(const std::string& path);
  // Without Close(): nothing is left at the path.
  ~XlsxWorkbook();
  XlsxWorkbook(const XlsxWorkbook&) = delete;
  XlsxWorkbook& operator=(const XlsxWorkbook&) = delete;

  // Adds a sheet named `name` (an XlsxSheetName); returns its index.
  // @throws WriteError if the name is refused.
  int AddSheet(const std::string& name);
  // The cell (row, column), 0-based; rows of a sheet in increasing order.
  // A value that is not finite leaves the cell empty (Excel has no NaN).
  // @throws WriteError if the cell cannot be written.
  void Number(int sheet, int row, int column, double value, XlsxStyle style = XlsxStyle::kPlain);
  void Text(int sheet, int row, int column, const std::string& text, XlsxStyle style = XlsxStyle::kPlain);
  // Keeps the first `rows` rows in view when scrolling.
  void Freeze(int sheet, int rows);
  void ColumnWidth(int sheet, int first_column, int last_column, double characters);

  // Writes the file.
  // @throws WriteError if it cannot be written; nothing is left at the path.
  void Close();

 private:
  struct Handle;
  std::string path_;
  std::unique_ptr<Handle> handle_;
};

}  // namespace deb::formats
