#include "lang/mask.h"

#include <algorithm>
#include <array>
#include <bitset>
#include <cctype>

#include "lang/conditionals.h"
#include "lang/lexer.h"
#include "lang/syntax.h"

namespace lwc {
namespace {

using namespace std::string_view_literals;

constexpr std::array kModifiers = {
    "in"sv, "out"sv, "inout"sv, "uniform"sv, "groupshared"sv, "nointerpolation"sv, "linear"sv,
    "centroid"sv, "noperspective"sv, "sample"sv, "row_major"sv, "column_major"sv, "snorm"sv, "unorm"sv,
    "globallycoherent"sv};
// Geometry-shader input primitives, only as parameter modifiers.
constexpr std::array kPrimitiveModifiers = {"point"sv, "line"sv, "triangle"sv, "lineadj"sv,
                                            "triangleadj"sv};
// Words that can never be a macro's name: statements, and what starts a declaration.
constexpr std::array kKeywords = {
    "if"sv, "for"sv, "while"sv, "switch"sv, "return"sv, "do"sv, "else"sv, "case"sv, "default"sv,
    "break"sv, "continue"sv, "discard"sv, "struct"sv, "class"sv, "cbuffer"sv, "tbuffer"sv, "typedef"sv,
    "namespace"sv, "sizeof"sv, "template"sv, "typename"sv, "const"sv, "static"sv, "register"sv,
    "packoffset"sv, "layout"sv};
// After these, a `{` opens a declaration block, not code.
constexpr std::array kBlockKeywords = {"struct"sv, "class"sv, "cbuffer"sv, "tbuffer"sv, "namespace"sv,
                                       "enum"sv, "interface"sv, "layout"sv, "uniform"sv, "buffer"sv};

// Every identifier of a file is looked up in these lists: the first byte is compared before the
// rest (a memcmp per word of the same length was most of the masking's time).
template <size_t N>
bool one_of(std::string_view word, const std::array<std::string_view, N>& set) {
  for (std::string_view s : set)
    if (s.size() == word.size() && s[0] == word[0] && s == word) return true;
  return false;
}

constexpr size_t kNone = SIZE_MAX;

// The file's own tokens and macro knowledge, masked in place in `out`.
class Masker {
 public:
  Masker(std::string_view src, std::string& out, std::vector<Token> tokens, Lang lang, const MacroTable& table,
         const MacroTable& learnt)
      : src_(src), out_(out), t_(std::move(tokens)), masked_(t_.size(), false), lang_(lang), table_(table), learnt_(learnt) {
    match_brackets();
    for (const MacroTable* names : {&table_, &learnt_})
      for (const auto& [name, use] : *names)
        if (!name.empty()) macro_shapes_.set(shape(name));
  }

  void run() {
    std::vector<int> pending_ternary{0};  // per nesting level, the `?` still waiting for their `:`
    bool in_case_label = false;
    for (size_t i = 0; i < t_.size(); ++i) {
      if (t_[i].kind == Tok::directive || masked_[i]) continue;
      std::string_view w = word(i);
      if (t_[i].kind == Tok::ident) {
        if (w == "case" || w == "default") in_case_label = true;
        i = identifier(i);
        continue;
      }
      if (t_[i].kind != Tok::punct) continue;
      if (lang_ == Lang::hlsl && (w == "%" || w == "{")) {
        if (size_t j = placeholder(i); j != kNone) {
          i = j;
          continue;
        }
      }
      track_scope(i, w);
      if (lang_ == Lang::glsl) continue;
      if (w == "(" || w == "{" || w == "[") pending_ternary.push_back(0);
      else if ((w == ")" || w == "}" || w == "]") && pending_ternary.size() > 1) pending_ternary.pop_back();
      if (w == ";" || w == "{" || w == "}") in_case_label = false;
      if (w == "?") ++pending_ternary.back();
      if (w == "[" && starts_attribute(i)) {
        size_t close = matching(i);
        if (close < t_.size()) {
          mask(i, close);
          pending_ternary.pop_back();
          i = close;
        }
        continue;
      }
      if (w == ":") {
        if (pending_ternary.back() > 0) { --pending_ternary.back(); continue; }
        if (in_case_label) { in_case_label = false; continue; }
        i = mask_binding(i);
      }
    }
  }

 private:
  enum class Scope { file, decl, code, init };

  std::string_view word(size_t i) const {
    if (i >= t_.size()) return {};
    return src_.substr(t_[i].begin, t_[i].end - t_[i].begin);
  }
  bool is(size_t i, Tok kind) const { return i < t_.size() && t_[i].kind == kind; }
  // The nearest token before `i` still in the output (directives included), or kNone.
  size_t prev(size_t i) const {
    while (i-- > 0)
      if (!masked_[i]) return i;
    return kNone;
  }
  size_t prev_code(size_t i) const {
    for (size_t p = prev(i); p != kNone; p = prev(p))
      if (t_[p].kind != Tok::directive) return p;
    return kNone;
  }
  // At the start of a statement or declaration.
  bool at_boundary(size_t i) const {
    size_t p = prev(i);
    if (p == kNone || t_[p].kind == Tok::directive) return true;
    std::string_view w = word(p);
    return w == ";" || w == "{" || w == "}";
  }
  bool same_line(size_t a, size_t b) const {
    return src_.substr(t_[a].end, t_[b].begin - t_[a].end).find('\n') == std::string_view::npos;
  }
  // Words that can follow a modifier-like identifier without it being a modifier.
  bool is_keyword_like(size_t i) const {
    std::string_view w = word(i);
    return w == "return" || w == "else" || w == "if" || w == "for" || w == "while";
  }
  void blank(uint32_t begin, uint32_t end) {
    for (uint32_t k = begin; k < end; ++k)
      if (out_[k] != '\n' && out_[k] != '\r') out_[k] = ' ';
  }
  void mask(size_t from, size_t to) {
    blank(t_[from].begin, t_[to].end);
    for (size_t k = from; k <= to; ++k) masked_[k] = true;
  }
  // The bracket that closes the one at `open` (counting that kind of bracket only), or the end.
  size_t matching(size_t open) const { return open < closer_.size() ? closer_[open] : t_.size(); }

  // Every bracket's partner, worked out once (one stack per kind): a lookup is O(1), so nesting
  // costs linear time however deep it goes.
  void match_brackets() {
    closer_.assign(t_.size(), t_.size());
    std::vector<size_t> open[3];
    for (size_t k = 0; k < t_.size(); ++k) {
      if (t_[k].kind != Tok::punct) continue;
      std::string_view w = word(k);
      int kind = w == "(" || w == ")" ? 0 : w == "[" || w == "]" ? 1 : w == "{" || w == "}" ? 2 : -1;
      if (kind < 0) continue;
      if (w == "(" || w == "[" || w == "{") {
        open[kind].push_back(k);
      } else if (!open[kind].empty()) {
        closer_[open[kind].back()] = k;
        open[kind].pop_back();
      }
    }
  }

  // ---- scopes: what a `{` opens decides whether a call-like line can be a declaration macro
  void track_scope(size_t i, std::string_view w) {
    if (w == "(") ++parens_;
    else if (w == ")" && parens_ > 0 && --parens_ == 0) statement_has_parameters_ = true;
    if (w == "{") {
      Scope current = scopes_.back();
      size_t p = prev_code(i);
      std::string_view pw = p == kNone ? std::string_view() : word(p);
      Scope s = current == Scope::init || pw == "=" || pw == "," || pw == "(" || pw == "return" ? Scope::init
                : current == Scope::code                                                        ? Scope::code
                : statement_is_block_                                                           ? Scope::decl
                : statement_has_parameters_                                                     ? Scope::code
                                                                                                : Scope::decl;
      scopes_.push_back(s);
    } else if (w == "}" && scopes_.size() > 1) {
      scopes_.pop_back();
    }
    if (w == ";" || w == "{" || w == "}") {
      statement_is_block_ = statement_has_parameters_ = false;
      parens_ = 0;
    }
  }

  // ---- identifiers: block keywords, macros, modifiers
  size_t identifier(size_t i) {
    std::string_view w = word(i);
    if (one_of(w, kBlockKeywords)) statement_is_block_ = true;
    if (lang_ == Lang::hlsl && (w == "cbuffer" || w == "tbuffer") && is(i + 1, Tok::ident)) {
      mask_block_keyword(i);
      return i + 1;
    }
    if (auto use = macro_use(w)) {
      if (size_t j = apply_macro(i, *use); j != kNone) return j;
    }
    if (lang_ == Lang::glsl) {
      // bgfx's `SAMPLER2D(s_texColor, 0);` declares at file scope.
      if (scopes_.back() == Scope::file && at_boundary(i) && word(i + 1) == "(" && !one_of(word(i), kKeywords)) {
        size_t close = matching(i + 1);
        if (close < t_.size() && word(close + 1) == ";") {
          mask(i, close + 1);
          return close + 1;
        }
      }
      return glsl_identifier(i);
    }
    if (is(i + 1, Tok::ident) && !is_keyword_like(i + 1)) {
      if (one_of(w, kModifiers)) { mask(i, i); return i; }
      size_t p = prev_code(i);
      if (one_of(w, kPrimitiveModifiers) && p != kNone && (word(p) == "(" || word(p) == ",")) { mask(i, i); return i; }
      if (w == "precise") { out_.replace(t_[i].begin, 7, "mutable"); return i; }
    }
    if (size_t j = call_like_macro(i); j != kNone) return j;
    if (lone_macro(i)) mask(i, i);
    return i;
  }

  // An all-caps name alone on its line between statements or declarations, as Unreal writes
  // macros that expand to struct members (`TANGENTTOWORLD_INTERPOLATOR_BLOCK`) or to attributes
  // before a function or a block (`PIXELSHADER_EARLYDEPTHSTENCIL`).
  bool lone_macro(size_t i) const {
    std::string_view w = word(i);
    if (w.size() < 4 || w.find('_') == std::string_view::npos) return false;
    if (!std::all_of(w.begin(), w.end(), [](char c) { return std::isupper(static_cast<unsigned char>(c)) || std::isdigit(static_cast<unsigned char>(c)) || c == '_'; }))
      return false;
    size_t p = prev(i), n = i + 1;
    if (p != kNone && same_line(p, i)) return false;
    if (n < t_.size() && same_line(i, n)) return false;
    std::string_view pw = p == kNone || t_[p].kind == Tok::directive ? ";" : word(p);
    if (pw != ";" && pw != "{" && pw != "}" && pw != ")") return false;
    return n >= t_.size() || t_[n].kind == Tok::directive || t_[n].kind == Tok::ident || word(n) == "[" || word(n) == "{" ||
           word(n) == "}";
  }

  // What the GLSL grammar (0.2.0) reads badly and lwcport does not need: precision qualifiers and
  // the memory qualifiers it has no rule for (`restrict`, `coherent`, `volatile`; `readonly` and
  // `writeonly` it reads, and the verifier's kernels need them), a scalar constructor after
  // `(` (`(float(n) * p)` reads as a cast), and array types written on the type (`float[9] kernel`,
  // `float[](...)`), whose brackets become spaces.
  size_t glsl_identifier(size_t i) {
    std::string_view w = word(i);
    if (w == "highp" || w == "mediump" || w == "lowp" || w == "restrict" || w == "coherent" || w == "volatile") {
      mask(i, i);
      return i;
    }
    size_t j = i;
    if (word(j + 1) == "[") {
      size_t close = matching(j + 1);
      if (close < t_.size() && (is(close + 1, Tok::ident) || word(close + 1) == "(")) {
        mask(j + 1, close);
        j = close;
      }
    }
    if ((w == "float" || w == "int" || w == "bool" || w == "double") && word(j + 1) == "(")
      out_.replace(t_[i].begin, w.size(), std::string(w.size(), '_'));
    return j;
  }
  // A name's length and first byte, which most words share with no macro.
  static size_t shape(std::string_view w) { return std::min<size_t>(w.size(), 63) * 64 + (static_cast<unsigned char>(w[0]) & 63); }
  std::optional<MacroUse> macro_use(std::string_view w) const {
    if (!macro_shapes_.test(shape(w))) return std::nullopt;
    if (auto it = learnt_.find(w); it != learnt_.end()) return it->second;
    if (auto it = table_.find(w); it != table_.end()) return it->second;
    return std::nullopt;
  }

  // Returns the last token consumed, or kNone when the macro is left as written.
  size_t apply_macro(size_t i, MacroUse use) {
    bool call = word(i + 1) == "(";
    size_t close = call ? matching(i + 1) : kNone;
    if (call && close >= t_.size()) return kNone;
    switch (use) {
      case MacroUse::qualifier:
      case MacroUse::suffix:
        mask(i, i);
        return i;
      case MacroUse::attribute:
        mask(i, call ? close : i);
        return call ? close : i;
      case MacroUse::declaration: {
        size_t end = call ? close : i;
        if (word(end + 1) == ";") ++end;
        mask(i, end);
        return end;
      }
      case MacroUse::type:
        if (!call) return kNone;
        mask(i + 1, close);
        return close;
      case MacroUse::loop: {
        if (!call || word(i).size() < 3) return kNone;
        out_.replace(t_[i].begin, word(i).size(), std::string("for") + std::string(word(i).size() - 3, ' '));
        int depth = 0;
        for (size_t k = i + 1; k < close; ++k) {
          std::string_view kw = word(k);
          depth += (kw == "(" || kw == "[" || kw == "{") ? 1 : (kw == ")" || kw == "]" || kw == "}") ? -1 : 0;
          if (depth == 1 && kw == ",") out_[t_[k].begin] = ';';
        }
        return i;
      }
    }
    return kNone;
  }

  // `NAME(...)` where the grammar cannot read a call: a macro that names a function
  // (`NAME(X)(params)`), declares at file or struct level (`NAME(float2)` alone on its line, or
  // `NAME(a, b);`), or makes a type (`NAME(uint) Buffer;`, also as a parameter's type).
  size_t call_like_macro(size_t i) {
    if (word(i + 1) != "(" || one_of(word(i), kKeywords) || one_of(word(i), kModifiers)) return kNone;
    size_t p = prev_code(i);
    std::string_view pw = p == kNone ? std::string_view() : word(p);
    if (pw == "." || pw == "->" || pw == "::") return kNone;
    size_t close = matching(i + 1);
    if (close >= t_.size()) return kNone;
    size_t a = close + 1;
    std::string_view aw = word(a);
    bool a_ident = is(a, Tok::ident) && !one_of(aw, kKeywords);
    bool tight = a < t_.size() && same_line(close, a);
    if (aw == "(") {
      mask(i + 1, close);
      return close;
    }
    Scope scope = scopes_.back();
    bool start = at_boundary(i);
    // A macro that defines a function (`RAY_TRACING_ENTRY_MISS(Name, FPayload, Payload) { ... }`):
    // its name becomes `void ___...`, so the body is read as a function's.
    if (scope == Scope::file && start && aw == "{" && word(i).size() >= 6) {
      std::string name = "void " + std::string(word(i).size() - 5, '_');
      out_.replace(t_[i].begin, name.size(), name);
      return i;
    }
    if ((scope == Scope::file || scope == Scope::decl) && start) {
      if (aw == ";") {
        mask(i, a);
        return a;
      }
      if ((a >= t_.size() || !tight || t_[a].kind == Tok::directive) && aw != "{" && aw != ":") {
        mask(i, close);
        return close;
      }
    }
    bool parameter = pw == "(" || pw == ",";
    if (a_ident && tight && (start || parameter)) {
      mask(i + 1, close);
      return close;
    }
    return kNone;
  }

  // Niagara's `%{placeholder}` (blanked) and `{Placeholder}` inside a name (an identifier).
  size_t placeholder(size_t i) {
    auto tight = [&](size_t a, size_t b) { return b < t_.size() && t_[a].end == t_[b].begin; };
    if (word(i) == "%") {
      if (word(i + 1) == "{" && is(i + 2, Tok::ident) && word(i + 3) == "}" && tight(i, i + 1) && tight(i + 1, i + 2) &&
          tight(i + 2, i + 3)) {
        mask(i, i + 3);
        return i + 3;
      }
      return kNone;
    }
    if (!is(i + 1, Tok::ident) || word(i + 2) != "}" || !tight(i, i + 1) || !tight(i + 1, i + 2)) return kNone;
    size_t p = prev_code(i);
    std::string_view pw = p == kNone ? std::string_view() : word(p);
    std::string_view after = word(i + 3);
    bool used = after == "[" || after == "." || after == "(";  // an initialiser list is never indexed or called
    if (!used && (pw == "=" || pw == "," || pw == "(" || pw == "{" || pw == "[")) return kNone;
    out_[t_[i].begin] = '_';
    out_[t_[i + 2].begin] = '_';
    return i + 2;
  }

  // `cbuffer Name` -> `extern"C"` plus spaces: both need at least 9 bytes.
  void mask_block_keyword(size_t i) {
    uint32_t begin = t_[i].begin, end = t_[i + 1].end;
    blank(begin, end);
    out_.replace(begin, 9, "extern\"C\"");
    statement_is_block_ = true;
  }
  // `[name...]` opens an attribute where a statement or declaration may begin.
  bool starts_attribute(size_t i) const {
    if (!is(i + 1, Tok::ident)) return false;
    size_t p = prev(i);
    if (p == kNone || t_[p].kind == Tok::directive) return true;
    std::string_view w = word(p);
    return w == ";" || w == "{" || w == "}" || w == "else";
  }
  // At a `:` that is not a ternary or case label: a semantic (`: SV_Target0`), or a binding
  // (`: register(b0)`, `: packoffset(c0.x)`) after a declarator or a parameter list.
  size_t mask_binding(size_t colon) {
    size_t p = prev_code(colon);
    if (p == kNone || !is(colon + 1, Tok::ident)) return colon;
    std::string_view pw = word(p);
    bool after_declarator = is(p, Tok::ident) || pw == ")" || pw == "]";
    if (!after_declarator) return colon;
    // `struct Derived : Base` keeps its base clause.
    size_t pp = prev_code(p);
    if (pp != kNone && (word(pp) == "struct" || word(pp) == "class")) return colon;
    std::string_view next = word(colon + 1);
    if ((next == "register" || next == "packoffset") && word(colon + 2) == "(") {
      size_t close = matching(colon + 2);
      if (close >= t_.size()) return colon;
      mask(colon, close);
      return close;
    }
    mask(colon, colon + 1);
    return colon + 1;
  }

  std::string_view src_;
  std::string& out_;
  std::vector<Token> t_;
  std::vector<bool> masked_;
  std::vector<size_t> closer_;  // per opening bracket token: its closing one (t_.size() if none)
  Lang lang_;
  const MacroTable& table_;
  const MacroTable& learnt_;
  std::bitset<64 * 64> macro_shapes_;  // shape() of every macro name either table has
  std::vector<Scope> scopes_{Scope::file};
  bool statement_is_block_ = false, statement_has_parameters_ = false;
  int parens_ = 0;
};

// A JavaScript template substitution (`${GROUND_ALBEDO}`, in shader files that JavaScript fills in
// and in GLSL inside template literals) becomes one identifier of its length.
void mask_substitutions(std::string& text) {
  for (size_t at = text.find("${"); at != std::string::npos; at = text.find("${", at + 1)) {
    size_t k = at + 2;
    for (int depth = 1; k < text.size() && depth > 0; ++k) depth += text[k] == '{' ? 1 : text[k] == '}' ? -1 : 0;
    for (size_t c = at; c < k; ++c)
      if (text[c] != '\n' && text[c] != '\r') text[c] = '_';
    at = k - 1;
  }
}

// Statements the GLSL grammar (0.2.0) does not parse and lwcport does not need:
// `precision highp float;` and interface defaults such as `layout(local_size_x = 64) in;`.
void mask_glsl_statements(std::string_view text, const std::vector<Token>& t, std::string& out) {
  auto word = [&](size_t i) { return i < t.size() ? text.substr(t[i].begin, t[i].end - t[i].begin) : std::string_view(); };
  auto blank = [&](size_t from, size_t to) {
    for (uint32_t k = t[from].begin; k < t[to].end; ++k)
      if (out[k] != '\n' && out[k] != '\r') out[k] = ' ';
  };
  for (size_t i = 0; i < t.size(); ++i) {
    // bgfx's `$input a_position, a_normal` and `$output ...` lines name the varyings.
    if (word(i) == "$" && (word(i + 1) == "input" || word(i + 1) == "output" || word(i + 1) == "raw") && t[i].end == t[i + 1].begin) {
      size_t j = i + 1;
      while (j + 1 < t.size() && text.substr(t[j].end, t[j + 1].begin - t[j].end).find('\n') == std::string_view::npos) ++j;
      blank(i, j);
      i = j;
      continue;
    }
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
}

}  // namespace

// A BOM is blanked before lexing: a directive on the first line must still start its line.
MaskResult mask_source(std::string_view original, Lang lang, const MaskOptions& options) {
  MaskResult result;
  result.text.assign(original);
  std::string& text = result.text;
  if (text.size() >= 3 && text.compare(0, 3, "\xEF\xBB\xBF") == 0) text.replace(0, 3, "   ");
  mask_substitutions(text);
  const std::string source = text;  // what the tokens index: the file with its BOM and substitutions masked
  std::shared_ptr<const LexResult> lexed_text = lex(source);
  const LexResult& lexed = *lexed_text;
  result.unterminated_comment = lexed.unterminated_comment;

  ConditionalPlan plan = plan_conditionals(source, lexed.tokens, options.variant);
  result.variants = plan.variants;
  result.resolved_conditionals = std::move(plan.regions);
  result.kept_arms = std::move(plan.kept_arms);
  std::vector<Token> kept;
  kept.reserve(lexed.tokens.size());
  for (size_t i = 0; i < lexed.tokens.size(); ++i) {
    if (!plan.dropped[i]) {
      kept.push_back(lexed.tokens[i]);
      continue;
    }
    for (uint32_t k = lexed.tokens[i].begin; k < lexed.tokens[i].end; ++k)
      if (text[k] != '\n' && text[k] != '\r') text[k] = ' ';
  }

  // A continuation with blanks after its backslash: the grammar wants the backslash last.
  // Pragmas and the like carry nothing lwcport reads, and the GLSL grammar rejects them in code.
  // Comments inside a directive go too: the grammar ends a macro at a `//` even inside `/* */`.
  auto blank = [&](size_t from, size_t to) {
    for (size_t k = from; k < to; ++k)
      if (text[k] != '\n' && text[k] != '\r') text[k] = ' ';
  };
  for (const Token& t : kept) {
    if (t.kind != Tok::directive) continue;
    std::string_view keyword = read_directive(std::string_view(source).substr(t.begin, t.end - t.begin)).keyword;
    if (keyword == "pragma" || keyword == "line" || keyword == "error" || keyword == "warning") {
      blank(t.begin, t.end);
      continue;
    }
    for (size_t k = t.begin; k + 1 < t.end; ++k) {
      if (source[k] == '/' && source[k + 1] == '*') {
        size_t end = source.find("*/", k + 2);
        end = end == std::string::npos || end + 2 > t.end ? t.end : end + 2;
        blank(k, end);
        k = end - 1;
      } else if (source[k] == '/' && source[k + 1] == '/') {
        size_t end = source.find('\n', k);
        end = std::min<size_t>(end == std::string::npos ? source.size() : end, t.end);
        blank(k, end);
        k = end;
      }
    }
    for (uint32_t k = t.begin; k < t.end; ++k) {
      size_t after = continuation_end(source, k);
      if (after == k) continue;
      size_t eol = after - (source[after - 2] == '\r' ? 2 : 1);  // after k: at least `\` and a newline
      if (eol == k + 1) continue;
      text[k] = ' ';
      text[eol - 1] = '\\';
      k = static_cast<uint32_t>(after - 1);
    }
  }

  // Blanks that end a directive (a `#define X` whose comment was blanked above, or written so):
  // the grammar would read the next line as the macro's value, so the line breaks before them and
  // they open the next line instead; every other byte stays where it was.
  for (const Token& t : kept) {
    if (t.kind != Tok::directive || t.end >= text.size() || text[t.end] != '\n') continue;
    size_t line_break = t.end > t.begin && text[t.end - 1] == '\r' ? t.end - 1 : t.end;
    size_t last = line_break;
    while (last > t.begin && (text[last - 1] == ' ' || text[last - 1] == '\t')) --last;
    if (last == line_break || text[last - 1] == '\\') continue;
    std::string moved = text.substr(line_break, t.end + 1 - line_break) + std::string(line_break - last, ' ');
    text.replace(last, moved.size(), moved);
  }

  const MacroTable& table = options.macros ? *options.macros : known_macros(lang);
  MacroTable learnt;
  learn_macros(source, table, learnt);
  if (lang == Lang::glsl) mask_glsl_statements(source, kept, text);
  Masker(source, text, std::move(kept), lang, table, learnt).run();
  return result;
}

}  // namespace lwc
