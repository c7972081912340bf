// The harness kernel builder: which values a function reads and writes, and how textures and
// `out` parameters reach the input and output records.
#include <gtest/gtest.h>

#include <algorithm>

#include "verify/compile.h"
#include "verify/kernel.h"
#include "verify/kernel_builder.h"

namespace lwc {
namespace {

const Leaf* find_leaf(const std::vector<Leaf>& leaves, const std::string& path) {
  auto it = std::find_if(leaves.begin(), leaves.end(), [&](const Leaf& l) { return l.path == path; });
  return it == leaves.end() ? nullptr : &*it;
}

// The kernel compiles with glslang (HLSL), the error and the source shown when it does not.
void ExpectKernelCompiles(const HarnessKernel& k, bool float64) {
  KernelSpec spec;
  spec.lang = Lang::hlsl;
  spec.name = "kernel.usf";
  spec.declarations = k.declarations;
  spec.body = k.body;
  spec.in_stride = k.in_stride;
  spec.out_stride = k.out_stride;
  spec.float64 = float64;
  CompileResult compiled = compile_kernel(spec);
  EXPECT_TRUE(compiled.ok) << format_messages(compiled) << kernel_source(spec);
}

TEST(KernelBuilder, HlslOutAndInoutParametersAreResults) {
  std::string text = "void Split(float3 WorldPosition, out float3 High, inout float3 Low : TEXCOORD0)\n"
                     "{\n\tHigh = WorldPosition;\n\tLow += WorldPosition - High;\n}\n";
  HarnessKernel k = build_harness_kernel(Lang::hlsl, text, "Split", false);
  ASSERT_EQ(k.problem, "");
  EXPECT_NE(find_leaf(k.inputs, "lwc_p0"), nullptr);
  EXPECT_EQ(find_leaf(k.inputs, "lwc_p1"), nullptr);  // `out`: written only
  EXPECT_NE(find_leaf(k.inputs, "lwc_p2"), nullptr);  // `inout`: both
  EXPECT_EQ(find_leaf(k.outputs, "lwc_p0"), nullptr);
  EXPECT_NE(find_leaf(k.outputs, "lwc_p1"), nullptr);
  EXPECT_NE(find_leaf(k.outputs, "lwc_p2"), nullptr);
}

TEST(KernelBuilder, HlslTextureSamplesBecomeOneValuePerInvocation) {
  std::string text = "Texture2D<float> HeightMap : register(t0);\nSamplerState LinearSampler;\nTexture2D Albedo;\n"
                     "RWTexture2D<float4> Output;\n"
                     "float Shade(float2 UV)\n{\n\tfloat h = HeightMap.SampleLevel(LinearSampler, UV * 2.0, 0) * 100.0;\n"
                     "\tOutput[uint2(UV)] = Albedo.Sample(LinearSampler, float2(UV.x, (UV.y))) * h;\n\treturn h;\n}\n";
  HarnessKernel k = build_harness_kernel(Lang::hlsl, text, "Shade", false);
  ASSERT_EQ(k.problem, "");
  const Leaf* height = find_leaf(k.inputs, "lwc_texel_HeightMap");
  ASSERT_NE(height, nullptr);
  EXPECT_EQ(height->type, "float");
  const Leaf* albedo = find_leaf(k.inputs, "lwc_texel_Albedo");
  ASSERT_NE(albedo, nullptr);
  EXPECT_EQ(albedo->components, 4);
  EXPECT_NE(find_leaf(k.outputs, "lwc_texel_Output"), nullptr);  // a RW texture is written
  EXPECT_EQ(find_leaf(k.outputs, "lwc_texel_Albedo"), nullptr);
  EXPECT_EQ(k.declarations.find("SampleLevel"), std::string::npos) << k.declarations;
  EXPECT_EQ(k.declarations.find("SamplerState"), std::string::npos) << k.declarations;
  EXPECT_NE(k.declarations.find("lwc_texel_Output = lwc_texel_Albedo * h;"), std::string::npos) << k.declarations;
}

// Real plugin code hands textures and samplers to helpers and keeps them in structs, splits a
// buffer over `inout T x[2][4]` parameters, and uses groupshared scratch arrays: each becomes
// something the kernel can hold, and the kernel compiles, float32 and float64.
// A global struct holding a texture and a sampler (Unreal's `View.PerlinNoiseGradientTexture`) is
// filled member by member: the texture with its texel's value, the sampler with an int, as the
// kernel declares them.
TEST(KernelBuilder, AGlobalStructWithTextureMembersIsFilled) {
  std::string text = "struct FViewUniforms\n{\n\tfloat4 ViewSizeAndInvSize;\n\tTexture2D NoiseTexture;\n\tSamplerState NoiseSampler;\n"
                     "};\nFViewUniforms View;\n"
                     "float4 Noise(float2 UV)\n{\n\treturn View.NoiseTexture.SampleLevel(View.NoiseSampler, UV, 0) * View.ViewSizeAndInvSize;\n}\n";
  for (bool float64 : {false, true}) {
    HarnessKernel k = build_harness_kernel(Lang::hlsl, float64 ? promote_to_double(Lang::hlsl, text) : text, "Noise", float64);
    ASSERT_EQ(k.problem, "");
    const Leaf* texture = find_leaf(k.inputs, "View.NoiseTexture");
    const Leaf* sampler = find_leaf(k.inputs, "View.NoiseSampler");
    ASSERT_NE(texture, nullptr);
    ASSERT_NE(sampler, nullptr);
    EXPECT_EQ(texture->components, 4);
    EXPECT_TRUE(sampler->integer);
    ExpectKernelCompiles(k, float64);
  }
}

TEST(KernelBuilder, TexturesPassedOnArrayParametersAndGroupsharedScratchBuild) {
  std::string text =
      "struct FResources\n{\n\tTexture2D<float4> Irradiance;\n\tSamplerState Bilinear;\n};\n"
      "Texture2D<float4> ProbeIrradiance;\nSamplerState LinearClampSampler;\n"
      "groupshared float Scratch[2 * 8];\n"
      "float4 Fetch(Texture2D<float4> Tex, SamplerState S, float2 UV) { return Tex.SampleLevel(S, UV, 0); }\n"
      "float4 FetchFrom(FResources R, float2 UV) { return R.Irradiance.SampleLevel(R.Bilinear, UV, 0); }\n"
      "void Unpack(inout float2 Values[2][4], uint I)\n{\n\tScratch[I] = Values[0][I].x;\n\tValues[1][I] = Values[0][I] * Scratch[I];\n}\n"
      "float4 Shade(float2 UV, inout float2 Values[2][4])\n{\n\tFResources R;\n\tR.Irradiance = ProbeIrradiance;\n"
      "\tR.Bilinear = LinearClampSampler;\n\tUnpack(Values, 1u);\n"
      "\treturn Fetch(ProbeIrradiance, LinearClampSampler, UV) + FetchFrom(R, UV);\n}\n";
  for (bool float64 : {false, true}) {
    HarnessKernel k = build_harness_kernel(Lang::hlsl, float64 ? promote_to_double(Lang::hlsl, text) : text, "Shade", float64);
    ASSERT_EQ(k.problem, "");
    EXPECT_NE(find_leaf(k.inputs, "lwc_texel_ProbeIrradiance"), nullptr);
    EXPECT_NE(find_leaf(k.inputs, "lwc_p1[1][3]"), nullptr);   // every element of the array parameter
    EXPECT_NE(find_leaf(k.outputs, "lwc_p1[1][3]"), nullptr);  // and it is a result (inout)
    for (const Leaf& l : k.inputs) EXPECT_EQ(l.path.find("Scratch"), std::string::npos) << "groupshared is not an input: " << l.path;
    EXPECT_EQ(k.declarations.find("SampleLevel"), std::string::npos) << k.declarations;
    ExpectKernelCompiles(k, float64);
  }
}

// A finding inside an entry point written through an engine macro belongs to the function the
// macro defines, not to the macro (the report once named `RACING_ENTRY_RAYGEN`).
TEST(KernelBuilder, AnEntryPointWrittenThroughAMacroIsNamedByItsArgument) {
  std::string text = "RaytracingAccelerationStructure TLAS;\nRAY_TRACING_ENTRY_RAYGEN(ProbeUpdateRGS)\n{\n\tfloat3 P = 1;\n}\n"
                     "float3 Plain(float3 X) { return X; }\n";
  std::vector<std::string> names = enclosing_functions(Lang::hlsl, text, {static_cast<uint32_t>(text.find("float3 P")),
                                                                         static_cast<uint32_t>(text.find("return X"))});
  EXPECT_EQ(names, (std::vector<std::string>{"ProbeUpdateRGS", "Plain"}));
}

TEST(KernelBuilder, GlslSamplersAndImagesBecomeOneValuePerInvocation) {
  std::string text = "#version 450\nuniform sampler2D heightMap;\nlayout(rgba32f) uniform image2D outImage;\n"
                     "float store(vec2 uv) {\n  vec4 h = texture(heightMap, uv * vec2(2.0, 1.0));\n"
                     "  imageStore(outImage, ivec2(uv), h * 2.0);\n  return h.r;\n}\nvoid main() {}\n";
  HarnessKernel k = build_harness_kernel(Lang::glsl, text, "store", false);
  ASSERT_EQ(k.problem, "");
  EXPECT_NE(find_leaf(k.inputs, "lwc_texel_heightMap"), nullptr);
  EXPECT_NE(find_leaf(k.outputs, "lwc_texel_outImage"), nullptr);
  EXPECT_NE(k.declarations.find("vec4 h = lwc_texel_heightMap;"), std::string::npos) << k.declarations;
  EXPECT_NE(k.declarations.find("(lwc_texel_outImage =  h * 2.0);"), std::string::npos) << k.declarations;
  // The reference's copy is double.
  HarnessKernel reference = build_harness_kernel(Lang::glsl, promote_to_double(Lang::glsl, text), "store", true);
  ASSERT_EQ(reference.problem, "");
  EXPECT_EQ(find_leaf(reference.inputs, "lwc_texel_heightMap")->type, "dvec4");
}

// Interface blocks become private variables the kernel fills (a block left as written would
// alias the kernel's own buffers); runtime-sized arrays hold one element, read at index 0.
TEST(KernelBuilder, GlslInterfaceBlocksAndUniformArraysAreFilled) {
  std::string text = "#version 450\nstruct Bounds { vec4 centerRadius; };\n"
                     "layout(std430, binding = 0) readonly buffer In { Bounds bounds[]; };\n"
                     "layout(std430, binding = 1) buffer Out { uint visible[]; };\n"
                     "layout(std140, binding = 2) uniform View { mat4 viewProjection; vec3 cameraPosition; } view;\n"
                     "uniform vec4 planes[6];\n"
                     "void main() {\n  uint i = gl_GlobalInvocationID.x;\n"
                     "  vec3 d = bounds[i].centerRadius.xyz - view.cameraPosition;\n"
                     "  visible[i] = dot(planes[2].xyz, d) > 0.0 ? 1u : 0u;\n}\n";
  HarnessKernel k = build_harness_kernel(Lang::glsl, text, "main", false);
  ASSERT_EQ(k.problem, "");
  EXPECT_NE(find_leaf(k.inputs, "bounds[0].centerRadius"), nullptr);
  EXPECT_NE(find_leaf(k.inputs, "view.cameraPosition"), nullptr);
  EXPECT_EQ(find_leaf(k.inputs, "view.viewProjection"), nullptr);  // never read: zero, not drawn
  EXPECT_NE(k.body.find("view.viewProjection = mat4(0, 0,"), std::string::npos) << k.body;
  EXPECT_NE(find_leaf(k.inputs, "planes[5]"), nullptr);
  EXPECT_EQ(find_leaf(k.inputs, "planes[6]"), nullptr);
  EXPECT_NE(find_leaf(k.outputs, "visible[0]"), nullptr);          // a writable buffer's members are results
  EXPECT_EQ(find_leaf(k.outputs, "bounds[0].centerRadius"), nullptr);  // a readonly one's are not
  EXPECT_NE(k.declarations.find("bounds[0].centerRadius.xyz"), std::string::npos) << k.declarations;
  EXPECT_NE(k.declarations.find("visible[0] = "), std::string::npos) << k.declarations;
  EXPECT_EQ(k.declarations.find("binding"), std::string::npos) << k.declarations;
}

// The builder reads text by tokens in one pass: a 40,000-character name, a 2,000-member struct and
// runs of 100,000 blanks cost no stack (std::regex recursed once per matched character and
// overflowed this thread's stack on each of them).
TEST(KernelBuilder, LongNamesWideStructsAndLongBlanksCostNoStack) {
  std::string name(40000, 'x'), blanks(100000, ' '), members;
  for (int i = 0; i < 2000; ++i) members += "\tfloat m" + std::to_string(i) + ";\n";
  std::string text = "#version" + blanks + "450\nprecision" + blanks + "highp float;\nstruct Big {\n" + members + "};\nuniform Big big;\n"
                     "uniform float " + name + ";\nuniform sampler2D tex;\n"
                     "float Wide(vec3 p)" + blanks + "{ return big.m1999 + " + name + " + sin" + blanks + "(p.x) + texture" + blanks +
                     "(tex, p.xy).x; }\n";
  std::string promoted = promote_to_double(Lang::glsl, text);
  EXPECT_NE(promoted.find("lwc_f32_sin" + blanks + "(p.x)"), std::string::npos);
  EXPECT_EQ(promoted.find("precision"), std::string::npos);
  HarnessKernel k = build_harness_kernel(Lang::glsl, promoted, "Wide", true);
  ASSERT_EQ(k.problem, "");
  EXPECT_NE(find_leaf(k.inputs, "big.m1999"), nullptr);
  EXPECT_NE(find_leaf(k.inputs, name), nullptr);
  EXPECT_EQ(std::count_if(k.inputs.begin(), k.inputs.end(), [](const Leaf& l) { return l.path.starts_with("big."); }), 1);
  EXPECT_NE(k.body.find("big.m1998 = double(0);"), std::string::npos);
  EXPECT_NE(k.declarations.find("+ lwc_texel_tex.x;"), std::string::npos);
  EXPECT_EQ(k.declarations.find("#version"), std::string::npos);
}

// Only the members the function's code reads are drawn per invocation (Unreal's View struct has
// hundreds; records of all of them made verify 16 times slower); the others are set to zero, the
// same in every variant. A struct handed whole to a callee keeps the members the callee reads.
TEST(KernelBuilder, MembersTheFunctionNeverReadsAreZeroNotDrawn) {
  std::string text = "struct Inner { float3 Origin; float Unused; };\n"
                     "struct ViewData { float4x4 Skipped; Inner Camera; float3 Direction; };\n"
                     "ViewData View;\n"
                     "float3 Eye(Inner c) { return c.Origin; }\n"
                     "float3 Offset(float3 P) { return P - Eye(View.Camera) + View.Direction; }\n";
  HarnessKernel k = build_harness_kernel(Lang::hlsl, text, "Offset", false);
  ASSERT_EQ(k.problem, "");
  EXPECT_NE(find_leaf(k.inputs, "View.Camera.Origin"), nullptr);
  EXPECT_NE(find_leaf(k.inputs, "View.Direction"), nullptr);
  EXPECT_EQ(find_leaf(k.inputs, "View.Camera.Unused"), nullptr);
  EXPECT_EQ(find_leaf(k.inputs, "View.Skipped"), nullptr);
  EXPECT_NE(k.body.find("View.Camera.Unused = float(0);"), std::string::npos) << k.body;
  EXPECT_NE(k.body.find("View.Skipped = float4x4(0, 0,"), std::string::npos) << k.body;
  // The record holds the drawn leaves only, packed.
  EXPECT_EQ(k.in_stride, 3 + 3 + 3);
}

// Struct fields as the harness reads them: qualifiers skipped, several declarators, arrays and
// semantics; a declarator it cannot read is left out without losing its neighbours.
TEST(KernelBuilder, StructFieldsWithQualifiersArraysAndSemantics) {
  std::string text = "struct VSOut { nointerpolation float3 A : TEXCOORD0, B[2]; float4 Pos : SV_POSITION; float C = 1, D; };\n"
                     "VSOut Make(float3 P) { VSOut o; o.A = P; o.B[0] = P; o.B[1] = P; o.Pos = float4(P, 1); o.D = P.x; return o; }\n";
  HarnessKernel k = build_harness_kernel(Lang::hlsl, text, "Make", false);
  ASSERT_EQ(k.problem, "");
  const Leaf* a = find_leaf(k.outputs, "lwc_result.A");
  ASSERT_NE(a, nullptr);
  EXPECT_EQ(a->semantic, "TEXCOORD0");
  EXPECT_NE(find_leaf(k.outputs, "lwc_result.B[1]"), nullptr);
  EXPECT_EQ(find_leaf(k.outputs, "lwc_result.Pos")->semantic, "SV_POSITION");
  EXPECT_EQ(find_leaf(k.outputs, "lwc_result.C"), nullptr);
  EXPECT_NE(find_leaf(k.outputs, "lwc_result.D"), nullptr);
}

TEST(KernelBuilder, PromotesEveryFloatTypeAndNothingElse) {
  EXPECT_EQ(promote_to_double(Lang::hlsl, "float a; half3 b; min16float2x3 c; float3x4 d; floatx e; float_t f; uint2 g; // float\n"),
            "double a; double3 b; double2x3 c; double3x4 d; floatx e; float_t f; uint2 g; // float\n");
  EXPECT_EQ(promote_to_double(Lang::glsl, "precision highp float;\nprecision highp int;\nvec3 a; mat4x3 b; ivec2 c; dvec2 d; float e = pow(x, 2.0);"),
            "\nprecision highp int;\ndvec3 a; dmat4x3 b; ivec2 c; dvec2 d; double e = lwc_f32_pow(x, 2.0);");
}

}  // namespace
}  // namespace lwc
