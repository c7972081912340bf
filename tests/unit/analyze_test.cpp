// analyze(): what it makes of files the parser reads in variants or with syntax errors.
#include <gtest/gtest.h>

#include "fix/apply.h"
#include "support.h"

namespace lwc {
namespace {

size_t count(const std::vector<Finding>& findings, const std::string& rule) {
  size_t n = 0;
  for (const Finding& f : findings) n += f.rule == rule;
  return n;
}

// UE4 code with preprocessor groups inside a parameter list and an expression: every arm is
// analysed, one variant at a time.
const char* kArms = R"(float3 CameraOffset(
#if USE_TRANSLATED
	float3 TranslatedPos
#else
	float3 WorldPos
#endif
	)
{
#if USE_TRANSLATED
	return TranslatedPos - View.TranslatedWorldCameraOrigin;
#else
	return WorldPos - View.WorldCameraOrigin;
#endif
}
float3 ToView(float3 WorldPos)
{
	return WorldPos
#if USE_VIEW_ORIGIN
		- View.WorldViewOrigin
#else
		- View.WorldCameraOrigin
#endif
		;
}
)";

TEST(Variants, FindingsInEveryArmAreReportedOnce) {
  auto findings = test::lint_text(kArms, Lang::hlsl, "lwc-primary-view");
  ASSERT_EQ(count(findings, "lwc-primary-view"), 3u);
  // In the function body the grammar reads the group itself: the finding and its rewrite are the
  // same in both variants. Inside the expression each arm is read in one variant only: found, but
  // no rewrite is sure to fit the other arm.
  EXPECT_EQ(findings[0].fixes.size(), 1u);
  for (size_t i : {1, 2}) {
    EXPECT_TRUE(findings[i].fixes.empty());
    ASSERT_FALSE(findings[i].withheld.empty());
    EXPECT_NE(findings[i].withheld.back().find("preprocessor branches"), std::string::npos);
  }
  EXPECT_EQ(count(test::lint_text(kArms, Lang::hlsl), "lwc-input"), 0u);
}

TEST(Variants, ASuppressionUsedInOneArmIsNotUnused) {
  std::string code = std::string(kArms);
  code.replace(code.find("- View.WorldViewOrigin"), 0, "// lwcport-ignore: lwc-primary-view\n\t\t");
  auto findings = test::lint_text(code, Lang::hlsl);
  EXPECT_EQ(count(findings, "lwc-unused-suppression"), 0u);
  EXPECT_EQ(count(findings, "lwc-primary-view"), 2u);
}

TEST(SyntaxErrors, OnlyTheBrokenDeclarationLosesItsRewrites) {
  std::string code =
      "float3 Broken(float3 P) { return P - View.WorldCameraOrigin +* ; }\n"
      "float3 Fine(float3 P) { return P - View.WorldCameraOrigin; }\n";
  auto findings = test::lint_text(code, Lang::hlsl);
  ASSERT_EQ(count(findings, "lwc-input"), 1u);
  int with_fix = 0, without = 0;
  for (const Finding& f : findings) {
    if (f.rule != "lwc-primary-view") continue;
    (f.fixes.empty() ? without : with_fix) += 1;
    if (f.fixes.empty()) {
      ASSERT_FALSE(f.withheld.empty());
      EXPECT_NE(f.withheld.back().find("syntax error"), std::string::npos);
    }
  }
  EXPECT_EQ(with_fix, 1);
  EXPECT_LE(without, 1);
}

}  // namespace
}  // namespace lwc
