#pragma once
// Shader text as tokens, for the small textual rewrites the verifier makes around the syntax
// tree (renaming types, cutting a kernel, replacing texture reads). It replaced std::regex, whose
// matcher recursed once per character a pattern matched: a long name or struct overflowed the
// stack. Every operation here is one linear pass without recursion.
#include <functional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "core/finding.h"
#include "lang/lexer.h"

namespace lwc {

struct TokenText {
  explicit TokenText(std::string_view text);

  std::string_view text;
  std::vector<Token> tokens;

  size_t size() const { return tokens.size(); }
  std::string_view operator[](size_t i) const;  // the token's text ("" past the end)
  bool ident(size_t i) const { return i < size() && tokens[i].kind == Tok::ident; }
  // Tokens from `i` are exactly `words`, in order ("" stands for any identifier).
  bool spells(size_t i, std::initializer_list<std::string_view> words) const;
  // The token closing the bracket `(` or `[` at `open` (nested brackets of either kind counted),
  // or npos when the text ends first or a bracket of the other kind closes it.
  size_t closing(size_t open) const;
  // An edit replacing tokens [first, last] with `text`.
  Edit replace(size_t first, size_t last, std::string text) const { return {{tokens[first].begin, tokens[last].end}, std::move(text)}; }
};

// The identifier-shaped words of a text (comments and strings included), each once.
std::set<std::string, std::less<>> identifiers(std::string_view text);

// Each identifier token `rename` gives a new name for (empty: unchanged) renamed.
std::string rename_identifiers(std::string_view text, const std::function<std::string(std::string_view)>& rename);

}  // namespace lwc
