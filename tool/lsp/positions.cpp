#include "lsp/positions.h"

#include <algorithm>

#include "core/source.h"

namespace lwc::lsp {
namespace {

// The bytes of the character at `i`: a UTF-8 sequence; a lone surrogate in generalised UTF-8 (ED
// A0..BF 80..BF: lsp/json_reader.h writes an escaped one so), one character as the client holds
// it; or a byte that is neither, one character as `lint` and editors count it.
size_t character_bytes(std::string_view text, size_t i) {
  if (static_cast<unsigned char>(text[i]) < 0x80) return 1;
  if (size_t n = utf8_sequence(text, i)) return n;
  auto byte = [&](size_t k) { return i + k < text.size() ? static_cast<unsigned char>(text[i + k]) : 0; };
  if (byte(0) == 0xED && byte(1) >= 0xA0 && byte(1) <= 0xBF && byte(2) >= 0x80 && byte(2) <= 0xBF) return 3;
  return 1;
}

// A character of `bytes` UTF-8 bytes in the negotiated units (UTF-16: two beyond the BMP).
long units_of(size_t bytes, bool utf8) { return utf8 ? static_cast<long>(bytes) : bytes == 4 ? 2 : 1; }

}  // namespace

std::vector<size_t> line_starts(const std::string& text) {
  std::vector<size_t> starts = {0};
  if (text.find('\r') == std::string::npos) {  // the usual file: memchr finds its lines far faster than a byte loop
    for (size_t at = text.find('\n'); at != std::string::npos; at = text.find('\n', at + 1)) starts.push_back(at + 1);
    return starts;
  }
  for (size_t i = 0; i < text.size(); ++i)
    if (text[i] == '\n' || (text[i] == '\r' && (i + 1 == text.size() || text[i + 1] != '\n'))) starts.push_back(i + 1);
  return starts;
}

size_t offset_at(const std::string& text, const std::vector<size_t>& lines, long line, long character, bool utf8) {
  if (line < 0) return 0;
  if (static_cast<size_t>(line) >= lines.size()) return text.size();
  size_t at = lines[line], end = static_cast<size_t>(line) + 1 < lines.size() ? lines[line + 1] : text.size();
  if (end > at && text[end - 1] == '\n') --end;
  if (end > at && text[end - 1] == '\r') --end;
  for (long units = 0; at < end && units < character;) {
    size_t n = std::min(character_bytes(text, at), end - at);
    units += units_of(n, utf8);
    at += n;
  }
  return at;
}

std::pair<size_t, long> line_and_column(const std::string& text, const std::vector<size_t>& lines, size_t at, bool utf8) {
  at = std::min(at, text.size());
  size_t line = static_cast<size_t>(std::upper_bound(lines.begin(), lines.end(), at) - lines.begin()) - 1;
  long units = 0;
  for (size_t i = lines[line]; i < at;) {
    size_t n = std::min(character_bytes(text, i), at - i);
    units += units_of(n, utf8);
    i += n;
  }
  return {line, units};
}

}  // namespace lwc::lsp
