#include "lang/embedded.h"

#include <cctype>
#include <cstring>

#include "lang/lexer.h"

namespace lwc {

namespace {

// Enough of a JavaScript/TypeScript scanner to find template literals: comments, strings, regular
// expressions and `${...}` nesting are stepped over, so nothing inside them is taken for code.
class Scanner {
 public:
  Scanner(std::string_view s, bool every_literal) : s_(s), every_(every_literal) {}

  // The literals' contents, each with the `${...}` substitutions it holds.
  std::vector<Span> run(std::vector<Span>& substitutions) {
    code(0, false);
    for (Span sub : substitutions_)
      for (Span lit : found_)
        if (lit.begin <= sub.begin && sub.end <= lit.end) substitutions.push_back(sub);
    return found_;
  }

 private:
  // Scans code from `i`; inside a substitution it stops after the `}` that closes it.
  size_t code(size_t i, bool substitution) {
    int depth = 0;
    bool glsl_comment = false;  // the last thing seen was /* glsl */
    while (i < s_.size()) {
      char c = s_[i];
      if (c == '/' && i + 1 < s_.size() && s_[i + 1] == '/') {
        while (i < s_.size() && s_[i] != '\n') ++i;
        continue;
      }
      if (c == '/' && i + 1 < s_.size() && s_[i + 1] == '*') {
        size_t end = s_.find("*/", i + 2);
        end = end == std::string_view::npos ? s_.size() : end;
        glsl_comment = trimmed(s_.substr(i + 2, end - i - 2)) == "glsl";
        i = std::min(s_.size(), end + 2);
        continue;
      }
      if (c == ' ' || c == '\t' || c == '\r' || c == '\n') {
        ++i;
        continue;
      }
      if (c == '`') {
        bool tagged = glsl_comment || last_word_ == "glsl" || last_word_ == "GLSL";
        size_t end = literal(i + 1);
        Span content{static_cast<uint32_t>(i + 1), static_cast<uint32_t>(end > i + 1 ? end - 1 : i + 1)};
        if (!substitution && (every_ || tagged || starts_like_glsl(content))) found_.push_back(content);
        i = end;
        glsl_comment = false;
        last_word_ = {};
        previous_ = '`';
        continue;
      }
      glsl_comment = false;
      if (c == '\'' || c == '"') {
        i = string(i);
        previous_ = c;
        last_word_ = {};
        continue;
      }
      if (c == '/' && regex_may_start()) {
        i = regex(i);
        previous_ = '/';
        continue;
      }
      if (ident_start(c) || c == '$') {
        size_t b = i;
        while (i < s_.size() && (ident_char(s_[i]) || s_[i] == '$')) ++i;
        last_word_ = s_.substr(b, i - b);
        previous_ = 'a';
        continue;
      }
      last_word_ = {};
      if (c == '{') ++depth;
      if (c == '}' && depth-- == 0 && substitution) return i + 1;
      previous_ = c;
      ++i;
    }
    return i;
  }

  // From just after an opening backtick to just after the closing one.
  size_t literal(size_t i) {
    while (i < s_.size()) {
      if (s_[i] == '\\') {
        i += 2;
      } else if (s_[i] == '`') {
        return i + 1;
      } else if (s_[i] == '$' && i + 1 < s_.size() && s_[i + 1] == '{') {
        std::string_view word = last_word_;
        char previous = previous_;
        size_t begin = i;
        i = code(i + 2, true);
        substitutions_.push_back({static_cast<uint32_t>(begin), static_cast<uint32_t>(i)});
        last_word_ = word;
        previous_ = previous;
      } else {
        ++i;
      }
    }
    return s_.size();
  }

  size_t string(size_t i) {
    char quote = s_[i++];
    while (i < s_.size() && s_[i] != quote && s_[i] != '\n') i += s_[i] == '\\' ? 2 : 1;
    return std::min(s_.size(), i + 1);
  }

  // A `/` starts a regular expression where a value is expected, not after one.
  bool regex_may_start() const {
    if (previous_ == 'a') return last_word_ == "return" || last_word_ == "typeof" || last_word_ == "case" || last_word_ == "in" ||
                                 last_word_ == "of" || last_word_ == "yield" || last_word_ == "await";
    return previous_ == 0 || std::strchr("(,=:[!&|?{};+-*%<>~^", previous_) != nullptr;
  }

  size_t regex(size_t i) {
    bool in_class = false;
    for (++i; i < s_.size() && s_[i] != '\n'; ++i) {
      if (s_[i] == '\\') ++i;
      else if (s_[i] == '[') in_class = true;
      else if (s_[i] == ']') in_class = false;
      else if (s_[i] == '/' && !in_class) return i + 1;
    }
    return i;
  }

  static std::string_view trimmed(std::string_view t) {
    size_t b = t.find_first_not_of(" \t\r\n"), e = t.find_last_not_of(" \t\r\n");
    return b == std::string_view::npos ? std::string_view() : t.substr(b, e - b + 1);
  }

  // An untagged literal that is GLSL by its content: a version line first (after a line
  // continuation, as some libraries open them), a precision statement first, or a stage's entry
  // point or output beside GLSL's own words.
  bool starts_like_glsl(Span content) const {
    std::string_view t = trimmed(s_.substr(content.begin, content.end - content.begin));
    if (t.starts_with("\\")) t = trimmed(t.substr(1));
    if (t.starts_with("#version") || t.starts_with("precision highp") || t.starts_with("precision mediump") ||
        t.starts_with("precision lowp"))
      return true;
    auto has = [&](std::string_view w) { return t.find(w) != std::string_view::npos; };
    if (has("gl_Position") || has("gl_FragColor") || has("gl_FragData")) return true;
    return has("void main") && (has("uniform ") || has("varying ") || has("attribute ") || has("in vec") || has("out vec") ||
                                has("gl_FragCoord") || has("texture2D("));
  }

  std::string_view s_;
  bool every_;
  std::vector<Span> found_, substitutions_;
  std::string_view last_word_;
  char previous_ = 0;  // the last significant character ('a' for a word)
};

}  // namespace

std::vector<Span> glsl_template_literals(std::string_view path, std::string_view script) {
  std::vector<Span> substitutions;
  return glsl_template_literals(path, script, substitutions);
}

std::vector<Span> glsl_template_literals(std::string_view path, std::string_view script, std::vector<Span>& substitutions) {
  bool every = path.ends_with(".glsl.js") || path.ends_with(".glsl.ts");
  return Scanner(script, every).run(substitutions);
}

std::string glsl_view(std::string_view script, const std::vector<Span>& literals, const std::vector<Span>& substitutions) {
  std::string out(script.size(), ' ');
  for (size_t i = 0; i < script.size(); ++i)
    if (script[i] == '\n' || script[i] == '\r') out[i] = script[i];
  for (Span s : literals) {
    for (uint32_t i = s.begin; i < s.end; ++i) {
      // A backslash before a line end is JavaScript's line continuation, not GLSL.
      bool continuation = script[i] == '\\' && i + 1 < s.end && (script[i + 1] == '\n' || script[i + 1] == '\r');
      out[i] = continuation ? ' ' : script[i];
    }
    // The closing backtick ends the literal's last statement: the next literal starts afresh.
    if (s.end < out.size()) out[s.end] = ';';
  }
  // A substitution is whatever JavaScript puts there: alone on its line, declarations (blank);
  // inside a line, a value (one identifier of its first line's length).
  auto blank_line_around = [&](Span s) {
    size_t line = script.rfind('\n', s.begin);
    line = line == std::string_view::npos ? 0 : line + 1;
    size_t eol = script.find('\n', s.end);
    eol = eol == std::string_view::npos ? script.size() : eol;
    auto blank = [](std::string_view t) { return t.find_first_not_of(" \t\r;") == std::string_view::npos; };
    return blank(script.substr(line, s.begin - line)) && blank(script.substr(s.end, eol - s.end));
  };
  for (Span s : substitutions) {
    bool alone = blank_line_around(s), first_line = true;
    for (uint32_t i = s.begin; i < s.end; ++i) {
      if (out[i] == '\n' || out[i] == '\r') first_line = false;
      else out[i] = first_line && !alone ? '_' : ' ';
    }
  }
  return out;
}

}  // namespace lwc
