#pragma once
#include <string>
#include <string_view>

namespace lwc {

// A unified diff (as `diff -u` / `git diff` print it) from `before` to `after`, with `context`
// lines around each change; "" when the texts are equal. Line endings are kept as they are, so a
// CRLF file's diff shows CRLF lines.
std::string unified_diff(std::string_view path, std::string_view before, std::string_view after, int context = 3);

}  // namespace lwc
