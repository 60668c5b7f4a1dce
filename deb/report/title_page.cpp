#include "deb/report/title_page.h"

#include <sstream>

#include "deb/report/plot.h"
#include "deb/report/plot_style.h"
#include "deb/version.h"

namespace deb::report {
namespace {

constexpr double kPageHeightCm = 21.0, kPageWidthCm = 29.7;
constexpr double kTopCm = 0.9, kBottomCm = 1.3, kLeftCm = 1.6;
constexpr std::size_t kMaxLineChars = 180;  // DejaVu Sans Mono 9.5 pt across 26.5 cm

enum class Kind { kTitle, kHeading, kText, kMono, kGap };

struct Line {
  Kind kind;
  std::string text;
};

double HeightCm(Kind kind) {
  switch (kind) {
    case Kind::kTitle: return 1.25;
    case Kind::kHeading: return 0.8;
    case Kind::kText: return 0.5;
    case Kind::kMono: return 0.43;
    case Kind::kGap: return 0.3;
  }
  return 0.5;
}

std::string Font(Kind kind) {
  switch (kind) {
    case Kind::kTitle: return std::string(kFont) + " Bold,20";
    case Kind::kHeading: return std::string(kFont) + " Bold,13";
    case Kind::kText: return std::string(kFont) + ",10";
    default: return std::string(kMonoFont) + ",9.5";
  }
}

}  // namespace

std::vector<std::string> Wrap(const std::string& text, std::size_t width) {
  std::vector<std::string> lines;
  std::istringstream words(text);
  std::string word, line;
  while (words >> word) {
    if (!line.empty() && line.size() + 1 + word.size() > width) {
      lines.push_back(line);
      line.clear();
    }
    line += (line.empty() ? "" : " ") + word;
  }
  if (!line.empty()) lines.push_back(line);
  return lines;
}

std::string PageFooter(const std::string& budget_name, const std::string& digest, int page, int total_pages) {
  return "deb " + std::string(DEB_VERSION) + " · " + budget_name +
         (digest.empty() ? "" : " · SHA-256 " + digest.substr(0, 12)) + " · page " + std::to_string(page) + "/" +
         std::to_string(total_pages);
}

TitlePages MakeTitlePages(const std::string& budget_name, const std::string& description, const ReportFacts& facts,
                          const std::vector<Table>& tables, const std::vector<std::string>& warnings,
                          int following_pages, const std::string& digest) {
  // Blocks: a heading, lines repeated at the top of a continuation (a
  // table's column header), and the body.
  struct Block {
    std::vector<Line> head, repeat, body;
  };
  std::vector<Block> blocks(1);
  blocks[0].head.push_back({Kind::kTitle, "Dynamic error budget: " + budget_name});
  for (const auto& l : Wrap(description, 150)) blocks[0].head.push_back({Kind::kText, l});
  blocks[0].head.push_back({Kind::kGap, ""});
  std::size_t key_width = 0;
  for (const auto& [key, value] : facts.items) key_width = std::max(key_width, key.size());
  for (const auto& [key, value] : facts.items)
    blocks[0].body.push_back({Kind::kMono, key + std::string(key_width + 2 - key.size(), ' ') + value});
  blocks.push_back({{{Kind::kHeading, "Conventions"}}, {}, {}});
  for (const auto& c : facts.conventions) blocks.back().body.push_back({Kind::kText, c});
  for (const Table& t : tables) {
    std::vector<std::string> shortened;
    const std::vector<std::string> text = ToText(t, 30, kMaxLineChars, &shortened);
    blocks.push_back({{{Kind::kHeading, t.title}}, {{Kind::kMono, text[0]}, {Kind::kMono, text[1]}}, {}});
    for (std::size_t i = 2; i < text.size(); ++i) blocks.back().body.push_back({Kind::kMono, text[i]});
    // What the columns cut ("…"), in full below the table.
    for (const std::string& cell : shortened) {
      const auto wrapped = Wrap(cell, kMaxLineChars - 4);
      for (std::size_t i = 0; i < wrapped.size(); ++i)
        blocks.back().body.push_back({Kind::kMono, (i ? "    " : "  * ") + wrapped[i]});
    }
  }
  if (!warnings.empty()) {
    blocks.push_back({{{Kind::kHeading, "Warnings"}}, {}, {}});
    for (const auto& w : warnings) {
      const auto wrapped = Wrap(w, kMaxLineChars - 2);
      for (std::size_t i = 0; i < wrapped.size(); ++i)
        blocks.back().body.push_back({Kind::kMono, (i ? "  " : "- ") + wrapped[i]});
    }
  }

  // A block starts on a new page unless it fits in the rest of this one (or
  // would not fit on any page); a split block repeats heading and header.
  const double usable = kPageHeightCm - kTopCm - kBottomCm;
  const auto height = [](const std::vector<Line>& lines) {
    double h = 0.0;
    for (const Line& l : lines) h += HeightCm(l.kind);
    return h;
  };
  std::vector<std::vector<Line>> pages(1);
  double used = 0.0;
  const auto add = [&](const std::vector<Line>& lines) {
    pages.back().insert(pages.back().end(), lines.begin(), lines.end());
    used += height(lines);
  };
  const auto new_page = [&] {
    pages.emplace_back();
    used = 0.0;
  };
  for (const Block& b : blocks) {
    const double whole = height(b.head) + height(b.repeat) + height(b.body);
    const double start = height(b.head) + height(b.repeat) + HeightCm(Kind::kMono) * 3;
    if (!pages.back().empty() && (used + whole > usable && (whole <= usable || used + start > usable))) new_page();
    add(b.head);
    add(b.repeat);
    for (const Line& l : b.body) {
      if (used + HeightCm(l.kind) > usable) {
        new_page();
        std::vector<Line> head = b.head;
        if (!head.empty()) head[0].text += " (continued)";
        add(head);
        add(b.repeat);
      }
      add({l});
    }
  }

  std::ostringstream s;
  for (std::size_t p = 0; p < pages.size(); ++p) {
    s << "reset\nset encoding utf8\nunset border\nunset tics\nunset key\nset margins 0,0,0,0\n"
         "set xrange [0:1]\nset yrange [0:1]\n";
    double y = kTopCm;
    int n = 0;
    for (const Line& l : pages[p]) {
      y += HeightCm(l.kind);
      if (l.kind == Kind::kGap) continue;
      s << "set label " << ++n << " " << Quote(l.text) << " at screen " << CsvNumber(kLeftCm / kPageWidthCm) << ","
        << CsvNumber(1.0 - (y - 0.12) / kPageHeightCm) << " left font " << Quote(Font(l.kind))
        << " textcolor rgb '#1a1a1a' noenhanced\n";
    }
    s << "set label " << ++n << " "
      << Quote(PageFooter(budget_name, digest, static_cast<int>(p) + 1,
                          static_cast<int>(pages.size()) + following_pages))
      << " at screen " << CsvNumber(1.0 - kLeftCm / kPageWidthCm) << "," << CsvNumber(0.6 / kPageHeightCm)
      << " right font " << Quote(std::string(kFont) + ",8") << " textcolor rgb '#707070' noenhanced\n";
    s << "plot 2 notitle\n";
  }
  return {s.str(), static_cast<int>(pages.size())};
}

}  // namespace deb::report
