#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "lang/mask.h"
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
  std::string masked = mask_source(code, Lang::hlsl).text;
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
  EXPECT_EQ(mask_source(code, Lang::hlsl).text, code);
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
  auto r = mask_source("float a; /* never closed\nfloat b;\n", Lang::hlsl);
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
  // Memory qualifiers before a storage block or an image (GLSL 4.30).
  std::string storage = R"(#version 430
layout(std430, binding = 0) restrict buffer Lights { vec4 data[]; };
layout(std430, binding = 1) restrict readonly buffer Inputs { vec4 inputs[]; };
layout(rgba16f, binding = 2) restrict writeonly uniform image2D target;
layout(r32f, binding = 3) coherent volatile uniform image2D scratch;
layout(local_size_x = 8) in;
void main() { imageStore(target, ivec2(gl_GlobalInvocationID.xy), inputs[0] + data[0]); }
)";
  EXPECT_EQ(errors(storage, Lang::glsl), 0);
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

namespace lwc {
namespace {

// Every variant of a text: its masked text and its parse's error count.
struct Variant {
  std::string masked;
  int errors;
};
std::vector<Variant> variants(const std::string& code, Lang lang = Lang::hlsl, const MacroTable* macros = nullptr) {
  std::vector<Variant> out;
  Source src("t", code);
  for (int v = 0, n = 1; v < n; ++v) {
    MaskResult m = mask_source(code, lang, {macros, v});
    EXPECT_EQ(m.text.size(), code.size());
    n = m.variants;
    out.push_back({m.text, parse(src, lang, {macros, v}).error_count});
  }
  return out;
}

TEST(Conditionals, AGroupInsideAParameterListIsReadOneArmPerVariant) {
  std::string code =
      "float4 Main(\n#if A\n\tfloat3 P : POSITION,\n#else\n\tfloat4 P : POSITION,\n#endif\n\tfloat2 UV : TEXCOORD0) : SV_Target\n"
      "{ return 0; }\n";
  auto v = variants(code);
  ASSERT_EQ(v.size(), 2u);
  EXPECT_EQ(v[0].errors, 0);
  EXPECT_EQ(v[1].errors, 0);
  EXPECT_NE(v[0].masked.find("float3 P"), std::string::npos);
  EXPECT_EQ(v[0].masked.find("float4 P"), std::string::npos);
  EXPECT_NE(v[1].masked.find("float4 P"), std::string::npos);
  EXPECT_EQ(v[1].masked.find("#"), std::string::npos);
}

TEST(Conditionals, ElseAfterAGroupAndGroupsInsideExpressionsAndArgumentsAreResolved) {
  std::string code =
      "float F(float a, float b) {\n"
      "\tif (a > 0) { a = 1; }\n#if B\n\telse if (b > 0) { a = 2; }\n#endif\n\telse { a = 3; }\n"
      "\tfloat c = a\n#if C\n\t\t+ b\n#endif\n\t\t;\n"
      "\treturn max(c,\n#if D\n\t\ta\n#else\n\t\tb\n#endif\n\t);\n}\n";
  auto v = variants(code);
  ASSERT_EQ(v.size(), 2u);
  for (const Variant& x : v) EXPECT_EQ(x.errors, 0) << x.masked;
}

TEST(Conditionals, GroupsTheGrammarReadsStayAsTheyAreAndIfZeroIsNeverKept) {
  std::string native = "float F(float a) {\n#if A\n\ta += 1;\n#else\n\ta -= 1;\n#endif\n\treturn a;\n}\n";
  auto v = variants(native);
  ASSERT_EQ(v.size(), 1u);
  EXPECT_EQ(v[0].masked, native);
  EXPECT_EQ(v[0].errors, 0);
  std::string zero = "#if 0\nthis is not code (at all\n#endif\nfloat G() { return 1; }\n";
  auto z = variants(zero);
  ASSERT_EQ(z.size(), 1u);
  EXPECT_EQ(z[0].errors, 0);
  EXPECT_EQ(z[0].masked.find("not code"), std::string::npos);
}

TEST(Conditionals, ArmsThatOpenBlocksOfTheirOwnAreResolved) {
  std::string code = "#if A\nvoid F(int a) {\n#else\nvoid F() {\n#endif\n\tfloat x = 1;\n}\n";
  auto v = variants(code);
  ASSERT_EQ(v.size(), 2u);
  for (const Variant& x : v) EXPECT_EQ(x.errors, 0) << x.masked;
}

// A group is weighed with one arm of each group nested in it: the nested group is read per variant,
// the one around it by the grammar. Where one arm only is ever kept (`#if 0` / `#else`), only the
// dead arm and the directives are out of bounds for rewrites.
TEST(Conditionals, OnlyTheNestedGroupWhoseArmsOpenBlocksIsResolved) {
  std::string code = "#if OUTER\n#if A\nvoid F(int a) {\n#else\nvoid F() {\n#endif\n\tfloat x = 1;\n}\n#endif\n";
  MaskResult m = mask_source(code, Lang::hlsl, {nullptr, 0});
  ASSERT_EQ(m.resolved_conditionals.size(), 1u);
  EXPECT_EQ(m.resolved_conditionals[0].begin, code.find("#if A"));
  EXPECT_EQ(m.resolved_conditionals[0].end, code.find("\n\tfloat x"));
  ASSERT_EQ(m.kept_arms.size(), 1u);
  EXPECT_NE(code.substr(m.kept_arms[0].begin, m.kept_arms[0].end - m.kept_arms[0].begin).find("int a"), std::string::npos);
  for (const Variant& x : variants(code)) EXPECT_EQ(x.errors, 0) << x.masked;

  std::string dead = "float F(float a) {\n#if 0\n\ta = (a\n#else\n\ta = a * 2;\n#endif\n\treturn a;\n}\n";
  MaskResult d = mask_source(dead, Lang::hlsl, {nullptr, 0});
  EXPECT_EQ(d.variants, 1);
  ASSERT_EQ(d.resolved_conditionals.size(), 2u);
  size_t live = dead.find("a * 2");
  for (Span r : d.resolved_conditionals) EXPECT_FALSE(r.begin <= live && live < r.end);
  EXPECT_TRUE(d.kept_arms.empty());
}

// `#define X` with blanks after it (or a comment blanked there): the grammar took the next line as
// its value and lost the group's `#endif`. The line now breaks before the blanks; every other byte,
// the next line's `#endif` included, stays where it was. Both languages, LF and CRLF.
TEST(Conditionals, AnEmptyDefineWithTrailingBlanksKeepsTheNextLine) {
  for (Lang lang : {Lang::hlsl, Lang::glsl})
    for (std::string eol : {"\n", "\r\n"}) {
      std::string code = "#if A" + eol + "#define ATTR [x]" + eol + "#else" + eol + "#define ATTR \t " + eol + "#endif" + eol +
                         "float F(float a)" + eol + "{" + eol + "#if B" + eol + "\treturn a;" + eol + "#else" + eol + "\treturn -a;" + eol +
                         "#endif" + eol + "}" + eol;
      EXPECT_EQ(errors(code, lang), 0) << code;
      std::string masked = mask_source(code, lang).text;
      ASSERT_EQ(masked.size(), code.size());
      EXPECT_EQ(masked.find("#endif"), code.find("#endif"));
      EXPECT_EQ(masked.find("float F"), code.find("float F"));
    }
}

TEST(Macros, EachUseIsMaskedSoTheCodeParses) {
  std::string code =
      "struct FOut {\n\tINVARIANT_OUTPUT float4 Position : SV_POSITION;\n\tVF_GPUSCENE_DECLARE_INPUT_BLOCK(13)\n};\n"
      "RWTexture3D<UNORM float> Atlas;\n"
      "RWCoherentStructuredBuffer(uint) Centers;\n"
      "float F(Texture2D<uint2> Stencil, uint2 P) {\n"
      "\tuint s = Stencil.Load(uint3(P, 0)) STENCIL_COMPONENT_SWIZZLE;\n"
      "\tDECLARE_SCALAR_ARRAY(float, Weights, 5);\n"
      "\tUNROLL_N(3) for (int i = 0; i < 3; ++i) { s += i; }\n"
      "\tSubstrate_for(uint k = 0, k < s, ++k) { s -= 1; }\n"
      "\treturn s;\n}\n";
  auto v = variants(code);
  ASSERT_EQ(v.size(), 1u);
  EXPECT_EQ(v[0].errors, 0) << v[0].masked;
  EXPECT_NE(v[0].masked.find("for          (uint k = 0; k < s; ++k)"), std::string::npos) << v[0].masked;
  EXPECT_EQ(v[0].masked.find("STENCIL"), std::string::npos);
}

TEST(Macros, AFilesOwnDefinesTeachTheirUse) {
  std::string code =
      "#define MY_QUALIFIERS linear noperspective\n#define MY_SWIZZLE .x\n#define MY_UNROLL [unroll]\n"
      "#define MY_UNROLL_N(N) MY_UNROLL\n#define MY_OPTIONAL_ARG , in bool bFront : SV_IsFrontFace\n"
      "float4 Main(in MY_QUALIFIERS float4 P : SV_Position\n\tMY_OPTIONAL_ARG) : SV_Target {\n"
      "\tfloat4 c = P MY_SWIZZLE;\n\tMY_UNROLL_N(2) for (int i = 0; i < 2; ++i) { c += 1; }\n\treturn c;\n}\n";
  auto v = variants(code);
  ASSERT_EQ(v.size(), 1u);
  EXPECT_EQ(v[0].errors, 0) << v[0].masked;
  MacroTable learnt;
  learn_macros(code, known_macros(Lang::hlsl), learnt);
  EXPECT_EQ(learnt.at("MY_QUALIFIERS"), MacroUse::qualifier);
  EXPECT_EQ(learnt.at("MY_SWIZZLE"), MacroUse::suffix);
  EXPECT_EQ(learnt.at("MY_UNROLL"), MacroUse::attribute);
  EXPECT_EQ(learnt.at("MY_UNROLL_N"), MacroUse::attribute);
  EXPECT_EQ(learnt.at("MY_OPTIONAL_ARG"), MacroUse::qualifier);
}

TEST(Macros, AProjectTableNamesWhatNothingElseTells) {
  std::string code = "float4 Main(float4 P : SV_Position PROJECT_EXTRA) : SV_Target { return P; }\n";
  EXPECT_GT(variants(code)[0].errors, 0);
  MacroTable table = known_macros(Lang::hlsl);
  add_macros(nlohmann::json::parse(R"({"PROJECT_EXTRA": "qualifier"})"), "test", table);
  EXPECT_EQ(variants(code, Lang::hlsl, &table)[0].errors, 0);
  EXPECT_THROW(add_macros(nlohmann::json::parse(R"({"X": "keyword"})"), "test", table), std::runtime_error);
  EXPECT_THROW(add_macros(nlohmann::json::parse(R"({"1X": "qualifier"})"), "test", table), std::runtime_error);
}

TEST(Macros, CallLikeAndLoneMacrosWhereTheGrammarExpectsDeclarations) {
  std::string code =
      "SafeSaturate_Def(float2)\nSafeSaturate_Def(float3)\n"
      "LWC_COMPARE_OP(LWCGreater, >, FLWCType)\n"
      "#define SUFFIX(N) N##A\n"
      "SUFFIX(FEnergy) SUFFIX(ComputeEnergy)(float2 E) { FEnergy r; return r; }\n"
      "struct FInterpolants {\n\tfloat4 Color : COLOR0;\n\tTANGENTTOWORLD_INTERPOLATOR_BLOCK\n};\n"
      "PIXEL_EARLY_DEPTH_MACRO\nvoid Main() {}\n";
  auto v = variants(code);
  EXPECT_EQ(v[0].errors, 0) << v[0].masked;
}

TEST(Macros, NiagaraPlaceholdersAndBlanksAfterAContinuation) {
  std::string code =
      "%{vertex_interpolators}\n"
      "float {ParameterName}_Value;\n"
      "float Get{ParameterName}() { return {ParameterName}_Value; }\n"
      "float Init[2] = {Value, 2};\n"
      "#define TWO_LINES(x) \\  \n\tx + x\n"
      "float H() { return 1; }\n";
  auto v = variants(code);
  EXPECT_EQ(v[0].errors, 0) << v[0].masked;
  EXPECT_NE(v[0].masked.find("float _ParameterName__Value;"), std::string::npos);
  EXPECT_NE(v[0].masked.find("{Value, 2}"), std::string::npos);
}

}  // namespace
}  // namespace lwc

namespace lwc {
namespace {

TEST(GlslFrontEnd, WhatTheGrammarReadsBadlyIsMasked) {
  std::string code = R"(#version 310 es
precision highp float;
const float weights[] = float[](0.25, 0.5, 0.25);
highp float decode(highp vec4 rgba) { return rgba.x; }
float conv(in float[9] kernel, in float[9] data) { return kernel[0] * data[0]; }
layout(std140) uniform Cascades { mat4[4] cascadeViewProj; } ubo;
const float ALBEDO = float(${GROUND_ALBEDO}) / 3.14;
void main() {
  float n = 4.0;
  float scale = 1.0 - 0.5 * (float(n) / float(n - 1.0));
  #pragma unroll_loop
  for (int i = 0; i < 3; i++) { scale += 1.0; }
}
)";
  Source src("t.frag", code);
  SyntaxTree tree = parse(src, Lang::glsl);
  EXPECT_EQ(tree.error_count, 0) << mask_source(code, Lang::glsl).text;
  // The constructor's name is still read from the file.
  bool seen = false;
  for (int id = 0; id < static_cast<int>(tree.nodes.size()); ++id)
    if (tree.is(id, "call_expression") && tree.text(tree.child_by_field(id, "function")) == "float") seen = true;
  EXPECT_TRUE(seen);
}

}  // namespace
}  // namespace lwc

namespace lwc {
namespace {

TEST(Macros, OnlyAForWhoseHeaderIsTheParametersIsALoop) {
  MacroTable learnt;
  learn_macros("#define MY_FOR(X,Y,Z) [loop] for(X;Y;Z)\n"
               "#define MY_LOOP(F, G) /* whole loop */ for (int i = 0; i < 4; ++i) { F(i); G(i); }\n",
               {}, learnt);
  EXPECT_EQ(learnt.at("MY_FOR"), MacroUse::loop);
  EXPECT_EQ(learnt.count("MY_LOOP"), 0u);  // a statement macro: its call reads as a call
}

TEST(Macros, AMacroThatDefinesAFunctionIsReadAsOne) {
  std::string code =
      "#define LONG_LINE_MACRO(a, b) a + \\\n  /* a comment // with slashes */ \\\n  b\n"
      "RAY_TRACING_ENTRY_MISS(MainMS, FPayload, Payload)\n{\n\tfloat3 WorldPosition = TranslatedWorldRayOrigin();\n}\n";
  Source src("t.usf", code);
  SyntaxTree tree = parse(src, Lang::hlsl);
  EXPECT_EQ(tree.error_count, 0);
  int functions = 0;
  for (const Node& n : tree.nodes) functions += std::string_view(n.type) == "function_definition";
  EXPECT_EQ(functions, 1);
}

}  // namespace
}  // namespace lwc
