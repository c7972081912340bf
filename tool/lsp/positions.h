#pragma once
// Positions in an open document as LSP counts them: lines end at "\n", "\r\n" or a lone "\r" (a
// line's end belongs to no column), and columns count UTF-16 code units, or bytes where the client
// chose UTF-8.
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace lwc::lsp {

// Where each line of `text` starts.
std::vector<size_t> line_starts(const std::string& text);

// The byte offset of (line, character), clamped to the text (a line past the end is its end, a
// character past a line's end is that end). `lines`: line_starts(text).
size_t offset_at(const std::string& text, const std::vector<size_t>& lines, long line, long character, bool utf8);

// The line of a byte offset and its column.
std::pair<size_t, long> line_and_column(const std::string& text, const std::vector<size_t>& lines, size_t at, bool utf8);

}  // namespace lwc::lsp
