#include "fix/suppress.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <vector>

#include "rules/analyze.h"

namespace lwc {

std::string with_suppressions(std::string_view text, const SuppressionSites& sites) {
  // Line starts, then each insertion as (offset, text), applied from the end.
  std::vector<size_t> starts{0};
  for (size_t i = 0; i < text.size(); ++i)
    if (text[i] == '\n') starts.push_back(i + 1);
  std::vector<std::pair<size_t, std::string>> inserts;
  for (const auto& [line, ids] : sites.rules_by_line) {
    if (line < 1 || static_cast<size_t>(line) > starts.size() || ids.empty()) continue;
    std::string list = fmt::format("{}", fmt::join(ids, ", "));
    size_t begin = starts[line - 1];
    size_t end = static_cast<size_t>(line) < starts.size() ? starts[line] - 1 : text.size();
    if (end > begin && text[end - 1] == '\r') --end;
    std::string_view content = text.substr(begin, end - begin);
    // A trailing `lwcport-ignore: a, b` on this line takes the new ids after its last one.
    if (size_t at = content.find("lwcport-ignore:"); at != std::string_view::npos) {
      std::vector<Span> listed = suppression_ids(content, at + 15);
      inserts.emplace_back(begin + (listed.empty() ? at + 15 : listed.back().end), ", " + list);
      continue;
    }
    if (auto inside = sites.inside_at.find(line); inside != sites.inside_at.end()) {
      inserts.emplace_back(inside->second, " /* lwcport-ignore: " + list + " */");
      continue;
    }
    size_t at = end;
    while (at > begin && (text[at - 1] == ' ' || text[at - 1] == '\t')) --at;
    if (at > begin && text[at - 1] == '\\') {  // a continued line: the comment must not swallow the backslash
      inserts.emplace_back(at - 1, "/* lwcport-ignore: " + list + " */ ");
      continue;
    }
    inserts.emplace_back(at, " // lwcport-ignore: " + list);
  }
  std::string out(text);
  for (auto it = inserts.rbegin(); it != inserts.rend(); ++it) out.insert(it->first, it->second);
  return out;
}

}  // namespace lwc
