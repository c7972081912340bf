#include "world/pattern.h"

namespace lwc {

bool glob_match(std::string_view glob, std::string_view text) {
  size_t g = 0, t = 0, star = std::string_view::npos, mark = 0;
  while (t < text.size()) {
    if (g < glob.size() && (glob[g] == '?' || glob[g] == text[t])) {
      ++g, ++t;
    } else if (g < glob.size() && glob[g] == '*') {
      star = g++, mark = t;
    } else if (star != std::string_view::npos) {
      g = star + 1, t = ++mark;
    } else {
      return false;
    }
  }
  while (g < glob.size() && glob[g] == '*') ++g;
  return g == glob.size();
}

PathPattern::PathPattern(std::string_view text) : text_(text) {
  std::vector<std::string> segments(1);
  int depth = 0;
  for (char c : text) {
    if (c == '(') ++depth;
    if (c == ')') --depth;
    if (c == '.' && depth == 0) segments.emplace_back();
    else segments.back() += c;
  }
  for (const std::string& segment : segments) {
    std::vector<Alternative> alternatives;
    size_t start = 0;
    while (start <= segment.size()) {
      size_t bar = segment.find('|', start);
      if (bar == std::string::npos) bar = segment.size();
      std::string alt = segment.substr(start, bar - start);
      bool call = alt.size() > 4 && alt.compare(alt.size() - 4, 4, "(..)") == 0;
      if (call) alt.resize(alt.size() - 4);
      alternatives.push_back({alt, call});
      start = bar + 1;
    }
    segments_.push_back(std::move(alternatives));
  }
}

bool PathPattern::matches(const Path& path) const {
  if (path.size() != segments_.size()) return false;
  for (size_t i = 0; i < path.size(); ++i) {
    bool any = false;
    for (const Alternative& alt : segments_[i]) {
      // A bare `*` stands for any base expression, called or not.
      if (alt.glob == "*" || (alt.call == path[i].call && glob_match(alt.glob, path[i].name))) {
        any = true;
        break;
      }
    }
    if (!any) return false;
  }
  return true;
}

std::string PathPattern::problem() const {
  for (const auto& segment : segments_)
    for (const Alternative& alt : segment) {
      if (alt.glob.empty()) return "an empty name (two dots or bars in a row, or one at an end)";
      for (char c : alt.glob)
        if (!(c == '_' || c == '*' || c == '?' || (c >= '0' && c <= '9') || (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z')))
          return c == '(' || c == ')' ? "a call is written `Name(..)`, with two dots between the parentheses"
                                      : "`" + alt.glob + "` holds '" + c + "', which no name has";
    }
  return "";
}

bool PathPattern::matches_name(std::string_view name) const {
  return matches(Path{{std::string(name), false}});
}

}  // namespace lwc
