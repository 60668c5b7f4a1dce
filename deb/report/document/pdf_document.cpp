#include "deb/report/document/pdf_document.h"

#include <cairo-pdf.h>
#include <cairo.h>
#include <pango/pangocairo.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>
#include <utility>

#include "deb/core/error.h"
#include "deb/core/number_text.h"
#include "deb/report/document/svg_figure.h"

namespace deb::report {

std::string TypesetExponents(const std::string& text) {
  const auto digit = [&](std::size_t k) { return k < text.size() && std::isdigit(static_cast<unsigned char>(text[k])); };
  std::string out;
  out.reserve(text.size() + 16);
  for (std::size_t i = 0; i < text.size(); ++i) {
    // "(µm/s)^2", "10^-6": a power after a base (not a space) as superscript.
    if (text[i] == '^' && i > 0 && text[i - 1] != ' ') {
      std::size_t k = i + 1;
      const bool negative = k < text.size() && text[k] == '-';
      if (negative) ++k;
      const std::size_t first = k;
      while (digit(k)) ++k;
      if (k > first && (k >= text.size() || !std::isalnum(static_cast<unsigned char>(text[k])))) {
        out += SuperscriptText(std::string_view(text).substr(i + 1, k - i - 1));  // the sign with the digits
        i = k - 1;
        continue;
      }
    }
    // "3.590e-04": a number (digits and a point, not part of a name), 'e',
    // a sign or none, digits, and no letter or digit after them.
    std::size_t start = i;
    while (start > 0 && (digit(start - 1) || text[start - 1] == '.')) --start;
    // (a name's part after a line-break chance, BreakableNames, is still in the name)
    const bool named =
        start > 0 && (std::isalpha(static_cast<unsigned char>(text[start - 1])) || text[start - 1] == '_' ||
                      (start >= 3 && text.compare(start - 3, 3, "\u200b") == 0));
    if (text[i] == 'e' && i > 0 && digit(i - 1) && !named) {
      std::size_t k = i + 1;
      const bool negative = k < text.size() && text[k] == '-';
      if (k < text.size() && (text[k] == '-' || text[k] == '+')) ++k;
      const std::size_t first = k;
      while (digit(k)) ++k;
      const bool ends = k >= text.size() || !(std::isalnum(static_cast<unsigned char>(text[k])) || text[k] == '_');
      if (k > first && ends) {
        std::size_t lead = first;
        while (lead + 1 < k && text[lead] == '0') ++lead;
        out += "·10" + SuperscriptText((negative ? "-" : "") + text.substr(lead, k - lead));
        i = k - 1;
        continue;
      }
    }
    out += text[i];
  }
  return out;
}

std::string NumbersKeptWithUnits(const std::string& text) {
  std::string out;
  out.reserve(text.size() + 8);
  std::size_t unit = std::string::npos;  // where the word after a number starts
  for (std::size_t i = 0; i < text.size(); ++i) {
    const bool after_digit = i > 0 && std::isdigit(static_cast<unsigned char>(text[i - 1]));
    const unsigned char next = i + 1 < text.size() ? static_cast<unsigned char>(text[i + 1]) : 0;
    if (text[i] == ' ' && after_digit && (std::isalpha(next) || next >= 0x80 || next == '%' || next == '(')) {
      out += "\u00a0";
      unit = i + 1;
      continue;
    }
    if (text[i] == ' ' && unit != std::string::npos && i - unit <= 4) {
      // A unit of two factors, "50 N s/mm": a short symbol and a word with a
      // '/' after it stay on the number's line.
      const std::size_t end = std::min(text.find(' ', i + 1), text.size());
      if (text.substr(i + 1, end - i - 1).find('/') != std::string::npos) {
        out += "\u00a0";
        unit = std::string::npos;
        continue;
      }
    }
    if (text[i] == ' ') unit = std::string::npos;
    out += text[i];
  }
  return out;
}

PdfBlock Heading(int level, std::string text) {
  PdfBlock b;
  b.kind = PdfBlockKind::kHeading;
  b.level = level;
  b.text = std::move(text);
  return b;
}

PdfBlock Paragraph(std::string text, double size_pt, bool bold, bool alert, bool good) {
  PdfBlock b;
  b.text = std::move(text);
  b.size_pt = size_pt;
  b.bold = bold;
  b.alert = alert;
  b.good = good;
  return b;
}

PdfBlock Bullet(std::string text) {
  PdfBlock b = Paragraph(std::move(text));
  b.bullet = true;
  return b;
}

PdfBlock TableBlock(std::string title, PdfTable table) {
  PdfBlock b;
  b.kind = PdfBlockKind::kTable;
  b.text = std::move(title);
  b.table = std::move(table);
  return b;
}

PdfBlock Figure(std::string svg_file, std::string caption) {
  PdfBlock b;
  b.kind = PdfBlockKind::kFigure;
  b.svg_file = std::move(svg_file);
  b.text = std::move(caption);
  return b;
}

PdfBlock Contents() {
  PdfBlock b;
  b.kind = PdfBlockKind::kContents;
  return b;
}

PdfBlock PageBreak(double unless_room_pt) {
  PdfBlock b;
  b.kind = PdfBlockKind::kPageBreak;
  b.unless_room_pt = unless_room_pt;
  return b;
}

namespace {

constexpr double kTextWidthPt = kPageWidthPt - 2.0 * kMarginPt;
constexpr double kFooterPt = 9.0;                                       // footer text height
constexpr double kBodyBottomPt = kPageHeightPt - kMarginPt - kFooterPt - 8.0;  // body stays above the footer
constexpr double kCellPadPt = 3.5, kRowPadPt = 2.0;
constexpr double kTableFontPt = 8.0, kSmallestTableFontPt = 5.5, kBoxInsetPt = 6.0;
constexpr double kLongestWordPt = 75.0;  // a longer word may break inside a narrow column
// A figure that does not fit below the cursor at the text width but would
// at this fraction of it or more is set that much smaller (centred) rather
// than moved to the next page, leaving the rest of this one empty.
constexpr double kMinFigureScale = 0.85;
// Contents of up to this many lines are kept whole on one page.
constexpr std::size_t kWholeContentsLines = 30;
// A bulleted list up to this height is kept whole on one page, with its heading.
constexpr double kShortListPt = 220.0;
const char* const kInk = "#1a1a1a";
const char* const kAlert = "#c00000";
const char* const kGood = "#1b7837";  // a met requirement
const char* const kGrey = "#707070";

void SetColour(cairo_t* cr, const std::string& hex) {
  unsigned r = 0, g = 0, b = 0;
  std::sscanf(hex.c_str(), "#%02x%02x%02x", &r, &g, &b);
  cairo_set_source_rgb(cr, r / 255.0, g / 255.0, b / 255.0);
}

cairo_status_t Discard(void*, const unsigned char*, unsigned int) { return CAIRO_STATUS_SUCCESS; }

struct LayoutDeleter {
  void operator()(PangoLayout* l) const { g_object_unref(l); }
};
using Layout = std::unique_ptr<PangoLayout, LayoutDeleter>;

// Each figure's SVG, parsed once for both passes.
class SvgCache {
 public:
  const SvgFigure& Get(const std::string& file) {
    auto it = svgs_.find(file);
    if (it == svgs_.end()) it = svgs_.emplace(file, std::make_unique<SvgFigure>(file)).first;
    return *it->second;
  }

 private:
  std::map<std::string, std::unique_ptr<SvgFigure>> svgs_;
};

// Where a heading landed in the first pass: the target of its bookmark and
// of its line in the table of contents.
struct Target {
  int page = 0;
  double y_pt = 0;
};

// One pass over the blocks onto `surface`. The first pass (`draw` false)
// only measures; the second knows every heading's page and the page count.
class Composer {
 public:
  Composer(const PdfDocumentSpec& spec, cairo_surface_t* surface, bool draw, SvgCache* svgs,
           std::vector<Target> targets, int total_pages)
      : spec_(spec), surface_(surface), cr_(cairo_create(surface)), draw_(draw), svgs_(svgs),
        targets_(std::move(targets)), total_pages_(total_pages) {}
  Composer(const Composer&) = delete;
  Composer& operator=(const Composer&) = delete;
  ~Composer() { cairo_destroy(cr_); }

  PdfLayout Run() {
    for (std::size_t i = 0; i < spec_.blocks.size(); ++i) {
      const PdfBlock& b = spec_.blocks[i];
      switch (b.kind) {
        case PdfBlockKind::kHeading:
          DoHeading(b, KeepAfterHeading(i));
          break;
        case PdfBlockKind::kParagraph: DoParagraph(b, KeepAfterItem(i)); break;
        case PdfBlockKind::kTable: DoTable(b); break;
        case PdfBlockKind::kFigure: DoFigure(b, i + 1 < spec_.blocks.size() ? &spec_.blocks[i + 1] : nullptr); break;
        case PdfBlockKind::kContents: DoContents(); break;
        case PdfBlockKind::kPageBreak:
          if (y_ > kMarginPt && (b.unless_room_pt <= 0.0 || kBodyBottomPt - y_ < b.unless_room_pt)) NewPage();
          break;
      }
    }
    EndPage();
    layout_.pages = page_;
    return layout_;
  }
  const std::vector<Target>& HeadingTargets() const { return found_; }

 private:
  Layout MakeLayout(const std::string& text, double size_pt, bool bold, double width_pt, bool italic = false) {
    Layout l(pango_cairo_create_layout(cr_));
    PangoFontDescription* font = pango_font_description_from_string(spec_.font.c_str());
    pango_font_description_set_absolute_size(font, size_pt * PANGO_SCALE);
    if (bold) pango_font_description_set_weight(font, PANGO_WEIGHT_BOLD);
    if (italic) pango_font_description_set_style(font, PANGO_STYLE_ITALIC);
    pango_layout_set_font_description(l.get(), font);
    pango_font_description_free(font);
    if (width_pt > 0) {
      pango_layout_set_width(l.get(), static_cast<int>(width_pt * PANGO_SCALE));
      pango_layout_set_wrap(l.get(), PANGO_WRAP_WORD_CHAR);
    }
    const std::string kept = NumbersKeptWithUnits(TypesetExponents(text));
    pango_layout_set_text(l.get(), kept.c_str(), -1);
    if (width_pt > 0) KeepBracketsWhole(l.get(), kept);
    return l;
  }
  // A bracket without a space inside, "[N/(mm/s)]" or "(-h)", is not broken
  // at its '/' or '-' (a unit split as "[N/(mm/" "s)]" in sweep.pdf's header).
  static void KeepBracketsWhole(PangoLayout* l, const std::string& text) {
    PangoAttrList* attrs = nullptr;
    for (std::size_t i = 0; i < text.size(); ++i) {
      if (text[i] != '(' && text[i] != '[') continue;
      int depth = 0;
      std::size_t end = i;
      for (; end < text.size() && text[end] != ' '; ++end) {
        if (text[end] == '(' || text[end] == '[') ++depth;
        if ((text[end] == ')' || text[end] == ']') && --depth == 0) break;
      }
      if (end >= text.size() || text[end] == ' ') continue;  // no closing bracket before a space
      if (!attrs) attrs = pango_attr_list_new();
      PangoAttribute* a = pango_attr_allow_breaks_new(FALSE);
      a->start_index = static_cast<guint>(i);
      a->end_index = static_cast<guint>(end + 1);
      pango_attr_list_insert(attrs, a);
      i = end;
    }
    if (!attrs) return;
    pango_layout_set_attributes(l, attrs);
    pango_attr_list_unref(attrs);
  }
  static std::pair<double, double> Size(PangoLayout* l) {
    int w = 0, h = 0;
    pango_layout_get_size(l, &w, &h);
    return {static_cast<double>(w) / PANGO_SCALE, static_cast<double>(h) / PANGO_SCALE};
  }
  void Show(PangoLayout* l, double x, double y, const std::string& colour) {
    if (!draw_) return;
    cairo_move_to(cr_, x, y);
    SetColour(cr_, colour);
    pango_cairo_show_layout(cr_, l);
  }
  void Place(const std::string& what, const std::string& text, double x, double y, double w, double h,
             const std::string& colour = "") {
    layout_.boxes.push_back({page_, what, text, x, y, w, h, colour});
  }
  void Rule(double x0, double x1, double y, double width, const char* colour) {
    if (!draw_) return;
    SetColour(cr_, colour);
    cairo_set_line_width(cr_, width);
    cairo_move_to(cr_, x0, y);
    cairo_line_to(cr_, x1, y);
    cairo_stroke(cr_);
  }

  void EndPage() {
    const std::string number = "page " + std::to_string(page_) + "/" + std::to_string(total_pages_);
    const double y = kPageHeightPt - kMarginPt - kFooterPt;
    Layout left = MakeLayout(spec_.footer, 7.0, false, kTextWidthPt * 0.8);
    Layout right = MakeLayout(number, 7.0, false, 0);
    const double right_w = Size(right.get()).first;
    Rule(kMarginPt, kPageWidthPt - kMarginPt, y - 3.0, 0.4, "#b0b0b0");
    Show(left.get(), kMarginPt, y, kGrey);
    Show(right.get(), kPageWidthPt - kMarginPt - right_w, y, kGrey);
    Place("footer", spec_.footer + " · " + number, kMarginPt, y, kTextWidthPt, kFooterPt, kGrey);
    cairo_show_page(cr_);
  }
  void NewPage() {
    EndPage();
    ++page_;
    y_ = kMarginPt;
  }
  // Starts a new page unless `height` fits below the cursor.
  void Need(double height) {
    if (y_ + height > kBodyBottomPt && y_ > kMarginPt) NewPage();
  }

  // The height of what must follow a heading on its page: a figure with its
  // caption, a table's title and first rows, a paragraph.
  // What heading i keeps on its page: the start of the block after it, and
  // where that is a short paragraph (a line saying what follows, such as a
  // nominal value) the start of the block after that too, so that a
  // heading and its one line are never all of a page's bottom.
  double KeepAfterHeading(std::size_t i) {
    const auto& blocks = spec_.blocks;
    if (i + 1 >= blocks.size()) return 0.0;
    // A short list goes whole with its heading.
    if (const std::optional<double> list = ShortListHeight(i + 1)) return *list;
    double keep = StartHeight(blocks[i + 1]);
    if (blocks[i + 1].kind == PdfBlockKind::kParagraph && keep < 40.0 && i + 2 < blocks.size() &&
        blocks[i + 2].kind != PdfBlockKind::kHeading && blocks[i + 2].kind != PdfBlockKind::kPageBreak)
      keep += 6.0 + StartHeight(blocks[i + 2]);
    return keep;
  }

  bool IsItem(std::size_t k) const {
    return k < spec_.blocks.size() && spec_.blocks[k].kind == PdfBlockKind::kParagraph && spec_.blocks[k].bullet;
  }
  // The height of the list starting at item i, if it is short enough to be
  // kept whole on a page (kShortListPt: a report's Conventions), else none.
  std::optional<double> ShortListHeight(std::size_t i) {
    if (!IsItem(i) || (i > 0 && IsItem(i - 1))) return std::nullopt;
    double h = 0.0;
    for (std::size_t k = i; IsItem(k); ++k) {
      h += StartHeight(spec_.blocks[k]) + 0.45 * spec_.blocks[k].size_pt;
      if (h > kShortListPt) return std::nullopt;
    }
    return h;
  }
  // What list item i keeps on its page: the rest of a short list from its
  // first item (a page holding the last two Conventions bullets alone read
  // as an afterthought); in a longer one, the list's last item where that
  // comes next, so that it never stands alone at the top of a page.
  double KeepAfterItem(std::size_t i) {
    if (!IsItem(i)) return 0.0;
    if (const std::optional<double> whole = ShortListHeight(i))
      return *whole - StartHeight(spec_.blocks[i]) - 0.45 * spec_.blocks[i].size_pt;
    if (!IsItem(i + 1) || IsItem(i + 2)) return 0.0;
    return 0.45 * spec_.blocks[i].size_pt + StartHeight(spec_.blocks[i + 1]);
  }

  double StartHeight(const PdfBlock& b) {
    switch (b.kind) {
      case PdfBlockKind::kFigure: {
        const double aspect = Aspect(b);
        const double shortest = b.min_height_px > 0 ? std::min(aspect, b.min_height_px / CanvasWidth(b)) : aspect;
        return 6.0 + kTextWidthPt * std::min(kMinFigureScale * aspect, shortest) + 30.0;
      }
      case PdfBlockKind::kParagraph: {
        Layout l = MakeLayout(b.text, b.size_pt, b.bold, kTextWidthPt);
        return Size(l.get()).second;
      }
      case PdfBlockKind::kTable: {
        // As DoTable starts it: all of a short table (a third of a page),
        // else its first two rows; rows of one line (about 13 pt) assumed,
        // with the title and the header.
        const double whole = 13.0 * static_cast<double>(b.table.rows.size());
        const double first = whole <= (kBodyBottomPt - kMarginPt) / 3.0 ? whole : 26.0;
        return 40.0 + first;
      }
      case PdfBlockKind::kContents: {
        // As DoContents keeps it: whole up to kWholeContentsLines lines (its
        // heading goes along: wafer_stage's stood alone at a page's foot).
        const std::size_t sections = ListedSections();
        Layout line = MakeLayout("Contents", 10.0, true, 0);
        const double h = Size(line.get()).second + 5.0;
        return sections <= kWholeContentsLines ? static_cast<double>(sections) * h : 2.0 * h;
      }
      default: return 80.0;
    }
  }

  void DoHeading(const PdfBlock& b, double keep_pt) {
    const double size = b.level <= 0 ? 20.0 : b.level == 1 ? 14.0 : 11.0;
    Layout l = MakeLayout(b.text, size, true, kTextWidthPt);
    const double h = Size(l.get()).second;
    if (y_ > kMarginPt) y_ += b.level <= 1 ? 10.0 : 6.0;
    // A heading stays with what follows it (up to 480 pt: a tall figure at
    // its smallest scale; 300 left sensitivity.pdf's tornado charts behind).
    Need(h + 10.0 + std::min(keep_pt, 480.0));
    Show(l.get(), kMarginPt, y_, kInk);
    Place("heading", b.text, kMarginPt, y_, kTextWidthPt, h, kInk);
    if (b.level >= 1) {
      layout_.outline.push_back({b.level, b.text, page_});
      found_.push_back({page_, y_});
      if (draw_) {
        const std::size_t k = found_.size() - 1;
        const int parent = b.level >= 2 && last_section_id_ > 0 ? last_section_id_ : CAIRO_PDF_OUTLINE_ROOT;
        const int id = cairo_pdf_surface_add_outline(surface_, parent, b.text.c_str(), Link(targets_[k]).c_str(),
                                                     static_cast<cairo_pdf_outline_flags_t>(0));
        if (b.level == 1) last_section_id_ = id;
      }
    }
    y_ += h + 4.0;
    if (b.level == 1) {
      Rule(kMarginPt, kPageWidthPt - kMarginPt, y_, 0.6, "#909090");
      y_ += 5.0;
    }
  }
  // The first pass's target of the first heading (level >= 1) reading `text`.
  const Target* HeadingTarget(const std::string& text) const {
    std::size_t k = 0;
    for (const PdfBlock& b : spec_.blocks) {
      if (b.kind != PdfBlockKind::kHeading || b.level < 1) continue;
      if (b.text == text) return k < targets_.size() ? &targets_[k] : nullptr;
      ++k;
    }
    return nullptr;
  }
  static std::string Link(const Target& t) {
    char text[80];
    std::snprintf(text, sizeof(text), "page=%d pos=[%.1f %.1f]", t.page, kMarginPt, std::max(0.0, t.y_pt - 6.0));
    return text;
  }

  void DoParagraph(const PdfBlock& b, double keep_pt) {
    // A bullet hangs left of its item's lines.
    const double indent = b.bullet ? 1.2 * b.size_pt : 0.0;
    const std::string text = b.bullet ? "•\t" + b.text : b.text;
    Layout l = MakeLayout(text, b.size_pt, b.bold, kTextWidthPt - indent);
    if (b.bullet) {
      pango_layout_set_indent(l.get(), static_cast<int>(-indent * PANGO_SCALE));
      PangoTabArray* tabs = pango_tab_array_new_with_positions(1, FALSE, PANGO_TAB_LEFT,
                                                               static_cast<int>(indent * PANGO_SCALE));
      pango_layout_set_tabs(l.get(), tabs);
      pango_tab_array_free(tabs);
    }
    const double h = Size(l.get()).second;
    Need(h + keep_pt);
    const std::string colour = b.alert ? kAlert : b.good ? kGood : kInk;
    Show(l.get(), kMarginPt + indent, y_, colour);
    Place("paragraph", text, kMarginPt, y_, kTextWidthPt, h, colour);
    y_ += h + 0.45 * b.size_pt;
  }

  // A figure's canvas: planned (width_px, height_px) or its SVG's.
  double CanvasWidth(const PdfBlock& b) {
    return b.width_px > 0 ? b.width_px : svgs_->Get(b.svg_file).width();
  }
  double Aspect(const PdfBlock& b) {
    if (b.width_px > 0 && b.height_px > 0) return static_cast<double>(b.height_px) / b.width_px;
    const SvgFigure& svg = svgs_->Get(b.svg_file);
    return svg.height() / svg.width();
  }

  // The height of figure block b's caption, numbered `number`.
  double CaptionHeight(const PdfBlock& b, int number) {
    Layout cap = MakeLayout("Figure " + std::to_string(number) + ". " + b.text, 8.5, false, kTextWidthPt, true);
    return Size(cap.get()).second;
  }

  // Figure `b` then figure `next` (both free to be drawn shorter): the
  // fraction of their heights at which both fit below the cursor, where
  // `b` fits whole but `next` would not fit after it, even at its least
  // height, and so would leave the rest of this page empty; none otherwise.
  std::optional<double> SharedScale(const PdfBlock& b, double cap_h, const PdfBlock* next) {
    if (!next || next->kind != PdfBlockKind::kFigure || b.min_height_px <= 0 || next->min_height_px <= 0)
      return std::nullopt;
    const double h = kTextWidthPt * Aspect(b), h_next = kTextWidthPt * Aspect(*next);
    const double cap_next = CaptionHeight(*next, figures_ + 1);
    const double room = kBodyBottomPt - y_;
    const double below_b = room - (h + 4.0 + cap_h + 10.0 + 6.0 + 4.0 + cap_next);
    const double least_next = h_next * next->min_height_px / next->height_px;
    if (h + 4.0 + cap_h > room || below_b >= least_next) return std::nullopt;
    const double scale = (room - (4.0 + cap_h + 10.0 + 6.0 + 4.0 + cap_next)) / (h + h_next);
    const double least = std::max(static_cast<double>(b.min_height_px) / b.height_px,
                                  static_cast<double>(next->min_height_px) / next->height_px);
    if (scale < least) return std::nullopt;
    return std::min(1.0, scale);
  }

  void DoFigure(const PdfBlock& b, const PdfBlock* next) {
    double w = kTextWidthPt, h = w * Aspect(b);
    ++figures_;
    const std::string caption = "Figure " + std::to_string(figures_) + ". " + b.text;
    Layout cap = MakeLayout(caption, 8.5, false, kTextWidthPt, true);
    const double cap_h = Size(cap.get()).second;
    if (y_ > kMarginPt) y_ += 6.0;
    const double px_per_pt = CanvasWidth(b) / kTextWidthPt;
    const std::optional<double> shared = y_ > kMarginPt ? SharedScale(b, cap_h, next) : std::nullopt;
    if (scale_next_) {
      // The second of two figures set shorter together.
      h = std::floor(*scale_next_ * h * px_per_pt) / px_per_pt;
      scale_next_.reset();
    } else if (shared) {
      h = std::floor(*shared * h * px_per_pt) / px_per_pt;
      scale_next_ = shared;
    } else if (const double room = kBodyBottomPt - y_ - 4.0 - cap_h; y_ > kMarginPt && h > room) {
      // Drawn shorter across the whole width where the caller allows it,
      // else smaller, centred, down to kMinFigureScale.
      if (b.min_height_px > 0 && room * px_per_pt >= b.min_height_px) {
        h = std::floor(room * px_per_pt) / px_per_pt;
      } else if (room >= kMinFigureScale * h) {
        w *= room / h;
        h = room;
      }
    }
    Need(h + 4.0 + cap_h);
    const double x = kMarginPt + 0.5 * (kTextWidthPt - w);
    if (draw_) svgs_->Get(b.svg_file).Draw(cr_, x, y_, w, h);
    Place("figure", b.svg_file, x, y_, w, h);
    y_ += h + 4.0;
    Show(cap.get(), kMarginPt, y_, kInk);
    Place("caption", caption, kMarginPt, y_, kTextWidthPt, cap_h, kInk);
    y_ += cap_h + 10.0;
  }

  // Whether `heading` is the contents' own (the block after it): not listed in them.
  bool HeadsContents(const PdfBlock& heading) const {
    const PdfBlock* next = &heading + 1;
    return next < spec_.blocks.data() + spec_.blocks.size() && next->kind == PdfBlockKind::kContents;
  }
  // The sections the contents list: level-1 headings but the contents' own.
  std::size_t ListedSections() const {
    std::size_t n = 0;
    for (const PdfBlock& b : spec_.blocks) n += b.kind == PdfBlockKind::kHeading && b.level == 1 && !HeadsContents(b);
    return n;
  }

  void DoContents() {
    // One line per section (level-1 heading) of the document, linked to it;
    // subsections are in the PDF's bookmarks. The first pass lays out the
    // same lines with its own (placeholder) page numbers.
    std::vector<const PdfBlock*> headings;
    for (const PdfBlock& b : spec_.blocks)
      if (b.kind == PdfBlockKind::kHeading && b.level >= 1) headings.push_back(&b);
    const std::size_t sections = ListedSections();
    std::size_t listed = 0;
    for (std::size_t k = 0; k < headings.size(); ++k) {
      const PdfBlock& b = *headings[k];
      if (b.level >= 2 || HeadsContents(b)) continue;
      ++listed;
      const double indent = b.level >= 2 ? 14.0 : 0.0, size = b.level >= 2 ? 9.0 : 10.0;
      const Target t = k < targets_.size() ? targets_[k] : Target{};
      Layout number = MakeLayout(std::to_string(t.page), size, b.level == 1, 0);
      const double number_w = Size(number.get()).first;
      Layout text = MakeLayout(b.text, size, b.level == 1, kTextWidthPt - indent - 40.0);
      const double h = Size(text.get()).second;
      // Up to 30 lines the contents stay whole on one page (wafer_stage's
      // last two stood at the top of page 2); a longer one never leaves its
      // last line alone: the one before it takes it along.
      if (listed == 1 && sections <= kWholeContentsLines)
        Need(static_cast<double>(sections) * (h + 5.0));  // each line: 3 pt above, 2 below
      else
        Need(listed + 1 == sections ? 2.0 * (h + 3.0) : h);
      if (b.level == 1) y_ += 3.0;
      if (draw_) cairo_tag_begin(cr_, CAIRO_TAG_LINK, Link(t).c_str());
      Show(text.get(), kMarginPt + indent, y_, kInk);
      Show(number.get(), kPageWidthPt - kMarginPt - number_w, y_, kInk);
      if (draw_) {  // dotted leader from the title's last line to its page number
        PangoRectangle last{};
        pango_layout_get_pixel_extents(text.get(), nullptr, &last);
        const double from = kMarginPt + indent + last.x + last.width + 4.0;
        const double to = kPageWidthPt - kMarginPt - number_w - 4.0;
        const double baseline = y_ + Size(text.get()).second - 0.3 * size;
        if (to > from) {
          const double dots[] = {0.6, 2.4};
          cairo_save(cr_);
          cairo_set_dash(cr_, dots, 2, 0.0);
          cairo_set_line_cap(cr_, CAIRO_LINE_CAP_ROUND);
          Rule(from, to, baseline, 0.8, "#909090");
          cairo_restore(cr_);
        }
      }
      if (draw_) cairo_tag_end(cr_, CAIRO_TAG_LINK);
      Place("contents", b.text + " ... " + std::to_string(t.page), kMarginPt + indent, y_, kTextWidthPt - indent, h,
            kInk);
      y_ += h + 2.0;
    }
  }

  // ---- tables ----
  struct Split {
    std::string left, right;  // a number cut at its decimal point
  };
  static Split AtDecimalPoint(const std::string& s) {
    for (std::size_t i = 1; i < s.size(); ++i)
      if (s[i] == '.' && s[i - 1] >= '0' && s[i - 1] <= '9') return {s.substr(0, i), s.substr(i)};
    // No decimal point: the integer part ends where the number's digits do.
    std::size_t end = s.find_first_of("0123456789");
    if (end == std::string::npos) return {s, ""};
    end = s.find_first_not_of("0123456789", end);
    return end == std::string::npos ? Split{s, ""} : Split{s.substr(0, end), s.substr(end)};
  }
  // The widest word of `text` (between spaces and line breaks); with
  // `identifiers`, a name's parts count as words (each up to and with its
  // underscore: BreakableNames lets a line break there).
  double LongestWord(const std::string& text, bool bold, bool identifiers = true) {
    double widest = 0.0;
    std::size_t start = 0;
    while (start <= text.size()) {
      std::size_t end = std::min(text.find(' ', start), text.find('\n', start));
      std::size_t next = end == std::string::npos ? end : end + 1;
      if (identifiers) {
        const std::size_t underscore = text.find('_', start);
        if (underscore != std::string::npos && underscore + 1 < std::min(end, text.size())) end = next = underscore + 1;
      }
      const std::size_t length = end == std::string::npos ? std::string::npos : end - start;
      widest = std::max(widest, Width(text.substr(start, length), bold));
      if (next == std::string::npos) break;
      start = next;
    }
    return widest;
  }
  // `text` as set in a cell `width` wide: where a word is wider than that, a
  // line may break after each underscore of a name (a zero-width space), so
  // that "measurement_to_position" wraps as "measurement_to_" "position", not
  // hyphenated inside a word. Text that fits is left as written.
  std::string BreakableNames(const std::string& text, bool bold, double width) {
    if (text.find('_') == std::string::npos || LongestWord(text, bold, false) <= width) return text;
    std::string out;
    for (std::size_t i = 0; i < text.size(); ++i) {
      out += text[i];
      if (text[i] == '_' && i + 1 < text.size() && text[i + 1] != ' ' && text[i + 1] != '_') out += "\u200b";
    }
    return out;
  }
  double Width(const std::string& text, bool bold) {
    if (text.empty()) return 0.0;
    Layout l = MakeLayout(text, table_font_, bold, 0);
    return Size(l.get()).first;
  }

  // A table's columns measured at table_font_: natural (one line), shortest
  // (its longest word; numbers whole), and a numeric column's widest integer
  // part (left) and fraction (right).
  struct ColumnMeasures {
    std::vector<double> natural, shortest, left, right;
  };
  static bool Numeric(const PdfTable& t, std::size_t c) { return c < t.numeric.size() && t.numeric[c]; }

  ColumnMeasures MeasureColumns(const PdfTable& t, std::size_t columns) {
    ColumnMeasures m{std::vector<double>(columns, 0.0), std::vector<double>(columns, 0.0),
                     std::vector<double>(columns, 0.0), std::vector<double>(columns, 0.0)};
    for (std::size_t c = 0; c < columns; ++c) {
      if (c < t.header.size()) {
        m.natural[c] = Width(t.header[c], true);
        m.shortest[c] = std::min(kLongestWordPt, LongestWord(t.header[c], true));
      }
      for (const auto& row : t.rows) {
        if (c >= row.size()) continue;
        if (Numeric(t, c)) {
          const Split s = AtDecimalPoint(row[c].text);
          m.left[c] = std::max(m.left[c], Width(s.left, row[c].bold));
          m.right[c] = std::max(m.right[c], Width(s.right, row[c].bold));
        } else {
          Layout l = MakeLayout(row[c].text, table_font_, row[c].bold, 0);
          m.natural[c] = std::max(m.natural[c], Size(l.get()).first);
          m.shortest[c] = std::max(m.shortest[c], std::min(kLongestWordPt, LongestWord(row[c].text, row[c].bold)));
        }
      }
      // A numeric column: its numbers whole, its header wrapped as text is
      // (sweep.pdf's variants table was set at 5.5 pt to keep ten headers
      // such as "gamma_velocity [µrad/s]" on one line each).
      if (Numeric(t, c)) {
        m.natural[c] = std::max(m.natural[c], m.left[c] + m.right[c]);
        m.shortest[c] = std::max(m.shortest[c], m.left[c] + m.right[c]);
      }
      m.natural[c] += 2.0 * kCellPadPt;
      m.shortest[c] += 2.0 * kCellPadPt;
    }
    return m;
  }

  // Sets table_font_ and measures: columns that cannot fit `width` even
  // wrapped get a smaller font, once.
  ColumnMeasures FitFont(const PdfTable& t, std::size_t columns, double width) {
    table_font_ = kTableFontPt;
    ColumnMeasures m = MeasureColumns(t, columns);
    double least = 0.0;
    for (double w : m.shortest) least += w;
    if (least <= width) return m;
    table_font_ = std::max(kSmallestTableFontPt, 0.97 * kTableFontPt * width / least);
    return MeasureColumns(t, columns);
  }

  // Each column's width. Too wide: every column keeps its longest word
  // (numbers whole); of the rest of the width, a column that lacks less than
  // an even share takes what it lacks, and the columns that must wrap share
  // what is left in proportion to what each lacks (as browsers share a
  // table's width), so that a column of long notes is not squeezed to the
  // width of a column of names (long text wraps, never cut).
  // A column at most this wide is not narrowed to fit a table that is too
  // wide even at the smallest font.
  static constexpr double kKeptWholePt = 28.0;

  static std::vector<double> ColumnWidths(const ColumnMeasures& m, double width, bool boxed) {
    const std::size_t columns = m.natural.size();
    std::vector<double> widths = m.natural;
    double total = 0.0, least = 0.0;
    for (std::size_t c = 0; c < columns; ++c) {
      total += m.natural[c];
      least += m.shortest[c];
    }
    if (total > width) {
      widths = m.shortest;
      double spare = std::max(0.0, width - least);
      std::vector<std::size_t> open;
      for (std::size_t c = 0; c < columns; ++c)
        if (m.natural[c] > m.shortest[c]) open.push_back(c);
      // A column that lacks less than an even share takes only that and stays on one line.
      while (!open.empty() && spare > 1e-9) {
        const double share = spare / static_cast<double>(open.size());
        std::vector<std::size_t> still;
        for (std::size_t c : open)
          if (m.natural[c] - widths[c] <= share) {
            spare -= m.natural[c] - widths[c];
            widths[c] = m.natural[c];
          } else {
            still.push_back(c);
          }
        if (still.size() == open.size()) {  // the rest wrap: shared in proportion to what each lacks
          double lacking = 0.0;
          for (std::size_t c : still) lacking += m.natural[c] - widths[c];
          for (std::size_t c : still) widths[c] += spare * (m.natural[c] - widths[c]) / lacking;
          break;
        }
        open = std::move(still);
      }
    }
    // Still too wide at the smallest font: the wide columns narrower, in
    // proportion to their width beyond kKeptWholePt (text wraps inside them;
    // a long number may reach into its neighbour), so that a narrow column,
    // a rank or a short name, keeps its header whole; if that is not enough,
    // every column narrower alike.
    if (least > width) {
      double reducible = 0.0;
      for (double w : widths) reducible += std::max(0.0, w - kKeptWholePt);
      const double excess = least - width;
      if (reducible >= excess) {
        for (double& w : widths) w -= excess * std::max(0.0, w - kKeptWholePt) / reducible;
      } else {
        for (double& w : widths) w *= width / least;
      }
    }
    if (boxed) {  // a box spans the text width: its last column takes what is left
      double used = 0.0;
      for (double w : widths) used += w;
      if (used < width) widths.back() += width - used;
    }
    return widths;
  }

  // A table being set: its block, its columns and where its box began.
  struct TableRun {
    const PdfBlock& block;
    std::size_t columns;
    std::vector<double> widths, right;  // right: a numeric column's widest fraction
    double inset, x0, table_width;
    double box_top = 0.0;
    std::vector<PdfCell> header_cells;
  };

  // A row's cell layouts and its height.
  std::pair<std::vector<Layout>, double> RowLayouts(const TableRun& run, const std::vector<PdfCell>& cells,
                                                    bool header) {
    std::vector<Layout> ls;
    double h = 0.0;
    for (std::size_t c = 0; c < run.columns; ++c) {
      const PdfCell cell = c < cells.size() ? cells[c] : PdfCell{};
      const bool split = Numeric(run.block.table, c) && !header;
      const double width = run.widths[c] - 2 * kCellPadPt;
      ls.push_back(split ? MakeLayout(cell.text, table_font_, cell.bold || header, 0)
                         : MakeLayout(BreakableNames(cell.text, cell.bold || header, width), table_font_,
                                      cell.bold || header, width));
      // A numeric column's header, wrapped or not, ends where its numbers do.
      if (header && Numeric(run.block.table, c)) pango_layout_set_alignment(ls.back().get(), PANGO_ALIGN_RIGHT);
      h = std::max(h, Size(ls.back().get()).second);
    }
    return std::make_pair(std::move(ls), h + 2.0 * kRowPadPt);
  }
  double RowHeight(const TableRun& run, const std::vector<PdfCell>& cells, bool header) {
    return RowLayouts(run, cells, header).second;
  }

  void CloseBox(const TableRun& run) {
    if (!run.block.table.boxed) return;
    y_ += run.inset;
    if (draw_) {
      SetColour(cr_, "#606060");
      cairo_set_line_width(cr_, 0.8);
      cairo_rectangle(cr_, kMarginPt, run.box_top, kTextWidthPt, y_ - run.box_top);
      cairo_stroke(cr_);
    }
    Place("box", run.block.text, kMarginPt, run.box_top, kTextWidthPt, y_ - run.box_top);
  }

  // One cell's text: numbers aligned at their decimal point (the text right
  // of it may stick out) or right-aligned, other text left-aligned. Returns
  // the decimal point's x (0 where not split).
  double ShowCell(const TableRun& run, std::size_t c, const PdfCell& cell, PangoLayout* layout, bool header, double x,
                  const std::string& colour) {
    if (Numeric(run.block.table, c) && !header) {
      const Split s = AtDecimalPoint(cell.text);
      const double point_x = x + run.widths[c] - kCellPadPt - run.right[c];
      Layout l = MakeLayout(s.left, table_font_, cell.bold, 0);
      Layout r = MakeLayout(s.right, table_font_, cell.bold, 0);
      Show(l.get(), point_x - Size(l.get()).first, y_ + kRowPadPt, colour);
      Show(r.get(), point_x, y_ + kRowPadPt, colour);
      return point_x;
    }
    Show(layout, x + kCellPadPt, y_ + kRowPadPt, colour);  // a numeric header: right-aligned in its layout
    return 0.0;
  }

  void DrawRow(const TableRun& run, const std::vector<PdfCell>& cells, bool header) {
    auto [ls, h] = RowLayouts(run, cells, header);
    double x = run.x0;
    std::string joined;
    for (std::size_t c = 0; c < run.columns; ++c) {
      const PdfCell cell = c < cells.size() ? cells[c] : PdfCell{};
      const std::string colour = cell.alert ? kAlert : cell.good ? kGood : kInk;
      const double point_x = ShowCell(run, c, cell, ls[c].get(), header, x, colour);
      if (!cell.link.empty() && draw_) {
        if (const Target* t = HeadingTarget(cell.link)) {
          char rect[120];
          std::snprintf(rect, sizeof(rect), " rect=[%.2f %.2f %.2f %.2f]", x, y_, run.widths[c], h);
          cairo_tag_begin(cr_, CAIRO_TAG_LINK, (Link(*t) + rect).c_str());
          cairo_tag_end(cr_, CAIRO_TAG_LINK);
        }
      }
      layout_.boxes.push_back(
          {page_, header ? "table header" : "table cell", cell.text, x, y_, run.widths[c], h, colour, point_x});
      joined += (c ? " | " : "") + cell.text;
      x += run.widths[c];
    }
    Place(header ? "table header row" : "table row", joined, run.x0, y_, run.table_width, h);
    y_ += h;
    Rule(run.x0, run.x0 + run.table_width, y_, header ? 0.7 : 0.3, header ? "#404040" : "#c8c8c8");
  }

  // A boxed table's shade goes under its rows: measured first, drawn before them.
  void ShadeBox(const TableRun& run, double header_h) {
    double h = header_h;
    for (const auto& row : run.block.table.rows) h += RowHeight(run, row, false);
    if (y_ + h + run.inset <= kBodyBottomPt) {
      SetColour(cr_, "#f3f3f3");
      cairo_rectangle(cr_, kMarginPt, run.box_top, kTextWidthPt, h + 2.0 * run.inset);
      cairo_fill(cr_);
    }
  }

  void Footnotes(const std::vector<std::string>& notes) {
    for (const std::string& note : notes) {
      Layout l = MakeLayout(note, 7.5, false, kTextWidthPt);
      const double h = Size(l.get()).second;
      Need(h);
      Show(l.get(), kMarginPt, y_, kInk);
      Place("footnote", note, kMarginPt, y_, kTextWidthPt, h, kInk);
      y_ += h + 1.5;
    }
  }

  void DoTable(const PdfBlock& b) {
    const PdfTable& t = b.table;
    std::size_t columns = t.header.size();
    for (const auto& row : t.rows) columns = std::max(columns, row.size());
    if (columns == 0) return;
    const double inset = t.boxed ? kBoxInsetPt : 0.0, width = kTextWidthPt - 2.0 * inset;
    const ColumnMeasures m = FitFont(t, columns, width);
    TableRun run{b, columns, ColumnWidths(m, width, t.boxed), m.right, inset, kMarginPt + inset, 0.0, 0.0, {}};
    for (double w : run.widths) run.table_width += w;
    for (const std::string& h : t.header) run.header_cells.push_back({h, true, false});

    Layout title = MakeLayout(b.text, 9.5, true, kTextWidthPt);
    const double title_h = b.text.empty() ? 0.0 : Size(title.get()).second;
    const double header_h = t.header.empty() ? 0.0 : RowHeight(run, run.header_cells, true);
    std::vector<double> row_h;
    for (const auto& row : t.rows) row_h.push_back(RowHeight(run, row, false));
    // A table starts where at least its first two rows fit; a short one
    // (at most a third of a page) where all of it does.
    double whole = 0.0;
    for (double h : row_h) whole += h;
    const double first_rows = whole <= (kBodyBottomPt - kMarginPt) / 3.0 ? whole
                              : row_h.size() >= 2                        ? row_h[0] + row_h[1]
                              : row_h.empty()                            ? 0.0
                                                                         : row_h[0];
    if (y_ > kMarginPt) y_ += 4.0;
    Need(title_h + 4.0 + header_h + first_rows + 2.0 * inset);
    if (!b.text.empty()) {
      Show(title.get(), kMarginPt, y_, kInk);
      Place("table title", b.text, kMarginPt, y_, kTextWidthPt, title_h, kInk);
      y_ += title_h + 3.0;
    }
    run.box_top = y_;
    y_ += inset;
    if (t.boxed && draw_) ShadeBox(run, header_h);
    if (!t.header.empty()) DrawRow(run, run.header_cells, true);
    std::size_t on_page = 0;  // rows drawn on this page
    for (std::size_t r = 0; r < t.rows.size(); ++r) {
      const auto& row = t.rows[r];
      // A break before the last two rows rather than before the last one:
      // no row alone on a page.
      const bool last_alone = r + 2 == t.rows.size() && on_page >= 2 &&
                              y_ + row_h[r] + row_h[r + 1] + inset > kBodyBottomPt;
      if (y_ + row_h[r] + inset > kBodyBottomPt || last_alone) {
        on_page = 0;
        CloseBox(run);
        NewPage();
        run.box_top = y_;
        y_ += inset;
        if (!t.header.empty()) DrawRow(run, run.header_cells, true);
      }
      DrawRow(run, row, false);
      ++on_page;
    }
    CloseBox(run);
    y_ += 3.0;
    Footnotes(t.footnotes);
    y_ += 6.0;
  }

  const PdfDocumentSpec& spec_;
  cairo_surface_t* surface_;
  cairo_t* cr_;
  bool draw_;
  SvgCache* svgs_;
  std::vector<Target> targets_, found_;
  int total_pages_;
  int page_ = 1, figures_ = 0, last_section_id_ = 0;
  std::optional<double> scale_next_;  // the next figure's share of a SharedScale
  double table_font_ = kTableFontPt;  // of the table being set
  double y_ = kMarginPt;
  PdfLayout layout_;
};

void SetMetadata(cairo_surface_t* surface, const PdfDocumentSpec& spec) {
  cairo_pdf_surface_set_metadata(surface, CAIRO_PDF_METADATA_TITLE, spec.title.c_str());
  cairo_pdf_surface_set_metadata(surface, CAIRO_PDF_METADATA_SUBJECT, spec.subject.c_str());
  if (!spec.create_date.empty()) {
    cairo_pdf_surface_set_metadata(surface, CAIRO_PDF_METADATA_CREATE_DATE, spec.create_date.c_str());
    cairo_pdf_surface_set_metadata(surface, CAIRO_PDF_METADATA_MOD_DATE, spec.create_date.c_str());
  }
}

}  // namespace

std::vector<int> FittedFigureHeightsPx(const PdfDocumentSpec& spec, const PdfLayout& layout) {
  std::vector<const PdfBlock*> figures;
  for (const PdfBlock& b : spec.blocks)
    if (b.kind == PdfBlockKind::kFigure) figures.push_back(&b);
  std::vector<int> heights;
  for (const PlacedBox& box : layout.boxes) {
    if (box.what != "figure") continue;
    DEB_DEMAND(heights.size() < figures.size());
    const PdfBlock& b = *figures[heights.size()];
    DEB_DEMAND(b.width_px > 0 && b.height_px > 0);
    // The placed height in px of the canvas, as DoFigure floored it; the
    // 1e-6 absorbs the round trip through points.
    const int placed = static_cast<int>(std::floor(box.height_pt * b.width_px / box.width_pt + 1e-6));
    heights.push_back(std::min(b.height_px, placed));
  }
  DEB_DEMAND(heights.size() == figures.size());
  return heights;
}

PdfLayout PlanPdfDocument(const PdfDocumentSpec& spec) {
  const std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> scratch(
      cairo_pdf_surface_create_for_stream(Discard, nullptr, kPageWidthPt, kPageHeightPt), &cairo_surface_destroy);
  SvgCache svgs;
  Composer measure(spec, scratch.get(), false, &svgs, {}, 0);
  return measure.Run();
}

PdfLayout WritePdfDocument(const PdfDocumentSpec& spec, const std::string& path) {
  struct SurfaceDeleter {
    void operator()(cairo_surface_t* s) const { cairo_surface_destroy(s); }
  };
  using Surface = std::unique_ptr<cairo_surface_t, SurfaceDeleter>;
  const auto scratch = [] {
    return Surface(cairo_pdf_surface_create_for_stream(Discard, nullptr, kPageWidthPt, kPageHeightPt));
  };
  SvgCache svgs;
  // First pass: where every heading lands and how many pages there are.
  std::vector<Target> targets;
  PdfLayout first;
  {
    const Surface measured = scratch();
    Composer measure(spec, measured.get(), false, &svgs, {}, 0);
    first = measure.Run();
    targets = measure.HeadingTargets();
  }
  if (path.empty()) {
    // The layout alone: the second pass's numbers without drawing.
    const Surface again = scratch();
    Composer lay(spec, again.get(), false, &svgs, targets, first.pages);
    return lay.Run();
  }
  const Surface surface(cairo_pdf_surface_create(path.c_str(), kPageWidthPt, kPageHeightPt));
  SetMetadata(surface.get(), spec);
  PdfLayout layout;
  {
    Composer compose(spec, surface.get(), true, &svgs, targets, first.pages);
    layout = compose.Run();
  }
  cairo_surface_finish(surface.get());
  const cairo_status_t status = cairo_surface_status(surface.get());
  if (status != CAIRO_STATUS_SUCCESS)
    throw WriteError("cannot write " + path + ": " + cairo_status_to_string(status));
  DEB_DEMAND(layout.pages == first.pages);
  return layout;
}

}  // namespace deb::report
