#include "lsp/positions.h"

#include <algorithm>

namespace lwc::lsp {
namespace {

// Bytes of the UTF-8 sequence that starts with `lead` (1 for a byte that starts none).
size_t sequence_length(unsigned char lead) { return lead >= 0xF0 ? 4 : lead >= 0xE0 ? 3 : lead >= 0xC0 ? 2 : 1; }

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
    size_t n = std::min(sequence_length(static_cast<unsigned char>(text[at])), end - at);
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
    size_t n = std::min(sequence_length(static_cast<unsigned char>(text[i])), at - i);
    units += units_of(n, utf8);
    i += n;
  }
  return {line, units};
}

}  // namespace lwc::lsp
