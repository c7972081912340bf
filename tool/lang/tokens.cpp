#include "lang/tokens.h"

#include <set>

namespace lwc {

TokenText::TokenText(std::string_view t) : text(t), tokens(lex(t)->tokens) {}

std::string_view TokenText::operator[](size_t i) const {
  if (i >= size()) return {};
  return text.substr(tokens[i].begin, tokens[i].end - tokens[i].begin);
}

bool TokenText::spells(size_t i, std::initializer_list<std::string_view> words) const {
  for (std::string_view w : words) {
    if (i >= size() || (w.empty() ? !ident(i) : (*this)[i] != w)) return false;
    ++i;
  }
  return true;
}

size_t TokenText::closing(size_t open) const {
  std::vector<char> expected;  // closers still owed, innermost last
  for (size_t i = open; i < size(); ++i) {
    std::string_view t = (*this)[i];
    if (t == "(" || t == "[") expected.push_back(t == "(" ? ')' : ']');
    if (t != ")" && t != "]") continue;
    if (expected.empty() || expected.back() != t[0]) return std::string_view::npos;
    expected.pop_back();
    if (expected.empty()) return i;
  }
  return std::string_view::npos;
}

std::string rename_identifiers(std::string_view text, const std::function<std::string(std::string_view)>& rename) {
  TokenText t(text);
  std::vector<Edit> edits;
  for (size_t i = 0; i < t.size(); ++i)
    if (t.ident(i))
      if (std::string name = rename(t[i]); !name.empty()) edits.push_back(t.replace(i, i, std::move(name)));
  return splice(text, edits);
}

std::set<std::string, std::less<>> identifiers(std::string_view text) {
  std::set<std::string, std::less<>> out;
  for (size_t i = 0; i < text.size();) {
    if (!ident_start(text[i])) {
      ++i;
      continue;
    }
    size_t b = i;
    while (i < text.size() && ident_char(text[i])) ++i;
    out.emplace(text.substr(b, i - b));
  }
  return out;
}

}  // namespace lwc
