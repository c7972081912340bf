// The DoubleFloat library compiles in both languages, with `precise` on its error-free steps, and
// emits only what a caller uses.
#include <gtest/gtest.h>

#include "shaderlib/shaderlib.h"
#include "verify/compile.h"

namespace lwc {
namespace {

CompileResult compile_library(Lang lang, const std::string& library, bool spirv) {
  CompileInput in;
  in.lang = lang;
  in.stage = Stage::compute;
  in.name = library_file_name(lang);
  in.spirv = spirv;
  if (lang == Lang::hlsl) {
    in.entry = "main";
    in.text = library + "\n[numthreads(1, 1, 1)] void main() {}\n";
  } else {
    in.text = "#version 450\n" + library + "\nlayout(local_size_x = 1) in;\nvoid main() {}\n";
  }
  return compile_shader(in);
}

TEST(ShaderLibrary, WholeLibraryCompilesInBothLanguagesToSpirv) {
  for (Lang lang : {Lang::hlsl, Lang::glsl}) {
    CompileResult r = compile_library(lang, full_library_text(lang), true);
    EXPECT_TRUE(r.ok) << lang_name(lang) << "\n" << format_messages(r);
    EXPECT_FALSE(r.spirv.empty());
  }
}

TEST(ShaderLibrary, CompilesInGlslEsWithoutPrecise) {
  CompileInput in;
  in.lang = Lang::glsl;
  in.stage = Stage::vertex;
  in.name = "es.vert";
  in.text = "#version 300 es\nprecision highp float;\n" + full_library_text(Lang::glsl) +
            "void main() { gl_Position = vec4(DFDemote(DFTwoSum(1.0, 1e-9)), 0.0, 0.0, 1.0); }\n";
  CompileResult r = compile_shader(in);
  EXPECT_TRUE(r.ok) << format_messages(r);
}

TEST(ShaderLibrary, EmitsOnlyWhatIsUsedWithItsDependencies) {
  std::string text = library_text(Lang::hlsl, {"DFFastLocalSubtractDemote"});
  EXPECT_NE(text.find("float3 DFFastLocalSubtractDemote(FDFVector3 A, FDFVector3 B)"), std::string::npos);
  EXPECT_NE(text.find("struct FDFVector3"), std::string::npos);
  EXPECT_EQ(text.find("DFTwoSum"), std::string::npos);
  EXPECT_EQ(text.find("DFMultiply"), std::string::npos);

  text = library_text(Lang::glsl, {"DFMultiply"});
  for (const char* needed : {"DFTwoProduct(", "DFTwoProductDekker(", "DFSplit(", "DFFastTwoSum(", "DFTwoSum(",
                             "struct FDFMatrix", "LWC_PRECISE vec3 C = 4097.0 * A;"})
    EXPECT_NE(text.find(needed), std::string::npos) << needed;
  EXPECT_EQ(text.find("DFDivide"), std::string::npos);
  EXPECT_TRUE(compile_library(Lang::glsl, text, true).ok);
}

TEST(ShaderLibrary, EveryErrorFreeStepIsPrecise) {
  // Each statement of TwoSum must be precise, or a reassociating driver returns Low = 0.
  std::string text = library_text(Lang::hlsl, {"DFTwoSum"});
  EXPECT_NE(text.find("precise float3 S = A + B;"), std::string::npos);
  EXPECT_NE(text.find("precise float3 V = S - A;"), std::string::npos);
  EXPECT_NE(text.find("precise float3 E = (A - (S - V)) + (B - V);"), std::string::npos);
}

TEST(ShaderLibrary, FindsTheNamesCodeUses) {
  auto used = library_names_used(Lang::hlsl, "FDFVector3 P = DFTwoSum(a, b); float DFTwoSumX = 0; // DFAdd\n");
  EXPECT_EQ(used, (std::set<std::string>{"DFAdd", "DFTwoSum", "FDFVector3"}));
}

TEST(ShaderLibrary, UnrealEnvironmentCompiles) {
  CompileResult r = compile_library(Lang::hlsl, unreal_environment_text(), false);
  EXPECT_TRUE(r.ok) << format_messages(r);
}

}  // namespace
}  // namespace lwc
