#include <gtest/gtest.h>

#include <random>
#include <thread>

#include "lang/lexer.h"
#include "support.h"

namespace lwc {
namespace {

// A lexing with nothing to start from: each thread keeps its own recent texts.
LexResult lexed_afresh(const std::string& text) {
  LexResult out;
  std::thread([&] { out = *lex(text); }).join();
  return out;
}

std::string describe(const Token& t) { return std::to_string(static_cast<int>(t.kind)) + "@" + std::to_string(t.begin) + "-" + std::to_string(t.end); }

// What changes the lexer's state far beyond itself: comments opened and closed, quotes, a `#`
// at a line start, continuations, line ends; and plain typing.
std::string random_edit(const std::string& text, std::mt19937& rng) {
  static const std::vector<std::string> pieces = {" ", "x", "1e", "+", "\n", "/*", "*/", "//", "\"", "'", "#", "#if A\n", "\\", "\\\n", "::", ":", ".5"};
  return test::random_edit(text, rng, pieces);
}

TEST(Lexer, AnEditedTextLexedAgainWhereItChangedGivesAFreshLexingsTokens) {
  std::mt19937 rng(20261124);
  int relexed = 0;
  for (const char* file : {"corpus/ue4/DeferredLightPixelShaders.usf", "corpus/ue5.4/EngineSpaces.usf", "corpus/glsl/lighting.glsl",
                           "corpus/negative/Suppressions.usf"}) {
    std::string original = test::read(test::source_dir() + "/" + file);
    std::string text = original;
    for (int edit = 0; edit < 200; ++edit) {
      text = edit % 40 == 39 ? original : random_edit(text, rng);
      std::shared_ptr<const LexResult> got = lex(text);
      LexResult want = lexed_afresh(text);
      ASSERT_EQ(got->unterminated_comment, want.unterminated_comment) << file << " edit " << edit;
      ASSERT_EQ(got->tokens.size(), want.tokens.size()) << file << " edit " << edit;
      for (size_t i = 0; i < want.tokens.size(); ++i)
        ASSERT_EQ(describe(got->tokens[i]), describe(want.tokens[i])) << file << " edit " << edit << " token " << i;
      ++relexed;
    }
  }
  EXPECT_EQ(relexed, 800);
}

TEST(Lexer, TheSameTextGivesTheSameTokensShared) {
  std::string text = "float3 P; // c\n#define A 1\n";
  std::shared_ptr<const LexResult> first = lex(text);
  lex("something else entirely");
  EXPECT_EQ(lex(text), first);
}

}  // namespace
}  // namespace lwc
