#pragma once
#include <cstdint>
#include <memory>
#include <optional>
#include <string_view>
#include <vector>

namespace lwc {

// A small shader lexer: enough to tell identifiers, numbers, strings, punctuation and
// preprocessor directives apart while skipping comments. Offsets are bytes of the text.
enum class Tok { ident, number, string, punct, directive };

struct Token {
  Tok kind;
  uint32_t begin, end;
};

struct LexResult {
  std::vector<Token> tokens;
  std::optional<uint32_t> unterminated_comment;  // offset of a `/*` that never ends
};

// Shared: the last text lexed on a thread is kept, and lexing the same text again gives its tokens.
std::shared_ptr<const LexResult> lex(std::string_view text);

bool ident_start(char c);
bool ident_char(char c);
// After a line continuation at `i` (a backslash, blanks, a line end), or `i` when there is none.
size_t continuation_end(std::string_view text, size_t i);

// A directive's keyword (`if`, `ifdef`, `define`...) and what follows it on its logical line
// (continuations joined by the caller's reading; comments left in).
struct Directive {
  std::string_view keyword;
  std::string_view rest;
};
Directive read_directive(std::string_view directive_text);

}  // namespace lwc
