#pragma once
#include <map>
#include <set>
#include <string>
#include <string_view>

namespace lwc {

// Where `lint --add-suppressions` writes: per line (1-based), the rule ids to silence there, and
// for a script's GLSL (where a line's end may be outside the literal), the byte after which a
// comment still sits in GLSL.
struct SuppressionSites {
  std::map<int, std::set<std::string>> rules_by_line;
  std::map<int, size_t> inside_at;  // only for scripts: the end of the line's first finding
};

// The text with a `lwcport-ignore: ids` comment on each line: appended to a trailing
// `lwcport-ignore:` already there, else ` // lwcport-ignore: ids` at the end of the line (before a
// line-continuation backslash, and for scripts at `inside_at`, as a block comment instead).
std::string with_suppressions(std::string_view text, const SuppressionSites& sites);

}  // namespace lwc
