#include "lang/hlsl_mask.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <vector>

namespace lwc {
namespace {

enum class Tok { ident, number, string, punct, directive };

struct Token {
  Tok kind;
  uint32_t begin, end;
};

bool ident_start(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool ident_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

// A small lexer: enough to tell identifiers, punctuation and directives apart while skipping
// comments and strings.
struct Lexer {
  std::string_view s;
  std::vector<Token> tokens;
  std::optional<uint32_t> unterminated_comment;

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
        tokens.push_back({Tok::directive, uint32_t(b), uint32_t(i)});
        continue;
      }
      line_start = false;
      size_t b = i;
      if (ident_start(c)) {
        while (i < n && ident_char(s[i])) ++i;
        tokens.push_back({Tok::ident, uint32_t(b), uint32_t(i)});
      } else if (std::isdigit(static_cast<unsigned char>(c)) || (c == '.' && i + 1 < n && std::isdigit(static_cast<unsigned char>(s[i + 1])))) {
        while (i < n && (ident_char(s[i]) || s[i] == '.' ||
                         ((s[i] == '+' || s[i] == '-') && (s[i - 1] == 'e' || s[i - 1] == 'E'))))
          ++i;
        tokens.push_back({Tok::number, uint32_t(b), uint32_t(i)});
      } else if (c == '"' || c == '\'') {
        ++i;
        while (i < n && s[i] != c && s[i] != '\n') i += (s[i] == '\\') ? 2 : 1;
        i = std::min(i + 1, n);
        tokens.push_back({Tok::string, uint32_t(b), uint32_t(i)});
      } else {
        i += (c == ':' && i + 1 < n && s[i + 1] == ':') ? 2 : 1;
        tokens.push_back({Tok::punct, uint32_t(b), uint32_t(i)});
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
      unterminated_comment = uint32_t(i);
      return s.size();
    }
    return end + 2;
  }
  // A directive runs to the end of the line, joined by backslash continuations; comments in it
  // may span lines.
  size_t skip_directive(size_t i) {
    while (i < s.size() && s[i] != '\n') {
      if (s[i] == '\\' && i + 1 < s.size() && (s[i + 1] == '\n' || s[i + 1] == '\r')) {
        i += (s[i + 1] == '\r' && i + 2 < s.size() && s[i + 2] == '\n') ? 3 : 2;
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

using namespace std::string_view_literals;

constexpr std::array kModifiers = {
    "in"sv, "out"sv, "inout"sv, "uniform"sv, "groupshared"sv, "nointerpolation"sv, "linear"sv,
    "centroid"sv, "noperspective"sv, "sample"sv, "row_major"sv, "column_major"sv, "snorm"sv, "unorm"sv,
    "globallycoherent"sv};
// Geometry-shader input primitives, only as parameter modifiers.
constexpr std::array kPrimitiveModifiers = {"point"sv, "line"sv, "triangle"sv, "lineadj"sv,
                                            "triangleadj"sv};
// Unreal's macros that expand to loop/branch attributes.
constexpr std::array kAttributeMacros = {"UNROLL"sv, "LOOP"sv, "BRANCH"sv, "FLATTEN"sv,
                                         "ISOLATE"sv, "ALLOW_UAV_CONDITION"sv};
constexpr std::array kStatementKeywords = {"for"sv, "while"sv, "do"sv, "if"sv, "switch"sv};

template <size_t N>
bool one_of(std::string_view word, const std::array<std::string_view, N>& set) {
  return std::find(set.begin(), set.end(), word) != set.end();
}

class Masker {
 public:
  Masker(std::string_view text, std::vector<Token> tokens) : src_(text), out_(text), t_(std::move(tokens)) {}

  std::string run() {
    // Per nesting level, the `?` still waiting for their `:`.
    std::vector<int> pending_ternary{0};
    bool in_case_label = false;
    for (size_t i = 0; i < t_.size(); ++i) {
      std::string_view w = word(i);
      if (t_[i].kind == Tok::ident) {
        if ((w == "cbuffer" || w == "tbuffer") && is(i + 1, Tok::ident)) {
          mask_block_keyword(i);
          ++i;
          continue;
        }
        if (w == "case" || w == "default") in_case_label = true;
        if (is(i + 1, Tok::ident) && !is_keyword_like(i + 1)) {
          if (one_of(w, kModifiers)) { blank(t_[i].begin, t_[i].end); continue; }
          if (one_of(w, kPrimitiveModifiers) && i > 0 && (word(i - 1) == "(" || word(i - 1) == ",")) {
            blank(t_[i].begin, t_[i].end);
            continue;
          }
          if (w == "precise") { out_.replace(t_[i].begin, 7, "mutable"); continue; }
        }
        if (one_of(w, kAttributeMacros) && i + 1 < t_.size() && one_of(word(i + 1), kStatementKeywords)) {
          blank(t_[i].begin, t_[i].end);
          continue;
        }
        continue;
      }
      if (t_[i].kind != Tok::punct) continue;
      if (w == "(" || w == "{" || w == "[") pending_ternary.push_back(0);
      else if ((w == ")" || w == "}" || w == "]") && pending_ternary.size() > 1) pending_ternary.pop_back();
      if (w == ";" || w == "{" || w == "}") in_case_label = false;
      if (w == "?") ++pending_ternary.back();
      if (w == "[" && starts_attribute(i)) {
        size_t close = matching(i);
        if (close < t_.size()) {
          blank(t_[i].begin, t_[close].end);
          pending_ternary.pop_back();
          i = close;
          attribute_end_ = close;
        }
        continue;
      }
      if (w == ":") {
        if (pending_ternary.back() > 0) { --pending_ternary.back(); continue; }
        if (in_case_label) { in_case_label = false; continue; }
        i = mask_binding(i);
      }
    }
    return std::move(out_);
  }

 private:
  std::string_view word(size_t i) const {
    if (i >= t_.size()) return {};
    return src_.substr(t_[i].begin, t_[i].end - t_[i].begin);
  }
  bool is(size_t i, Tok kind) const { return i < t_.size() && t_[i].kind == kind; }
  // Words that can follow a modifier-like identifier without it being a modifier.
  bool is_keyword_like(size_t i) const {
    std::string_view w = word(i);
    return w == "return" || w == "else" || w == "if" || w == "for" || w == "while";
  }
  void blank(uint32_t begin, uint32_t end) {
    for (uint32_t k = begin; k < end; ++k) {
      if (out_[k] != '\n' && out_[k] != '\r') out_[k] = ' ';
    }
  }
  // `cbuffer Name` -> `extern"C"` plus spaces: both need at least 9 bytes.
  void mask_block_keyword(size_t i) {
    uint32_t begin = t_[i].begin, end = t_[i + 1].end;
    blank(begin, end);
    out_.replace(begin, 9, "extern\"C\"");
  }
  size_t matching(size_t open) const {
    std::string_view o = word(open);
    std::string_view c = o == "[" ? "]" : o == "(" ? ")" : "}";
    int depth = 0;
    for (size_t k = open; k < t_.size(); ++k) {
      if (word(k) == o) ++depth;
      else if (word(k) == c && --depth == 0) return k;
    }
    return t_.size();
  }
  // `[name...]` opens an attribute where a statement or declaration may begin.
  bool starts_attribute(size_t i) const {
    if (!is(i + 1, Tok::ident)) return false;
    if (i == 0) return true;
    const Token& prev = t_[i - 1];
    if (prev.kind == Tok::directive) return true;
    std::string_view p = word(i - 1);
    if (p == ";" || p == "{" || p == "}" || p == "else") return true;
    return p == "]" && attribute_end_ == i - 1;
  }
  // At a `:` that is not a ternary or case label: a semantic (`: SV_Target0`), or a binding
  // (`: register(b0)`, `: packoffset(c0.x)`) after a declarator or a parameter list.
  size_t mask_binding(size_t colon) {
    if (colon == 0 || !is(colon + 1, Tok::ident)) return colon;
    std::string_view prev = word(colon - 1);
    bool after_declarator = is(colon - 1, Tok::ident) || prev == ")" || prev == "]";
    if (!after_declarator) return colon;
    // `struct Derived : Base` keeps its base clause.
    if (colon >= 2 && (word(colon - 2) == "struct" || word(colon - 2) == "class")) return colon;
    std::string_view next = word(colon + 1);
    if ((next == "register" || next == "packoffset") && word(colon + 2) == "(") {
      size_t close = matching(colon + 2);
      if (close >= t_.size()) return colon;
      blank(t_[colon].begin, t_[close].end);
      return close;
    }
    blank(t_[colon].begin, t_[colon + 1].end);
    return colon + 1;
  }

  std::string_view src_;
  std::string out_;
  std::vector<Token> t_;
  size_t attribute_end_ = SIZE_MAX;
};

void mask_bom(std::string& text) {
  if (text.size() >= 3 && text.compare(0, 3, "\xEF\xBB\xBF") == 0) text.replace(0, 3, "   ");
}

}  // namespace

// A BOM is blanked before lexing: a directive on the first line must still start its line.
MaskResult mask_hlsl(std::string_view original) {
  std::string text(original);
  mask_bom(text);
  Lexer lexer{text, {}, std::nullopt};
  lexer.run();
  return {Masker(text, std::move(lexer.tokens)).run(), lexer.unterminated_comment};
}

// Statements the GLSL grammar (0.2.0) does not parse and lwcport does not need:
// `precision highp float;` and interface defaults such as `layout(local_size_x = 64) in;`.
MaskResult mask_glsl(std::string_view original) {
  std::string owned(original);
  mask_bom(owned);
  std::string_view text = owned;
  Lexer lexer{text, {}, std::nullopt};
  lexer.run();
  MaskResult result{std::string(text), lexer.unterminated_comment};
  const auto& t = lexer.tokens;
  auto word = [&](size_t i) { return i < t.size() ? text.substr(t[i].begin, t[i].end - t[i].begin) : std::string_view(); };
  auto blank = [&](size_t from, size_t to) {
    for (uint32_t k = t[from].begin; k < t[to].end; ++k)
      if (result.text[k] != '\n' && result.text[k] != '\r') result.text[k] = ' ';
  };
  for (size_t i = 0; i < t.size(); ++i) {
    bool statement_start = i == 0 || word(i - 1) == ";" || word(i - 1) == "}" || t[i - 1].kind == Tok::directive;
    if (!statement_start || t[i].kind != Tok::ident) continue;
    if (word(i) == "precision" && word(i + 3) == ";") {
      blank(i, i + 3);
      i += 3;
    } else if (word(i) == "layout" && word(i + 1) == "(") {
      size_t k = i + 2;
      for (int depth = 1; k < t.size() && depth > 0; ++k) depth += word(k) == "(" ? 1 : word(k) == ")" ? -1 : 0;
      std::string_view q = word(k);
      if ((q == "in" || q == "out" || q == "uniform" || q == "buffer") && word(k + 1) == ";") {
        blank(i, k + 1);
        i = k + 1;
      }
    }
  }
  return result;
}

}  // namespace lwc
