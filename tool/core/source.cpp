#include "core/source.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstring>

namespace lwc {

Source::Source(std::string path, std::string text) : path_(std::move(path)), text_(std::move(text)) {
  bom_ = text_.size() >= 3 && std::memcmp(text_.data(), "\xEF\xBB\xBF", 3) == 0;
  // A line at a time (memchr): this runs on every keystroke in the language server.
  for (size_t begin = 0;;) {
    size_t end = text_.find('\n', begin);
    size_t stop = end == std::string::npos ? text_.size() : end;
    line_starts_.push_back(static_cast<uint32_t>(begin));
    ascii_lines_.push_back(ascii_run(std::string_view(text_).substr(begin, stop - begin)) == stop - begin);
    if (end == std::string::npos) break;
    if (end > 0 && text_[end - 1] == '\r') crlf_ = true;
    begin = end + 1;
  }
  if (bom_) ascii_lines_[0] = 0;
}

static bool is_continuation(unsigned char c) { return (c & 0xC0) == 0x80; }

size_t utf8_sequence(std::string_view text, size_t i) {
  const auto* s = reinterpret_cast<const unsigned char*>(text.data());
  unsigned char c = s[i];
  if (c < 0x80) return 1;
  size_t len;
  uint32_t min;
  if ((c & 0xE0) == 0xC0) { len = 2; min = 0x80; }
  else if ((c & 0xF0) == 0xE0) { len = 3; min = 0x800; }
  else if ((c & 0xF8) == 0xF0) { len = 4; min = 0x10000; }
  else return 0;
  if (i + len > text.size()) return 0;
  uint32_t cp = c & (0x7F >> len);
  for (size_t k = 1; k < len; ++k) {
    if (!is_continuation(s[i + k])) return 0;
    cp = (cp << 6) | (s[i + k] & 0x3F);
  }
  // Overlong forms, surrogates and values past U+10FFFF are not UTF-8.
  if (cp < min || (cp >= 0xD800 && cp <= 0xDFFF) || cp > 0x10FFFF) return 0;
  return len;
}

// One column per character: a valid UTF-8 sequence, or a byte that is not part of one (as an
// editor shows it: one replacement character each).
static size_t column_bytes(std::string_view text, size_t i) { return std::max<size_t>(1, utf8_sequence(text, i)); }

size_t utf8_char_start(std::string_view text, size_t i) {
  while (i > 0 && i < text.size() && is_continuation(static_cast<unsigned char>(text[i]))) --i;
  return i;
}

std::string escape_invalid_utf8(std::string_view text) {
  std::string out;
  for (size_t i = 0; i < text.size();) {
    size_t len = utf8_sequence(text, i);
    if (len == 0) {
      out += fmt::format("\\x{:02X}", static_cast<unsigned char>(text[i]));
      ++i;
    } else {
      out.append(text, i, len);
      i += len;
    }
  }
  return out;
}

Position Source::position(uint32_t offset) const {
  offset = std::min<uint32_t>(offset, text_.size());
  auto it = std::upper_bound(line_starts_.begin(), line_starts_.end(), offset);
  int line = static_cast<int>(it - line_starts_.begin());
  uint32_t start = line_starts_[line - 1];
  if (line == 1 && bom_) start = std::min<uint32_t>(3, offset);
  if (ascii_lines_[line - 1]) return {line, static_cast<int>(offset - start) + 1};  // one byte, one column
  int column = 1;
  for (size_t i = start; i < offset; i += column_bytes(text_, i)) ++column;
  return {line, column};
}

uint32_t Source::offset(Position pos) const {
  if (pos.line < 1) return 0;
  if (pos.line > line_count()) return static_cast<uint32_t>(text_.size());
  uint32_t i = line_starts_[pos.line - 1];
  if (pos.line == 1 && bom_) i = 3;
  std::string_view line = line_text(pos.line);
  uint32_t end = static_cast<uint32_t>(line.data() - text_.data() + line.size());
  if (ascii_lines_[pos.line - 1]) return pos.column < 1 ? i : static_cast<uint32_t>(std::min<size_t>(i + pos.column - 1, end));
  for (int column = 1; column < pos.column && i < end; ++column) i += column_bytes(text_, i);
  return std::min(i, end);
}

std::string_view Source::line_text(int line) const {
  if (line < 1 || line > line_count()) return {};
  uint32_t begin = line_starts_[line - 1];
  if (line == 1 && bom_) begin = 3;
  uint32_t end = line < line_count() ? line_starts_[line] : static_cast<uint32_t>(text_.size());
  if (end > begin && text_[end - 1] == '\n') --end;
  if (end > begin && text_[end - 1] == '\r') --end;
  return std::string_view(text_).substr(begin, end - begin);
}

std::optional<uint32_t> find_binary_marker(std::string_view text) {
  size_t n = std::min<size_t>(text.size(), 8192);
  const void* nul = std::memchr(text.data(), 0, n);
  if (!nul) return std::nullopt;
  return static_cast<uint32_t>(static_cast<const char*>(nul) - text.data());
}

size_t ascii_run(std::string_view text) {
  size_t i = 0;
  for (uint64_t word; i + 8 <= text.size(); i += 8) {  // eight bytes at a time while no high bit is set
    std::memcpy(&word, text.data() + i, 8);
    if (word & 0x8080808080808080ull) break;
  }
  while (i < text.size() && static_cast<unsigned char>(text[i]) < 0x80) ++i;
  return i;
}

std::optional<uint32_t> find_invalid_utf8(std::string_view text) {
  size_t i = 0;
  while ((i += ascii_run(text.substr(i))) < text.size()) {
    size_t len = utf8_sequence(text, i);
    if (len == 0) return static_cast<uint32_t>(i);
    i += len;
  }
  return std::nullopt;
}

std::string json_quoted(std::string_view text) {
  std::string out;
  out.reserve(text.size() + 2);
  out += '"';
  for (size_t i = 0; i < text.size();) {
    // Printable ASCII but for the quote and the backslash goes as it is, a run at a time.
    size_t run = i;
    while (run < text.size() && static_cast<unsigned char>(text[run]) >= 0x20 && static_cast<unsigned char>(text[run]) < 0x80 &&
           text[run] != '"' && text[run] != '\\')
      ++run;
    out.append(text, i, run - i);
    if ((i = run) == text.size()) break;
    size_t n = utf8_sequence(text, i);
    char c = text[i];
    if (n == 0) out += "\xEF\xBF\xBD";
    else if (n > 1) out.append(text, i, n);
    else if (c == '"' || c == '\\') (out += '\\') += c;
    else if (c == '\n') out += "\\n";
    else if (c == '\r') out += "\\r";
    else if (c == '\t') out += "\\t";
    else if (c == '\b') out += "\\b";
    else if (c == '\f') out += "\\f";
    else out += fmt::format("\\u{:04x}", c);
    i += std::max<size_t>(n, 1);
  }
  return out + '"';
}

}  // namespace lwc
