#include "lang/lexer.h"

#include <algorithm>
#include <cctype>
#include <string>

namespace lwc {

bool ident_start(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool ident_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

size_t continuation_end(std::string_view s, size_t i) {
  if (i >= s.size() || s[i] != '\\') return i;
  size_t k = i + 1;
  while (k < s.size() && (s[k] == ' ' || s[k] == '\t')) ++k;
  if (k < s.size() && s[k] == '\r') ++k;
  return k < s.size() && s[k] == '\n' ? k + 1 : i;
}

namespace {

struct Lexer {
  std::string_view s;
  LexResult out;

  void run() {
    size_t i = 0, n = s.size();
    bool line_start = true;
    while (i < n) {
      char c = s[i];
      if (c == '\n') { line_start = true; ++i; continue; }
      if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') { ++i; continue; }
      if (c == '/' && i + 1 < n && s[i + 1] == '/') { i = skip_line(i); continue; }
      if (c == '/' && i + 1 < n && s[i + 1] == '*') { i = skip_block_comment(i); continue; }
      if (c == '#' && line_start) {
        size_t b = i;
        i = skip_directive(i);
        out.tokens.push_back({Tok::directive, uint32_t(b), uint32_t(i)});
        continue;
      }
      line_start = false;
      size_t b = i;
      if (ident_start(c)) {
        while (i < n && ident_char(s[i])) ++i;
        out.tokens.push_back({Tok::ident, uint32_t(b), uint32_t(i)});
      } else if (std::isdigit(static_cast<unsigned char>(c)) || (c == '.' && i + 1 < n && std::isdigit(static_cast<unsigned char>(s[i + 1])))) {
        while (i < n && (ident_char(s[i]) || s[i] == '.' ||
                         ((s[i] == '+' || s[i] == '-') && (s[i - 1] == 'e' || s[i - 1] == 'E'))))
          ++i;
        out.tokens.push_back({Tok::number, uint32_t(b), uint32_t(i)});
      } else if (c == '"' || c == '\'') {
        ++i;
        while (i < n && s[i] != c && s[i] != '\n') i += (s[i] == '\\') ? 2 : 1;
        i = std::min(i + 1, n);
        out.tokens.push_back({Tok::string, uint32_t(b), uint32_t(i)});
      } else {
        i += (c == ':' && i + 1 < n && s[i + 1] == ':') ? 2 : 1;
        out.tokens.push_back({Tok::punct, uint32_t(b), uint32_t(i)});
      }
    }
  }

  size_t skip_line(size_t i) {
    while (i < s.size() && s[i] != '\n') ++i;
    return i;
  }
  size_t skip_block_comment(size_t i) {
    size_t end = s.find("*/", i + 2);
    if (end == std::string_view::npos) {
      out.unterminated_comment = uint32_t(i);
      return s.size();
    }
    return end + 2;
  }
  // A directive runs to the end of the line, joined by backslash continuations (blanks between
  // the backslash and the line end are allowed, as compilers allow them); comments in it may span
  // lines.
  size_t skip_directive(size_t i) {
    while (i < s.size() && s[i] != '\n') {
      if (size_t after = continuation_end(s, i); after != i) {
        i = after;
      } else if (s[i] == '/' && i + 1 < s.size() && s[i + 1] == '*') {
        i = skip_block_comment(i);
      } else if (s[i] == '/' && i + 1 < s.size() && s[i + 1] == '/') {
        return skip_line(i);
      } else {
        ++i;
      }
    }
    return i;
  }
};

}  // namespace

std::shared_ptr<const LexResult> lex(std::string_view text) {
  // A file is lexed by the masker and twice by era inference.
  thread_local std::string last_text;
  thread_local std::shared_ptr<const LexResult> last;
  if (last && text.size() == last_text.size() && text == last_text) return last;
  Lexer lexer{text, {}};
  lexer.run();
  last_text.assign(text);
  last = std::make_shared<const LexResult>(std::move(lexer.out));
  return last;
}

Directive read_directive(std::string_view d) {
  size_t i = 1;  // after '#'
  while (i < d.size() && (d[i] == ' ' || d[i] == '\t')) ++i;
  size_t b = i;
  while (i < d.size() && ident_char(d[i])) ++i;
  return {d.substr(b, i - b), d.substr(i)};
}

}  // namespace lwc
