#include "deb/formats/xlsx_file.h"

#include <xlsxwriter.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>

#include "deb/core/document_date.h"
#include "deb/core/error.h"
#include "deb/core/input_file.h"

namespace deb::formats {
namespace {

// UTF-8 characters of `s` (continuation bytes not counted).
std::size_t Characters(const std::string& s) {
  std::size_t n = 0;
  for (const char c : s) n += (static_cast<unsigned char>(c) & 0xC0) != 0x80 ? 1 : 0;
  return n;
}

// The first `n` characters of `s`.
std::string FirstCharacters(const std::string& s, std::size_t n) {
  std::size_t count = 0, i = 0;
  for (; i < s.size(); ++i) {
    if ((static_cast<unsigned char>(s[i]) & 0xC0) != 0x80 && count++ == n) break;
  }
  return s.substr(0, i);
}

std::string Lower(std::string s) {
  for (char& c : s)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return s;
}

constexpr std::size_t kMaxSheetName = 31;  // Excel's limit, in characters

}  // namespace

std::string XlsxSheetName(const std::string& name, const std::string& suffix, std::vector<std::string>& taken) {
  std::string clean;
  for (const char c : name) clean += std::strchr("[]:*?/\\", c) != nullptr && c != '\0' ? '_' : c;
  if (!clean.empty() && clean.front() == '\'') clean.front() = '_';
  if (clean.empty()) clean = "_";
  const auto used = [&](const std::string& candidate) {
    for (const std::string& t : taken)
      if (Lower(t) == Lower(candidate)) return true;
    return false;
  };
  std::string out;
  for (int k = 1;; ++k) {
    const std::string mark = k == 1 ? "" : "~" + std::to_string(k);
    const std::size_t room = kMaxSheetName - Characters(mark + suffix);
    std::string head = FirstCharacters(clean, room);
    if (suffix.empty() && mark.empty() && head.back() == '\'') head.back() = '_';
    out = head + mark + suffix;
    if (!used(out)) break;
  }
  taken.push_back(out);
  return out;
}

struct XlsxWorkbook::Handle {
  lxw_workbook* workbook = nullptr;
  std::string tmpdir;
  std::vector<lxw_worksheet*> sheets;
  lxw_format* header = nullptr;
  lxw_format* pass = nullptr;
  lxw_format* fail = nullptr;
};

XlsxWorkbook::XlsxWorkbook(const std::string& path) : path_(path), handle_(std::make_unique<Handle>()) {
  Handle& h = *handle_;
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  h.tmpdir = parent.empty() ? "." : parent.string();
  lxw_workbook_options options{};
  options.constant_memory = LXW_TRUE;
  options.tmpdir = h.tmpdir.data();
  h.workbook = workbook_new_opt(path.c_str(), &options);
  if (h.workbook == nullptr) throw WriteError(path + ": cannot make an Excel workbook (out of memory?)");
  lxw_doc_properties properties{};
  char creator[] = "deb";
  properties.author = creator;
  properties.created = DocumentTime();
  workbook_set_properties(h.workbook, &properties);
  h.header = workbook_add_format(h.workbook);
  h.pass = workbook_add_format(h.workbook);
  h.fail = workbook_add_format(h.workbook);
  if (h.header == nullptr || h.pass == nullptr || h.fail == nullptr)
    throw WriteError(path + ": cannot make the cell formats of an Excel workbook");
  format_set_bold(h.header);
  format_set_bottom(h.header, LXW_BORDER_THIN);
  format_set_font_color(h.pass, LXW_COLOR_GREEN);
  format_set_bold(h.fail);
  format_set_font_color(h.fail, LXW_COLOR_RED);
}

XlsxWorkbook::~XlsxWorkbook() {
  if (handle_->workbook == nullptr) return;
  lxw_workbook_free(handle_->workbook);  // discarded: nothing was written to the path
  std::error_code ec;
  std::filesystem::remove(path_, ec);
}

int XlsxWorkbook::AddSheet(const std::string& name) {
  lxw_worksheet* sheet = workbook_add_worksheet(handle_->workbook, name.c_str());
  if (sheet == nullptr)
    throw WriteError(path_ + ": cannot add the sheet '" + Excerpt(name) +
                     "' to the Excel workbook (a name of at most 31 characters, unique, without []:*?/\\)");
  handle_->sheets.push_back(sheet);
  return static_cast<int>(handle_->sheets.size()) - 1;
}

namespace {
lxw_format* FormatOf(const XlsxStyle style, lxw_format* header, lxw_format* pass, lxw_format* fail) {
  switch (style) {
    case XlsxStyle::kHeader: return header;
    case XlsxStyle::kPass: return pass;
    case XlsxStyle::kFail: return fail;
    case XlsxStyle::kPlain: break;
  }
  return nullptr;
}
}  // namespace

void XlsxWorkbook::Number(int sheet, int row, int column, double value, XlsxStyle style) {
  if (!std::isfinite(value)) return;
  Handle& h = *handle_;
  const lxw_error e = worksheet_write_number(h.sheets.at(static_cast<std::size_t>(sheet)), static_cast<lxw_row_t>(row),
                                         static_cast<lxw_col_t>(column), value,
                                         FormatOf(style, h.header, h.pass, h.fail));
  if (e != LXW_NO_ERROR)
    throw WriteError(path_ + ": cannot write row " + std::to_string(row + 1) + ", column " + std::to_string(column + 1) +
                     " of the Excel workbook: " + lxw_strerror(e));
}

void XlsxWorkbook::Text(int sheet, int row, int column, const std::string& text, XlsxStyle style) {
  Handle& h = *handle_;
  const lxw_error e = worksheet_write_string(h.sheets.at(static_cast<std::size_t>(sheet)), static_cast<lxw_row_t>(row),
                                         static_cast<lxw_col_t>(column), text.c_str(),
                                         FormatOf(style, h.header, h.pass, h.fail));
  if (e != LXW_NO_ERROR)
    throw WriteError(path_ + ": cannot write row " + std::to_string(row + 1) + ", column " + std::to_string(column + 1) +
                     " of the Excel workbook: " + lxw_strerror(e));
}

void XlsxWorkbook::Freeze(int sheet, int rows) {
  worksheet_freeze_panes(handle_->sheets.at(static_cast<std::size_t>(sheet)), static_cast<lxw_row_t>(rows), 0);
}

void XlsxWorkbook::ColumnWidth(int sheet, int first_column, int last_column, double characters) {
  worksheet_set_column(handle_->sheets.at(static_cast<std::size_t>(sheet)), static_cast<lxw_col_t>(first_column),
                          static_cast<lxw_col_t>(last_column), characters, nullptr);
}

void XlsxWorkbook::Close() {
  Handle& h = *handle_;
  lxw_workbook* const workbook = h.workbook;
  h.workbook = nullptr;  // freed by workbook_close, whatever it returns
  const lxw_error e = workbook_close(workbook);
  if (e != LXW_NO_ERROR) {
    std::error_code ec;
    std::filesystem::remove(path_, ec);
    throw WriteError(path_ + ": cannot write the Excel workbook: " + lxw_strerror(e));
  }
}

}  // namespace deb::formats
