// Token-level reading of shader text: what the verifier's small rewrites stand on.
#include <gtest/gtest.h>

#include "lang/tokens.h"

namespace lwc {
namespace {

TEST(Tokens, SpellsSkipsBlanksAndCommentsAndMatchesWholeTokens) {
  TokenText t("void /* x */ main\n  ( ) ; mainly(");
  EXPECT_TRUE(t.spells(0, {"void", "main", "("}));
  EXPECT_TRUE(t.spells(0, {"", "", "(", ")"}));
  EXPECT_FALSE(t.spells(4, {"main"}));  // `mainly`
  EXPECT_FALSE(t.spells(5, {"(", ")"}));  // the text ends first
  EXPECT_EQ(t[99], "");
}

TEST(Tokens, ClosingCountsBothBracketKindsAndRefusesAMismatch) {
  TokenText t("f(a[(1)], g(b)) h(c] k(");
  EXPECT_EQ(t[t.closing(1)], ")");
  EXPECT_EQ(t.closing(1), 13u);
  EXPECT_EQ(t.closing(15), std::string_view::npos);  // `(` closed by `]`
  EXPECT_EQ(t.closing(19), std::string_view::npos);  // never closed
}

TEST(Tokens, RenameTouchesIdentifiersOnlyAndKeepsEveryOtherByte) {
  std::string text = "#define gl_Position x\ngl_Position = vec4(gl_PositionX); // gl_Position\n\"gl_Position\"";
  std::string out = rename_identifiers(text, [](std::string_view w) { return w == "gl_Position" ? std::string("lwc_gl_Position") : std::string(); });
  EXPECT_EQ(out, "#define gl_Position x\nlwc_gl_Position = vec4(gl_PositionX); // gl_Position\n\"gl_Position\"");
}

TEST(Tokens, SpliceAppliesSortedEditsAsWritten) {
  TokenText t("a + b * c");
  EXPECT_EQ(splice(t.text, {t.replace(0, 0, "x"), t.replace(2, 4, "(b*c)\n")}), "x + (b*c)\n");
  EXPECT_EQ(splice("abc", {}), "abc");
}

}  // namespace
}  // namespace lwc
