// Where a finding's world-space value came from (world/provenance.h): the steps a finding carries
// as related locations, and the description of a value at an offset (the editor's hover).
#include <gtest/gtest.h>

#include "rules/analyze.h"
#include "support.h"

namespace lwc {
namespace {

const char* kSwizzleStore =
    "uniform mat4 modelMatrix;\n"
    "in vec3 position;\n"
    "out vec3 vWorldPosition;\n"
    "void main() {\n"
    "  vec4 p = vec4(position, 1.0);\n"
    "  p.xyz = (modelMatrix * vec4(position, 1.0)).xyz;\n"
    "  vWorldPosition = p.xyz;\n"
    "}\n";

int line_of(const std::string& text, Span span) { return Source("a.vert", text).position(span.begin).line; }

// The varying's finding is explained from its store back to the uniform: through the store into a
// part of `p` (a swizzle), not its small initialiser.
TEST(Provenance, AFindingIsTracedThroughStoresToItsSource) {
  std::vector<Finding> found = test::lint_text(kSwizzleStore, Lang::glsl, "lwc-float-world-position");
  const Finding* varying = nullptr;
  for (const Finding& f : found)
    if (line_of(kSwizzleStore, f.span) == 3) varying = &f;
  ASSERT_NE(varying, nullptr);
  ASSERT_EQ(varying->related.size(), 3u);
  EXPECT_EQ(line_of(kSwizzleStore, varying->related[0].first), 7);
  EXPECT_EQ(varying->related[0].second, "`vWorldPosition = p.xyz` (line 7)");
  EXPECT_EQ(line_of(kSwizzleStore, varying->related[1].first), 6);
  EXPECT_EQ(varying->related[1].second, "`p.xyz = (modelMatrix * vec4(position, 1.0)).xyz` (line 6)");
  EXPECT_EQ(line_of(kSwizzleStore, varying->related[2].first), 1);
  EXPECT_NE(varying->related[2].second.find("`mat4 modelMatrix`, a global (line 1): read as a matrix to absolute world"), std::string::npos);
}

// The value under an offset: its kind in words and its trail; nothing on a keyword or a value of
// unknown space.
TEST(Provenance, AValueAtAnOffsetIsDescribed) {
  std::string text = kSwizzleStore;
  Source source("a.vert", text);
  AnalyzeOptions options;
  std::optional<ValueDescription> p = describe_value(source, options, static_cast<uint32_t>(text.find("p.xyz;") + 2));
  ASSERT_TRUE(p);
  EXPECT_EQ(p->kind, Kind::absolute);
  EXPECT_EQ(source.slice(p->span), "p.xyz");
  EXPECT_NE(p->markdown.find("`p.xyz`: an absolute world position"), std::string::npos) << p->markdown;
  EXPECT_NE(p->markdown.find("from `p.xyz = (modelMatrix"), std::string::npos) << p->markdown;
  EXPECT_FALSE(describe_value(source, options, static_cast<uint32_t>(text.find("void"))));
  EXPECT_FALSE(describe_value(source, options, static_cast<uint32_t>(text.find("position;"))));
}

// A parameter is traced to the argument a call gives it (a store that the use is part of does not
// count as before it), and a function's return value to what it returns.
TEST(Provenance, ParametersAndReturnValuesAreTracedThroughTheirCalls) {
  const std::string code =
      "float4x4 World;\n"
      "float SampleHeight(float2 WorldXZ) { return WorldXZ.x * 0.5; }\n"
      "float4 VS(float3 P : POSITION) : SV_Position {\n"
      "  float4 worldPos = mul(float4(P, 1), World);\n"
      "  worldPos.y += SampleHeight(worldPos.xz);\n"
      "  return worldPos;\n"
      "}\n";
  std::vector<Finding> found = test::lint_text(code, Lang::hlsl, "lwc-float-world-position");
  const Finding *parameter = nullptr, *returned = nullptr;
  for (const Finding& f : found) {
    std::string_view at = std::string_view(code).substr(f.span.begin, f.span.end - f.span.begin);
    if (at == "WorldXZ") parameter = &f;
    if (at == "SampleHeight") returned = &f;
  }
  ASSERT_NE(parameter, nullptr);
  ASSERT_NE(returned, nullptr);
  std::vector<std::string> steps;
  for (const auto& [span, text] : parameter->related) steps.push_back(text);
  ASSERT_EQ(steps.size(), 4u);
  EXPECT_EQ(steps[0], "parameter `WorldXZ` (line 2), given `worldPos.xz` at line 5");
  EXPECT_EQ(steps[1], "`worldPos` = `mul(float4(P, 1), World)` (line 4)");
  EXPECT_EQ(steps[2], "through `mul` (line 4)");
  EXPECT_NE(steps[3].find("`float4x4 World`, a global (line 1)"), std::string::npos);
  ASSERT_FALSE(returned->related.empty());
  EXPECT_EQ(returned->related[0].second, "returns `WorldXZ.x * 0.5` (line 2)");
  EXPECT_EQ(returned->related[1].second, steps[0]);
}

}  // namespace
}  // namespace lwc
