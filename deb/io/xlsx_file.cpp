#include "deb/io/xlsx_file.h"

#include <xlsxwriter.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <mutex>

#include "deb/core/document_date.h"
#include "deb/core/error.h"
#include "deb/core/shared_library.h"
#include "deb/core/input_file.h"

namespace deb::io {
namespace {

// libxlsxwriter is not linked: it is loaded when the first workbook is made.
// Linked, it and the libraries under it (minizip, zlib, OpenSSL's
// libcrypto) cost about 2 ms at every start of deb, .xlsx or not
// (docs/result_files.md). Only the functions below are used;
// DEB_XLSXWRITER_SONAME is the library the build found.
struct XlsxApi {
  decltype(&::workbook_new_opt) WorkbookNewOpt;
  decltype(&::workbook_add_worksheet) AddWorksheet;
  decltype(&::workbook_add_format) AddFormat;
  decltype(&::workbook_set_properties) SetProperties;
  decltype(&::workbook_close) Close;
  void (*Free)(lxw_workbook*);  // lxw_workbook_free: exported, not declared in the headers
  decltype(&::format_set_bold) SetBold;
  decltype(&::format_set_bottom) SetBottom;
  decltype(&::format_set_font_color) SetFontColor;
  decltype(&::worksheet_write_number) WriteNumber;
  decltype(&::worksheet_write_string) WriteString;
  decltype(&::worksheet_freeze_panes) FreezePanes;
  decltype(&::worksheet_set_column) SetColumn;
  decltype(&::lxw_strerror) StrError;
};

struct LoadedXlsx {
  XlsxApi api{};
  std::string failure;  // why libxlsxwriter could not be loaded; "" if it was
};

LoadedXlsx LoadXlsx() {
  LoadedXlsx x;
  SharedLibrary library(DEB_XLSXWRITER_SONAME);
  XlsxApi& a = x.api;
  const bool all = library.Resolve("workbook_new_opt", a.WorkbookNewOpt) &&
                   library.Resolve("workbook_add_worksheet", a.AddWorksheet) &&
                   library.Resolve("workbook_add_format", a.AddFormat) &&
                   library.Resolve("workbook_set_properties", a.SetProperties) &&
                   library.Resolve("workbook_close", a.Close) &&
                   library.Resolve("lxw_workbook_free", a.Free) &&
                   library.Resolve("format_set_bold", a.SetBold) &&
                   library.Resolve("format_set_bottom", a.SetBottom) &&
                   library.Resolve("format_set_font_color", a.SetFontColor) &&
                   library.Resolve("worksheet_write_number", a.WriteNumber) &&
                   library.Resolve("worksheet_write_string", a.WriteString) &&
                   library.Resolve("worksheet_freeze_panes", a.FreezePanes) &&
                   library.Resolve("worksheet_set_column", a.SetColumn) &&
                   library.Resolve("lxw_strerror", a.StrError);
  if (!all) x.api = XlsxApi{};
  x.failure = library.failure();
  return x;
}

const XlsxApi& Xlsx(const std::string& path) {
  static const LoadedXlsx loaded = LoadXlsx();
  if (!loaded.failure.empty())
    throw WriteError(path + ": writing an Excel workbook needs the libxlsxwriter library (" DEB_XLSXWRITER_SONAME
                            "), which cannot be loaded: " + Excerpt(loaded.failure, 160) +
                     "; install it (Debian: libxlsxwriter4)");
  return loaded.api;
}

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
  const XlsxApi* api = nullptr;
  lxw_workbook* workbook = nullptr;
  std::string tmpdir;
  std::vector<lxw_worksheet*> sheets;
  lxw_format* header = nullptr;
  lxw_format* pass = nullptr;
  lxw_format* fail = nullptr;
};

XlsxWorkbook::XlsxWorkbook(const std::string& path) : path_(path), handle_(std::make_unique<Handle>()) {
  Handle& h = *handle_;
  h.api = &Xlsx(path);
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  h.tmpdir = parent.empty() ? "." : parent.string();
  lxw_workbook_options options{};
  options.constant_memory = LXW_TRUE;
  options.tmpdir = h.tmpdir.data();
  h.workbook = h.api->WorkbookNewOpt(path.c_str(), &options);
  if (h.workbook == nullptr) throw WriteError(path + ": cannot make an Excel workbook (out of memory?)");
  lxw_doc_properties properties{};
  char creator[] = "deb";
  properties.author = creator;
  properties.created = DocumentTime();
  h.api->SetProperties(h.workbook, &properties);
  h.header = h.api->AddFormat(h.workbook);
  h.pass = h.api->AddFormat(h.workbook);
  h.fail = h.api->AddFormat(h.workbook);
  if (h.header == nullptr || h.pass == nullptr || h.fail == nullptr)
    throw WriteError(path + ": cannot make the cell formats of an Excel workbook");
  h.api->SetBold(h.header);
  h.api->SetBottom(h.header, LXW_BORDER_THIN);
  h.api->SetFontColor(h.pass, LXW_COLOR_GREEN);
  h.api->SetBold(h.fail);
  h.api->SetFontColor(h.fail, LXW_COLOR_RED);
}

XlsxWorkbook::~XlsxWorkbook() {
  if (handle_->workbook == nullptr) return;
  handle_->api->Free(handle_->workbook);  // discarded: nothing was written to the path
  std::error_code ec;
  std::filesystem::remove(path_, ec);
}

int XlsxWorkbook::AddSheet(const std::string& name) {
  lxw_worksheet* sheet = handle_->api->AddWorksheet(handle_->workbook, name.c_str());
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
  const lxw_error e = h.api->WriteNumber(h.sheets.at(static_cast<std::size_t>(sheet)), static_cast<lxw_row_t>(row),
                                         static_cast<lxw_col_t>(column), value,
                                         FormatOf(style, h.header, h.pass, h.fail));
  if (e != LXW_NO_ERROR)
    throw WriteError(path_ + ": cannot write row " + std::to_string(row + 1) + ", column " + std::to_string(column + 1) +
                     " of the Excel workbook: " + h.api->StrError(e));
}

void XlsxWorkbook::Text(int sheet, int row, int column, const std::string& text, XlsxStyle style) {
  Handle& h = *handle_;
  const lxw_error e = h.api->WriteString(h.sheets.at(static_cast<std::size_t>(sheet)), static_cast<lxw_row_t>(row),
                                         static_cast<lxw_col_t>(column), text.c_str(),
                                         FormatOf(style, h.header, h.pass, h.fail));
  if (e != LXW_NO_ERROR)
    throw WriteError(path_ + ": cannot write row " + std::to_string(row + 1) + ", column " + std::to_string(column + 1) +
                     " of the Excel workbook: " + h.api->StrError(e));
}

void XlsxWorkbook::Freeze(int sheet, int rows) {
  handle_->api->FreezePanes(handle_->sheets.at(static_cast<std::size_t>(sheet)), static_cast<lxw_row_t>(rows), 0);
}

void XlsxWorkbook::ColumnWidth(int sheet, int first_column, int last_column, double characters) {
  handle_->api->SetColumn(handle_->sheets.at(static_cast<std::size_t>(sheet)), static_cast<lxw_col_t>(first_column),
                          static_cast<lxw_col_t>(last_column), characters, nullptr);
}

void XlsxWorkbook::Close() {
  Handle& h = *handle_;
  lxw_workbook* const workbook = h.workbook;
  h.workbook = nullptr;  // freed by workbook_close, whatever it returns
  const lxw_error e = h.api->Close(workbook);
  if (e != LXW_NO_ERROR) {
    std::error_code ec;
    std::filesystem::remove(path_, ec);
    throw WriteError(path_ + ": cannot write the Excel workbook: " + h.api->StrError(e));
  }
}

}  // namespace deb::io
