#include "lang/lexer.h"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <tuple>
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

  // Lexes from `i` (between two tokens; `line_start`: nothing but blanks and comments since the
  // last line end) to the end, or until `stop` says the tokens line up with an earlier lexing.
  template <typename Stop>
  void run(size_t i, bool line_start, Stop stop) {
    size_t n = s.size();
    while (i < n) {
      if (!out.tokens.empty() && out.tokens.back().end == i && stop()) return;
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

// How many bytes two texts share at their start, and then at their end (the two never overlap).
std::pair<size_t, size_t> common_ends(std::string_view a, std::string_view b) {
  constexpr size_t kBlock = 256;  // memcmp over blocks first: a byte loop would cost more than the lexing saved
  size_t limit = std::min(a.size(), b.size()), prefix = 0, suffix = 0;
  while (prefix + kBlock <= limit && std::memcmp(a.data() + prefix, b.data() + prefix, kBlock) == 0) prefix += kBlock;
  while (prefix < limit && a[prefix] == b[prefix]) ++prefix;
  while (suffix + kBlock <= limit - prefix &&
         std::memcmp(a.data() + a.size() - suffix - kBlock, b.data() + b.size() - suffix - kBlock, kBlock) == 0)
    suffix += kBlock;
  while (suffix < limit - prefix && a[a.size() - 1 - suffix] == b[b.size() - 1 - suffix]) ++suffix;
  return {prefix, suffix};
}

struct Lexed {
  std::string text;
  std::shared_ptr<const LexResult> result;
};

// `text` lexed again where it differs from `before`, whose lexing is `old`: the lexer's state
// between two tokens is only where it is and whether a line has begun, so it restarts after the
// last old token that ends before the first changed byte, and stops at the first token after the
// last changed byte that begins and ends where an old one did (the rest is the old tokens, moved).
LexResult relex(std::string_view before, const LexResult& old, std::string_view text, size_t prefix, size_t suffix) {
  const std::vector<Token>& was = old.tokens;
  size_t kept = std::lower_bound(was.begin(), was.end(), prefix, [](const Token& t, size_t at) { return t.end < at; }) - was.begin();
  Lexer lexer{text, {}};
  lexer.out.tokens.assign(was.begin(), was.begin() + kept);
  int64_t shift = static_cast<int64_t>(text.size()) - static_cast<int64_t>(before.size());
  size_t unchanged_from = text.size() - suffix;
  auto line_up = [&]() {
    const Token& t = lexer.out.tokens.back();
    if (t.begin < unchanged_from) return false;
    auto it = std::lower_bound(was.begin() + kept, was.end(), t.begin - shift, [](const Token& o, int64_t at) { return o.begin < at; });
    if (it == was.end() || it->begin != t.begin - shift || it->end != t.end - shift || it->kind != t.kind) return false;
    for (++it; it != was.end(); ++it)
      lexer.out.tokens.push_back({it->kind, static_cast<uint32_t>(it->begin + shift), static_cast<uint32_t>(it->end + shift)});
    if (old.unterminated_comment) lexer.out.unterminated_comment = static_cast<uint32_t>(*old.unterminated_comment + shift);
    return true;
  };
  bool directive_before = kept > 0 && was[kept - 1].kind == Tok::directive;
  lexer.run(kept > 0 ? was[kept - 1].end : 0, kept == 0 || directive_before, line_up);
  return std::move(lexer.out);
}

}  // namespace

std::shared_ptr<const LexResult> lex(std::string_view text) {
  // A file is lexed by the masker and twice by era inference, and again after every edit in the
  // language server: the last few texts are kept, and a text like one of them is lexed again only
  // where it differs.
  constexpr size_t kKept = 4;
  thread_local std::vector<Lexed> recent;
  for (size_t k = 0; k < recent.size(); ++k) {
    if (recent[k].text == text) {
      std::rotate(recent.begin(), recent.begin() + k, recent.begin() + k + 1);
      return recent.front().result;
    }
  }
  const Lexed* like = nullptr;
  size_t prefix = 0, suffix = 0;
  for (const Lexed& r : recent) {
    auto [p, q] = common_ends(r.text, text);
    if (p + q > prefix + suffix) std::tie(like, prefix, suffix) = std::tuple(&r, p, q);
  }
  LexResult result;
  if (like && prefix + suffix >= text.size() / 2) {
    result = relex(like->text, *like->result, text, prefix, suffix);
  } else {
    Lexer lexer{text, {}};
    lexer.run(0, true, [] { return false; });
    result = std::move(lexer.out);
  }
  if (recent.size() == kKept) recent.pop_back();
  recent.insert(recent.begin(), Lexed{std::string(text), std::make_shared<const LexResult>(std::move(result))});
  return recent.front().result;
}

Directive read_directive(std::string_view d) {
  size_t i = 1;  // after '#'
  while (i < d.size() && (d[i] == ' ' || d[i] == '\t')) ++i;
  size_t b = i;
  while (i < d.size() && ident_char(d[i])) ++i;
  return {d.substr(b, i - b), d.substr(i)};
}

}  // namespace lwc
