// CheckContext::fix, the one door every rewrite goes through: what it refuses to offer.
#include <gtest/gtest.h>

#include "lang/syntax.h"
#include "rules/analyze.h"
#include "rules/rule.h"
#include "world/model.h"

namespace lwc {
namespace {

struct Offer {
  bool offered = false;
  std::vector<std::string> withheld;
};

// Offers one edit replacing `target` (its first occurrence in `code`) with `text` as a rewrite of
// lwc-translated-member.
Offer offer(const std::string& code, const std::string& target, const std::string& text) {
  Source source("t.usf", code);
  SyntaxTree tree = parse(source, Lang::hlsl);
  WorldModel world(tree, world_data(Lang::hlsl, nlohmann::json::array()));
  const RuleInfo* rule = find_rule("lwc-translated-member");
  std::vector<Finding> out;
  CheckContext ctx{tree, world, *rule, out, std::nullopt};
  uint32_t at = static_cast<uint32_t>(code.find(target));
  Finding& f = ctx.report(Span{at, at + static_cast<uint32_t>(target.size())}, {});
  Vars vars{{"twin", "X"}, {"marker", "DFHackToFloat"}, {"stored", "X"}};
  bool offered = ctx.fix(f, "absolute", vars, {{Span{at, at + static_cast<uint32_t>(target.size())}, text}}) != nullptr;
  return {offered, f.withheld};
}

const char* kCode =
    "struct FLight { float3 Position; float4 Packed[2]; };\n"
    "float3 F(float3 P)\n"
    "{\n"
    "\tFLight LightData;\n"
    "\tLightData.Position = P;\n"
    "\tLightData.Packed[0].xyz += P;\n"
    "\tLightData.Packed[1]++;\n"
    "\treturn LightData.Position - P;\n"
    "}\n";

TEST(CheckContext, NeverRewritesAStoreTargetIntoAnExpression) {
  Offer store = offer(kCode, "LightData.Position =", "LightData.Position");  // the place itself: allowed
  EXPECT_TRUE(store.offered);
  Offer broken = offer(kCode, "LightData.Position", "(LightData.Translated - DFHackToFloat(PrimaryView.PreViewTranslation))");
  EXPECT_FALSE(broken.offered);
  ASSERT_EQ(broken.withheld.size(), 1u);
  EXPECT_NE(broken.withheld[0].find("not a place"), std::string::npos) << broken.withheld[0];
  // The object of a member stored into, and the target of ++, are places too.
  EXPECT_FALSE(offer(kCode, "LightData.Packed[0]", "Unpack(LightData.Packed[0])").offered);
  EXPECT_FALSE(offer(kCode, "LightData.Packed[1]", "(LightData.Packed[1] * 2)").offered);
}

TEST(CheckContext, RewritesPlacesIntoPlacesAndValuesIntoAnything) {
  EXPECT_TRUE(offer(kCode, "LightData.Position", "LightData.TranslatedWorldPosition").offered);
  EXPECT_TRUE(offer(kCode, "LightData.Packed[0]", "LightData.Packed[Index + 1]").offered);
  // A read (the return's operand) may become any expression.
  std::string read = "LightData.Position - P";
  EXPECT_TRUE(offer(kCode, read, "DFSubtractDemote(LightData.Position, P)").offered);
}

}  // namespace
}  // namespace lwc
