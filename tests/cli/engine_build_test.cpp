// "engine-shaders": `fix --check-build` compiles against the engine's own headers, lwcport standing
// in only for what Unreal's shader compiler generates. The engine here is a small folder written
// for these tests (tests/cli/engine_shaders), shaped as Unreal 5.4's.
#include <gtest/gtest.h>

#include <filesystem>

#include "support.h"

namespace fs = std::filesystem;

namespace lwc {
namespace {

// A project whose engine is a copy of the test engine beside it, named relative to the project.
std::string engine_project(const std::string& name, const std::string& extra_config = "") {
  std::string dir = test::scratch(name);
  fs::create_directories(dir + "/Engine");
  fs::copy(test::source_dir() + "/tests/cli/engine_shaders", dir + "/Engine/Shaders", fs::copy_options::recursive);
  test::write(dir + "/Project/.lwcport.json", "{\"engine-shaders\": \"../Engine/Shaders\"" + extra_config + "}\n");
  return dir + "/Project";
}

std::string fix_with_build_check(const std::string& dir, const std::string& file) {
  return test::run("cd " + dir + " && " + test::binary() + " fix --unsafe-fixes --check-build --color never " + file + " 2>&1").out;
}

// UE4 code in a project whose engine is 5.4: the original cannot compile against the engine's
// headers (View has no PreViewTranslation there), the port to translated world does.
const char* const kUe4Fog =
    "#include \"/Engine/Private/Common.ush\"\n"
    "float DistanceToCamera(float4 SvPosition)\n{\n"
    "\tfloat3 WorldPosition = SvPositionToTranslatedWorld(SvPosition) - View.PreViewTranslation;\n"
    "\treturn length(WorldPosition - View.WorldCameraOrigin);\n}\n";

TEST(EngineBuild, APortOfUe4CodeCompilesAgainstTheEnginesOwnHeaders) {
  std::string dir = engine_project("engine-port");
  test::write(dir + "/Fog.usf", kUe4Fog);
  std::string out = fix_with_build_check(dir, "Fog.usf");
  EXPECT_NE(out.find("build checked: the fixed file compiles as the original did (glslang, against the engine's headers (UE 5.4+; "
                     "lwcport stands in for what the shader compiler generates), which the original (UE4 code) did not)"),
            std::string::npos) << out;
  std::string fixed = test::read(dir + "/Fog.usf");
  EXPECT_NE(fixed.find("TranslatedWorldPosition - PrimaryView.TranslatedWorldCameraOrigin"), std::string::npos) << fixed;
}

// The engine's headers, not lwcport's stub: a function the stub has and this engine lacks fails.
TEST(EngineBuild, TheEnginesHeadersAreReadNotTheStub) {
  std::string dir = engine_project("engine-not-stub");
  test::write(dir + "/Far.usf",
              "#include \"/Engine/Private/Common.ush\"\n"
              "float3 CameraFar(float3 P)\n{\n\treturn P - DFHackToFloat(PrimaryView.WorldCameraOrigin);\n}\n"
              "float3 Offset(float3 TranslatedWorldPosition)\n{\n\treturn TranslatedWorldPosition - View.PreViewTranslation;\n}\n");
  std::string out = fix_with_build_check(dir, "Far.usf");
  EXPECT_NE(out.find("build not checked: the original does not compile where lwcport builds it (glslang, against the engine's headers"),
            std::string::npos) << out;
  EXPECT_NE(out.find("DFHackToFloat"), std::string::npos) << out;
}

// What lwcport does not stand in for is named, and the file is left unchecked, not "broken".
TEST(EngineBuild, AGeneratedHeaderWithoutAStandInLeavesTheFileUnchecked) {
  std::string dir = engine_project("engine-material");
  test::write(dir + "/Material.usf", std::string("#include \"/Engine/Generated/Material.ush\"\n") + kUe4Fog);
  std::string out = fix_with_build_check(dir, "Material.usf");
  EXPECT_NE(out.find("build not checked"), std::string::npos) << out;
  EXPECT_NE(out.find("/Engine/Generated/Material.ush"), std::string::npos) << out;
  EXPECT_EQ(out.find("fix held back"), std::string::npos) << out;
}

// The stand-ins say what they are, and the shader compiler's macros reach the engine's headers:
// without them Platform.ush stops the build.
TEST(EngineBuild, TheShaderCompilersMacrosAreStoodInForAndCanBeOverridden) {
  std::string dir = engine_project("engine-macros", ", \"defines\": {\"SM5_PROFILE\": 0}");
  test::write(dir + "/Fog.usf", kUe4Fog);
  std::string out = fix_with_build_check(dir, "Fog.usf");
  EXPECT_NE(out.find("the shader compiler defines the shader profile"), std::string::npos) << out;
  EXPECT_EQ(test::read(dir + "/Fog.usf").find("View.PreViewTranslation"), std::string::npos);  // not a break: the port is written
}

// The material template is the engine's own, its blanks filled as for a material with no
// expressions; a material helper is compiled after it, as its includers compile it.
TEST(EngineBuild, TheMaterialTemplateIsTheEnginesFilledInForADefaultMaterial) {
  std::string dir = engine_project("engine-material-template");
  test::write(dir + "/Wind.ush",
              "float3 WindOffset(FMaterialPixelParameters Parameters, float Time)\n{\n"
              "\tfloat3 WorldPosition = Parameters.TranslatedWorldPosition - View.PreViewTranslation;\n"
              "\treturn sin(WorldPosition * 0.01f + Time) * GetMaterialCustomData0(Parameters);\n}\n");
  std::string out = fix_with_build_check(dir, "Wind.ush");
  EXPECT_NE(out.find("build checked: the fixed file compiles"), std::string::npos) << out;
}

TEST(EngineBuild, TheEngineFolderSetsTheEraAndIsCheckedAgainstTheProjects) {
  std::string dir = engine_project("engine-era");
  test::write(dir + "/a.usf", "float3 F(float3 P)\n{\n\treturn P - View.WorldCameraOrigin;\n}\n");
  auto r = test::run("cd " + dir + " && " + test::binary() + " lint a.usf --color never 2>&1");
  EXPECT_NE(r.out.find("UE 5.4+"), std::string::npos) << r.out;  // the engine's era, with no "unreal" setting
  test::write(dir + "/.lwcport.json", "{\"engine-shaders\": \"../Engine/Shaders\", \"unreal\": \"5.0\"}\n");
  r = test::run("cd " + dir + " && " + test::binary() + " lint a.usf --color never 2>&1");
  EXPECT_NE(r.out.find("\"engine-shaders\" holds UE 5.4+'s headers but \"unreal\" says UE 5.0-5.3"), std::string::npos) << r.out;
  test::write(dir + "/.lwcport.json", "{\"engine-shaders\": \"../Nowhere\"}\n");
  r = test::run("cd " + dir + " && " + test::binary() + " lint a.usf --color never 2>&1");
  EXPECT_NE(r.out.find("\"engine-shaders\" is not an engine Shaders folder here"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace lwc
