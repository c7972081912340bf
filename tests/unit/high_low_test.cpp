// The High/Low rewrite of plain HLSL/GLSL (LWC-BRIEF §7): what it writes, that the result compiles
// with the library, and why it holds back where it cannot follow a value.
#include <gtest/gtest.h>

#include "fix/apply.h"
#include "shaderlib/shaderlib.h"
#include "support.h"
#include "verify/compile.h"

namespace lwc {
namespace {

FixOutcome fix_all(const std::string& path, const std::string& code) {
  AnalyzeOptions options;
  options.lang = lang_from_path(path);
  options.select = {"lwc-float-world-position"};
  return fix_source(Source(path, code), options, true);
}

// Compiles fixed code with the library `lwcport fix` writes beside it.
CompileResult compile_with_library(const std::string& path, const std::string& text, Stage stage, const std::string& entry) {
  CompileInput in;
  in.lang = *lang_from_path(path);
  in.stage = stage;
  in.name = path;
  in.text = text;
  in.entry = entry;
  // What `lwcport fix` writes: the names the fixed text uses, and their dependencies.
  in.include = [lang = in.lang, text](const std::string& name, const std::string&) -> std::optional<IncludedFile> {
    if (name == library_file_name(lang)) return IncludedFile{name, library_text(lang, library_names_used(lang, text))};
    return std::nullopt;
  };
  return compile_shader(in);
}

const char* kPlainHlsl =
    "// plain D3D\n"
    "cbuffer PerObject : register(b0)\n"
    "{\n"
    "\trow_major float4x4 World;\n"
    "\trow_major float4x4 ViewProj;\n"
    "\tfloat3 EyePosW;\n"
    "};\n"
    "\n"
    "float4 VS(float3 Pos : POSITION, out float Dist : TEXCOORD0) : SV_Position\n"
    "{\n"
    "\tfloat3 worldPos = mul(float4(Pos, 1.0f), World).xyz;\n"
    "\tworldPos.y += 2.0f;\n"
    "\tDist = distance(worldPos, EyePosW);\n"
    "\treturn mul(float4(worldPos, 1.0f), ViewProj);\n"
    "}\n";

TEST(HighLow, SplitsTheWorldMatrixFollowsEveryUseAndCompiles) {
  FixOutcome out = fix_all("a.hlsl", kPlainHlsl);
  EXPECT_EQ(out.text,
            "// plain D3D\n"
            "#include \"lwc_doublefloat.hlsl\"\n"
            "cbuffer PerObject : register(b0)\n"
            "{\n"
            "\tFDFVector3 CameraTranslation;\n"
            "\trow_major float3x3 WorldRotationScale;\n"
            "\tFDFVector3 WorldTranslation;\n"
            "\trow_major float4x4 TranslatedViewProj;\n"
            "\tfloat3 EyePosW;\n"
            "};\n"
            "\n"
            "float4 VS(float3 Pos : POSITION, out float Dist : TEXCOORD0) : SV_Position\n"
            "{\n"
            "\tfloat3 translatedWorldPos = mul(Pos, WorldRotationScale) + DFFastLocalSubtractDemote(WorldTranslation, CameraTranslation);\n"
            "\ttranslatedWorldPos.y += 2.0f;\n"
            "\tDist = length(translatedWorldPos);\n"
            "\treturn mul(float4(translatedWorldPos, 1.0f), TranslatedViewProj);\n"
            "}\n");
  CompileResult r = compile_with_library("a.hlsl", out.text, Stage::vertex, "VS");
  EXPECT_TRUE(r.ok) << format_messages(r);
}

TEST(HighLow, TheFixListsTheNewUniformsAndTheHostChange) {
  std::vector<Finding> findings = test::lint_text(kPlainHlsl, Lang::hlsl, "lwc-float-world-position");
  ASSERT_EQ(findings.size(), 1u);
  ASSERT_EQ(findings[0].fixes.size(), 1u);
  const Fix& fix = findings[0].fixes[0];
  EXPECT_EQ(fix.applicability, Applicability::unsafe);
  EXPECT_EQ(fix.strategy, "translated");
  EXPECT_EQ(fix.library, (std::vector<std::string>{"FDFVector3", "DFFastLocalSubtractDemote"}));
  ASSERT_GE(fix.notes.size(), 3u);
  EXPECT_NE(fix.notes[0].find("`float3x3 WorldRotationScale` (the rotation-scale part of `World`)"), std::string::npos) << fix.notes[0];
  EXPECT_NE(fix.notes[1].find("High = (float)d and Low = (float)(d - (double)High)"), std::string::npos) << fix.notes[1];
  EXPECT_NE(fix.notes[2].find("`TranslatedViewProj` replaces `ViewProj`"), std::string::npos) << fix.notes[2];
}

TEST(HighLow, TwoWorldMatricesInOneFileDeclareTheCameraOnce) {
  std::string code =
      "#version 450\n"
      "uniform mat4 modelMatrix;\n"
      "uniform mat4 u_world;\n"
      "uniform vec3 cameraPosition;\n"
      "in vec3 position;\n"
      "out vec3 vOffsetA;\n"
      "out vec3 vOffsetB;\n"
      "void main() {\n"
      "  vec3 worldA = (modelMatrix * vec4(position, 1.0)).xyz;\n"
      "  vec3 worldB = (u_world * vec4(position, 1.0)).xyz;\n"
      "  vOffsetA = worldA - cameraPosition;\n"
      "  vOffsetB = worldB - cameraPosition;\n"
      "}\n";
  FixOutcome out = fix_all("a.vert", code);
  EXPECT_EQ(out.applied, 2);
  size_t first = out.text.find("uniform FDFVector3 cameraTranslation;");
  ASSERT_NE(first, std::string::npos) << out.text;
  EXPECT_EQ(out.text.find("uniform FDFVector3 cameraTranslation;", first + 1), std::string::npos) << out.text;
  EXPECT_NE(out.text.find("vOffsetA = translatedWorldA;"), std::string::npos) << out.text;
  CompileResult r = compile_with_library("a.vert", out.text, Stage::vertex, "main");
  EXPECT_TRUE(r.ok) << format_messages(r) << out.text;
}

TEST(HighLow, WithheldWhereAUseCannotBeFollowedSayingWhy) {
  auto withheld = [](const std::string& code) {
    std::vector<Finding> findings = test::lint_text(code, Lang::glsl, "lwc-float-world-position");
    for (const Finding& f : findings)
      if (f.message.find("`worldPosition`") != std::string::npos) return f.fixes.empty() ? f.withheld.front() : std::string("fixed");
    return std::string("no finding");
  };
  std::string head = "#version 450\nuniform mat4 modelMatrix;\nin vec3 position;\nout float vHeight;\nfloat terrain(vec3 p);\n";
  EXPECT_EQ(withheld(head + "void main() {\n  vec4 worldPosition = modelMatrix * vec4(position, 1.0);\n  vHeight = terrain(worldPosition.xyz);\n}\n"),
            "translated world: it is passed to `terrain` (line 8), which expects an absolute position");
  EXPECT_EQ(withheld(head + "void main() {\n  vec4 worldPosition = modelMatrix * vec4(position, 1.0);\n  vHeight = modelMatrix[3].y;\n}\n"),
            "translated world: `modelMatrix` is read elsewhere too, and only this transform can use its High/Low split");
  EXPECT_EQ(withheld("#version 450\nlayout(location = 2) uniform mat4 modelMatrix;\nin vec3 position;\nout vec3 vOut;\n"
                     "void main() {\n  vec4 worldPosition = modelMatrix * vec4(position, 1.0);\n  vOut = worldPosition.xyz;\n}\n"),
            "translated world: `modelMatrix` has a layout qualifier, and lwcport does not choose locations for new uniforms");
}

}  // namespace
}  // namespace lwc
