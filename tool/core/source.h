#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace lwc {

// A byte range [begin, end) in a source buffer.
struct Span {
  uint32_t begin = 0;
  uint32_t end = 0;
  bool operator==(const Span&) const = default;
};

// 1-based line and column; columns count Unicode code points (a BOM and CR are not counted).
struct Position {
  int line = 1;
  int column = 1;
};

// One file's bytes with a line index. The text is kept byte-for-byte as read.
class Source {
 public:
  Source(std::string path, std::string text);

  const std::string& path() const { return path_; }
  const std::string& text() const { return text_; }
  bool has_bom() const { return bom_; }
  bool uses_crlf() const { return crlf_; }
  int line_count() const { return static_cast<int>(line_starts_.size()); }

  Position position(uint32_t offset) const;
  // Byte offset of a 1-based line/column (the inverse of position()).
  uint32_t offset(Position pos) const;
  // The line's text without its line ending.
  std::string_view line_text(int line) const;
  std::string_view slice(Span span) const { return std::string_view(text_).substr(span.begin, span.end - span.begin); }

 private:
  std::string path_;
  std::string text_;
  bool bom_ = false;
  bool crlf_ = false;
  std::vector<uint32_t> line_starts_;
  std::vector<char> ascii_lines_;  // per line: only ASCII, so a column is a byte (position() in O(1))
};

// The first NUL byte in the first 8 KiB marks a binary file (as git and grep decide).
std::optional<uint32_t> find_binary_marker(std::string_view text);
// How many bytes at the start of `text` are ASCII.
size_t ascii_run(std::string_view text);
// Offset of the first byte that is not valid UTF-8, if any.
std::optional<uint32_t> find_invalid_utf8(std::string_view text);
// The length of the valid UTF-8 sequence that starts at byte `i`, or 0 when none does there.
size_t utf8_sequence(std::string_view text, size_t i);
// The start of the character that holds byte `i` (back over continuation bytes): where a text
// may be cut without splitting a character.
size_t utf8_char_start(std::string_view text, size_t i);
// The text with each byte that is not valid UTF-8 shown as `\xNN` (for text output).
std::string escape_invalid_utf8(std::string_view text);
// The text as a JSON string, quotes included, as nlohmann::json writes it; each byte that is not
// UTF-8 becomes U+FFFD. For messages written without building a json value first.
std::string json_quoted(std::string_view text);

}  // namespace lwc
