// The status line fitted to the window's width (fit_status_line in ui.h).
#include <algorithm>

#include "editor/ui.h"

namespace glint {
namespace {

float text_width(const std::string& text) { return ImGui::CalcTextSize(text.c_str()).x; }

float line_width(const std::vector<StatusPiece>& pieces, const std::vector<bool>& keep) {
  float w = 0;
  bool first = true;
  for (size_t i = 0; i < pieces.size(); ++i) {
    if (!keep[i]) continue;
    // The first piece shown loses its separator (leading spaces and bar).
    const std::string& t = pieces[i].text;
    w += first ? text_width(t.substr(std::min(t.size(), t.find_first_not_of(" |")))) : text_width(t);
    first = false;
  }
  return w;
}

// `text` cut to at most `width` pixels, ending in "..." (empty when not even that fits).
std::string elide(const std::string& text, float width) {
  if (text_width(text) <= width) return text;
  size_t lo = 0, hi = text.size();
  while (lo < hi) {  // the longest prefix that fits with the ellipsis
    const size_t mid = (lo + hi + 1) / 2;
    if (text_width(text.substr(0, mid) + "...") <= width) lo = mid;
    else hi = mid - 1;
  }
  return lo == 0 ? std::string() : text.substr(0, lo) + "...";
}

}  // namespace

std::vector<StatusPiece> fit_status_line(std::vector<StatusPiece> pieces, float width) {
  std::vector<bool> keep(pieces.size(), true);
  size_t kept = pieces.size();
  while (kept > 1 && line_width(pieces, keep) > width) {
    // The least important piece left goes; of equally unimportant ones, the rightmost.
    size_t worst = pieces.size();
    for (size_t i = 0; i < pieces.size(); ++i)
      if (keep[i] && pieces[i].priority > 0 && (worst == pieces.size() || pieces[i].priority >= pieces[worst].priority))
        worst = i;
    if (worst == pieces.size()) break;  // only the most important are left
    keep[worst] = false;
    --kept;
  }
  std::vector<StatusPiece> out;
  for (size_t i = 0; i < pieces.size(); ++i)
    if (keep[i]) out.push_back(std::move(pieces[i]));
  if (!out.empty()) {
    std::string& first = out.front().text;
    first.erase(0, std::min(first.size(), first.find_first_not_of(" |")));
  }
  // Still too wide (a long message): the last piece is cut short, or goes if nothing of it fits.
  while (!out.empty()) {
    const float rest = line_width(out, std::vector<bool>(out.size(), true)) - text_width(out.back().text);
    out.back().text = elide(out.back().text, std::max(0.0f, width - rest));
    if (!out.back().text.empty()) break;
    out.pop_back();
  }
  return out;
}

}  // namespace glint
