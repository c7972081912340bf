#include <gtest/gtest.h>

#include "lang/hlsl_mask.h"
#include "lang/syntax.h"
#include "support.h"

namespace lwc {
namespace {

int errors(const std::string& code, Lang lang = Lang::hlsl) {
  Source src("t", code);
  return parse(src, lang).error_count;
}

TEST(HlslMask, KeepsEveryByteOffset) {
  std::string code =
      "cbuffer PerFrame : register(b0) { float4x4 World : packoffset(c0); };\n"
      "[numthreads(8, 8, 1)] void CS(uint3 Id : SV_DispatchThreadID) {}\n"
      "float4 PS(in float4 P : SV_Position, nointerpolation float3 N : TEXCOORD0) : SV_Target0 { precise float x = 1; return x; }\n";
  std::string masked = mask_hlsl(code).text;
  ASSERT_EQ(masked.size(), code.size());
  EXPECT_EQ(masked.find("SV_"), std::string::npos);
  EXPECT_EQ(masked.find("register"), std::string::npos);
  EXPECT_EQ(masked.find("numthreads"), std::string::npos);
  EXPECT_EQ(masked.find("nointerpolation"), std::string::npos);
  EXPECT_EQ(masked.substr(0, 9), "extern\"C\"");
  EXPECT_EQ(masked.find("mutable float x"), code.find("precise float x"));
  // Identifiers keep their places, so node text read from the original is right.
  EXPECT_EQ(masked.find("World"), code.find("World"));
  EXPECT_EQ(masked.find("PS("), code.find("PS("));
}

TEST(HlslMask, LeavesTernariesCaseLabelsBitfieldsAndBaseClassesAlone) {
  std::string code =
      "struct D : B { uint a : 4; };\n"
      "float F(float c, int k) { float r = c > 0 ? c : -c; switch (k) { case 1: r = 2; break; default: break; }\n"
      "  float q = (c ? (k ? 1 : 2) : 3); return r + q; }\n";
  EXPECT_EQ(mask_hlsl(code).text, code);
  EXPECT_EQ(errors(code), 0);
}

TEST(HlslMask, TypicalUnrealHlslParsesWithoutErrors) {
  std::string code = R"(#include "/Engine/Private/Common.ush"
cbuffer FogParams : register(b1)
{
	float4 FogColor;
	float FogDensity : packoffset(c1.x);
};
struct FVertexOutput
{
	float4 Position : SV_POSITION;
	nointerpolation float3 WorldNormal : TEXCOORD0;
	centroid float2 UV : TEXCOORD1;
};
groupshared float4 Cache[64];
[numthreads(8, 8, 1)]
void MainCS(uint3 DispatchId : SV_DispatchThreadID, uint GroupIndex : SV_GroupIndex)
{
	[unroll] for (int i = 0; i < 4; ++i) { Cache[GroupIndex] += 1; }
	[branch] if (GroupIndex == 0) { GroupMemoryBarrierWithGroupSync(); }
	UNROLL for (int j = 0; j < 2; ++j) { precise float s = 1.0f; }
}
void MainVS(in float3 LocalPos : ATTRIBUTE0, out FVertexOutput Out, inout float Depth : DEPTH)
{
	row_major float4x4 M = (float4x4)0;
	Out.Position = mul(float4(LocalPos, 1), M);
}
[maxvertexcount(3)] void MainGS(triangle FVertexOutput In[3], inout TriangleStream<FVertexOutput> Stream) {}
float4 MainPS(FVertexOutput In, bool bFront : SV_IsFrontFace) : SV_Target0 { return FogColor; }
)";
  EXPECT_EQ(errors(code), 0);
}

TEST(HlslMask, FindsAnUnterminatedComment) {
  auto r = mask_hlsl("float a; /* never closed\nfloat b;\n");
  ASSERT_TRUE(r.unterminated_comment.has_value());
  EXPECT_EQ(*r.unterminated_comment, 9u);
}

TEST(GlslFrontEnd, LayoutQualifiersBlocksPreciseAndInvariantParse) {
  std::string code = R"(#version 450
layout(location = 0) in vec3 position;
layout(std140, binding = 0) uniform Camera { mat4 viewProj; vec3 eye; } cam;
invariant gl_Position;
precise out vec3 vOut;
void main() { precise vec3 d = position - cam.eye; vOut = d; gl_Position = cam.viewProj * vec4(position, 1.0); }
)";
  EXPECT_EQ(errors(code, Lang::glsl), 0);
}

TEST(Languages, ExtensionsAndOverride) {
  for (const char* p : {"a.usf", "b.ush", "c.hlsl", "d.hlsli", "e.fx", "F.USF"}) EXPECT_EQ(lang_from_path(p), Lang::hlsl) << p;
  for (const char* p : {"a.glsl", "b.vert", "c.frag", "d.comp", "e.geom", "f.tesc", "g.tese"})
    EXPECT_EQ(lang_from_path(p), Lang::glsl) << p;
  EXPECT_FALSE(lang_from_path("x.cpp").has_value());
  EXPECT_FALSE(lang_from_path("dir.usf/file").has_value());
}

}  // namespace
}  // namespace lwc
