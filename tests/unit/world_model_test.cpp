#include <gtest/gtest.h>

#include "rules/analyze.h"
#include "support.h"

namespace lwc {
namespace {

// "line:col name" of each lwc-float-world-position finding.
std::vector<std::string> holders(const std::string& code, Lang lang = Lang::hlsl) {
  std::vector<std::string> out;
  Source src("t", code);
  for (const Finding& f : test::lint_text(code, lang, "lwc-float-world-position")) {
    Position p = src.position(f.span.begin);
    out.push_back(std::to_string(p.line) + ":" + std::to_string(p.column) + " " + std::string(src.slice(f.span)));
  }
  return out;
}

using V = std::vector<std::string>;

TEST(WorldModel, DirectionsAreNeverFlagged) {
  EXPECT_EQ(holders("void F(float3 N, float3 T) {\n"
                    "  float3 A = mul(float4(N, 0), Primitive.LocalToWorld).xyz;\n"
                    "  float3 B = mul(N, (float3x3)Primitive.LocalToWorld);\n"
                    "  float3x3 R = (float3x3)Primitive.LocalToWorld;\n"
                    "  float3 C = mul(T, R);\n"
                    "  float3 D = normalize(mul(float4(T, 1), Primitive.LocalToWorld).xyz - View.WorldCameraOrigin);\n"
                    "}\n"),
            V{});
  EXPECT_EQ(holders("uniform mat4 modelMatrix; in vec3 n; out vec3 o;\n"
                    "void main() { o = mat3(modelMatrix) * n; vec4 d = modelMatrix * vec4(n, 0.0); }\n",
                    Lang::glsl),
            V{});
}

TEST(WorldModel, FollowsLocalsSwizzlesAndCompoundAssignments) {
  EXPECT_EQ(holders("float3 F(float3 L) {\n"
                    "  float4 P = mul(float4(L, 1), Primitive.LocalToWorld);\n"
                    "  float3 Q = P.xyz;\n"
                    "  float3 T = Q;\n"
                    "  T += PrimaryView.PreViewTranslation;\n"
                    "  return T;\n"
                    "}\n"),
            (V{"2:10 P", "3:10 Q", "4:10 T"}));
}

TEST(WorldModel, TranslatedWorldIsNotAbsolute) {
  EXPECT_EQ(holders("float3 F(float3 L) {\n"
                    "  float3 T = mul(float4(L, 1), Primitive.LocalToTranslatedWorld).xyz;\n"
                    "  float3 U = T - View.TranslatedWorldCameraOrigin;\n"
                    "  float3 V = GetTranslatedWorldPosition(Parameters);\n"
                    "  return T + U + V;\n"
                    "}\n"),
            V{});
}

// Engine functions whose headers are absent, from rules/world-space.json "engine": vertex
// factories return translated world in every era (UE4 included), TransformLocalToWorld absolute.
TEST(WorldModel, EngineFunctionsByEraWithoutTheirHeaders) {
  EXPECT_EQ(holders("#include \"/Engine/Generated/VertexFactory.ush\"\n"
                    "void MainVS(FVertexFactoryInput Input, out float4 OutPosition : SV_POSITION) {\n"
                    "  FVertexFactoryIntermediates VFIntermediates = GetVertexFactoryIntermediates(Input);\n"
                    "  float4 WorldPos = VertexFactoryGetWorldPosition(Input, VFIntermediates);\n"
                    "  float3 Absolute = TransformLocalToWorld(Input.Position.xyz).xyz;\n"
                    "  OutPosition = mul(WorldPos, ResolvedView.TranslatedWorldToClip) + Absolute.x;\n"
                    "}\n"),
            V{"5:10 Absolute"});
}

TEST(WorldModel, FollowsParametersReturnsAndOutParametersWithinTheFile) {
  EXPECT_EQ(holders("float3 ToWorld(float3 L) { return mul(float4(L, 1), Primitive.LocalToWorld).xyz; }\n"
                    "float Fog(float3 P) { return length(P - ResolvedView.WorldCameraOrigin); }\n"
                    "void Get(float3 L, out float3 W) { W = ToWorld(L); }\n"
                    "float Main(float3 L) {\n"
                    "  float3 A;\n"
                    "  Get(L, A);\n"
                    "  return Fog(ToWorld(L)) + Fog(float3(0, 0, 0)) + length(A - ResolvedView.WorldCameraOrigin);\n"
                    "}\n"),
            (V{"1:8 ToWorld", "2:18 P", "3:31 W", "5:10 A"}));
}

TEST(WorldModel, StructFieldsAreReportedAtTheirDeclaration) {
  EXPECT_EQ(holders("struct VSOut { float4 Pos : SV_Position; float3 PosW : TEXCOORD0; };\n"
                    "VSOut VS(float3 L) { VSOut o; o.PosW = mul(float4(L, 1), World).xyz; o.Pos = 0; return o; }\n"
                    "float4 PS(VSOut i) : SV_Target { float3 d = i.PosW - EyePosW; return float4(d, 1); }\n"),
            (V{"1:49 PosW"}));
}

TEST(WorldModel, DoubleFloatTypesAreNotFloatHolders) {
  EXPECT_EQ(holders("FDFVector3 F(float3 L) { FDFVector3 W = DFMultiply(L, Primitive.LocalToWorld); return W; }\n"), V{});
}

TEST(WorldModel, GlslMatrixTimesPoint) {
  EXPECT_EQ(holders("uniform mat4 modelMatrix; in vec3 position; out vec3 vWorld;\n"
                    "void main() { vec4 w = modelMatrix * vec4(position, 1.0); vWorld = w.xyz; }\n",
                    Lang::glsl),
            (V{"1:54 vWorld", "2:20 w"}));
}

TEST(WorldModel, ProjectSourcesExtendTheBuiltInOnes) {
  std::string code = "float3 F(float3 L) { float3 P = mul(float4(L, 1), MyObjectToWorld).xyz; return 0; }\n";
  AnalyzeOptions o;
  o.lang = Lang::hlsl;
  o.select = {"lwc-float-world-position"};
  EXPECT_TRUE(analyze(Source("t", code), o).empty());
  o.world_sources = nlohmann::json::parse(R"([{"match": "MyObjectToWorld", "kind": "world-matrix"}])");
  EXPECT_EQ(analyze(Source("t", code), o).size(), 1u);
}

}  // namespace
}  // namespace lwc

namespace lwc {
namespace {

TEST(WorldModel, EveryPreprocessorBranchIsAnalysed) {
  std::string code =
      "float3 F(float3 L)\n{\n"
      "#if USE_DOUBLE\n"
      "\tFDFVector3 P = DFMultiply(L, Primitive.LocalToWorld);\n"
      "\treturn DFFastToTranslatedWorld(P, PrimaryView.PreViewTranslation);\n"
      "#elif USE_LEGACY\n"
      "\tfloat3 Q = mul(float4(L, 1), Primitive.LocalToWorld).xyz;\n"
      "\treturn Q + View.PreViewTranslation;\n"
      "#else\n"
      "\tfloat3 R = mul(float4(L, 1), Primitive.LocalToWorld).xyz;\n"
      "\treturn R;\n"
      "#endif\n}\n";
  std::vector<std::string> got;
  Source src("t", code);
  for (const Finding& f : test::lint_text(code, Lang::hlsl))
    got.push_back(std::to_string(src.position(f.span.begin).line) + " " + f.rule);
  EXPECT_EQ(got, (std::vector<std::string>{"1 lwc-float-world-position", "4 lwc-translated-world", "7 lwc-float-world-position",
                                           "8 lwc-primary-view", "10 lwc-float-world-position"}));
}

// A uniform declared in several #if arms is one name: the uses of every declaration count for
// each, read as its own declaration reads them (an element of the array, a component of the vector).
TEST(WorldModel, AUniformDeclaredInSeveralArmsIsJudgedByAllItsUsesAsEachArmDeclaresIt) {
  std::string code =
      "#if STEREO\nuniform vec3 cameraPosition[2];\n#elif MOBILE\nuniform vec3 cameraPosition;\n#else\nuniform vec3 cameraPosition;\n#endif\n"
      "in vec3 worldPos;\nout vec4 color;\n"
      "void main() {\n  color = vec4(cameraPosition[1] - worldPos, 1.0);\n}\n";
  std::vector<int> lines;
  Source src("t", code);
  for (const Finding& f : test::lint_text(code, Lang::glsl, "lwc-uniform-world-float")) lines.push_back(src.position(f.span.begin).line);
  EXPECT_EQ(lines, std::vector<int>{2});  // the right eye's position minus a world position; a vector's y is no position
}

}  // namespace
}  // namespace lwc

namespace lwc {
namespace {

// A GLSL stage output named as a world position is one, unless everything the shader stores into
// it is classified as something else: a constant says the name is wrong. A store the model cannot
// classify (a high/low sum it does not know) leaves the name as the evidence.
TEST(WorldModel, AStageOutputsStoresCanOverruleItsName) {
  auto flagged = [](const std::string& code) {
    for (const Finding& f : test::lint_text(code, Lang::glsl, "lwc-float-world-position"))
      if (f.message.find("`cameraPosition`") != std::string::npos) return true;
    return false;
  };
  EXPECT_FALSE(flagged("#version 300 es\nout vec3 cameraPosition;\nvoid main() { cameraPosition = vec3(1.0); gl_Position = vec4(0.0); }\n"));
  EXPECT_TRUE(flagged("#version 300 es\nuniform vec3 eyeHigh;\nuniform vec3 eyeLow;\nout vec3 cameraPosition;\n"
                      "void main() { cameraPosition = eyeHigh + eyeLow; gl_Position = vec4(0.0); }\n"));
  EXPECT_TRUE(flagged("#version 300 es\nuniform mat4 modelMatrix;\nin vec3 position;\nout vec3 cameraPosition;\n"
                      "void main() { cameraPosition = (modelMatrix * vec4(position, 1.0)).xyz; gl_Position = vec4(0.0); }\n"));
  // An input another stage of the program writes (a sibling template literal of a script) holds
  // what that stage stores: a constant there overrules its name here.
  auto flagged_in_script = [](const std::string& stored) {
    std::string code = "const vs = glsl`#version 300 es\nout vec3 cameraPosition;\nuniform mat4 modelMatrix;\nin vec3 position;\n"
                       "void main() { cameraPosition = " + stored + "; gl_Position = vec4(0.0); }`;\n"
                       "const fs = glsl`#version 300 es\nprecision highp float;\nin vec3 cameraPosition;\nout vec4 color;\n"
                       "void main() { color = vec4(cameraPosition, 1.0); }`;\n";
    int count = 0;
    for (const Finding& f : analyze(Source("program.js", code), AnalyzeOptions{}))
      count += f.rule == "lwc-float-world-position" && f.message.find("`cameraPosition`") != std::string::npos;
    return count;
  };
  EXPECT_EQ(flagged_in_script("vec3(1.0)"), 0);
  EXPECT_EQ(flagged_in_script("(modelMatrix * vec4(position, 1.0)).xyz"), 2);
  // An input has no store in this shader: its name is the evidence.
  EXPECT_TRUE(flagged("#version 300 es\nprecision highp float;\nin vec3 cameraPosition;\nout vec4 color;\n"
                      "void main() { color = vec4(cameraPosition, 1.0); }\n"));
}

}  // namespace
}  // namespace lwc

namespace lwc {
namespace {

// A comment between arguments (`/* out */ O`) is not an argument: each parameter gets what its
// own argument carries, and an out parameter hands its value back to the right variable.
TEST(WorldModel, ACommentBetweenArgumentsDoesNotShiftThemAgainstTheParameters) {
  std::string code =
      "float4x4 ObjectToWorld;\n"
      "void Place(float3 Local, /* the result */ out float3 Placed)\n{\n\tPlaced = mul(float4(Local, 1), ObjectToWorld).xyz;\n}\n"
      "float3 Run(float3 Local)\n{\n\tfloat3 P;\n\tPlace(/* in */ Local, /* out */ P);\n\treturn P - Local;\n}\n";
  std::vector<std::string> names;
  for (const Finding& f : test::lint_text(code, Lang::hlsl, "lwc-float-world-position")) names.push_back(f.message.substr(0, f.message.find(" (")));
  EXPECT_NE(std::find(names.begin(), names.end(), "variable `P`"), names.end()) << ::testing::PrintToString(names);
  EXPECT_EQ(std::find(names.begin(), names.end(), "parameter `Local`"), names.end()) << ::testing::PrintToString(names);
}

// A call whose argument count no definition has (the other arm of an `#if`'d header) gives no
// parameter the kinds of its arguments.
TEST(WorldModel, ACallMatchingNoDefinitionsArityGivesItsParametersNothing) {
  std::string code =
      "float4x4 ObjectToWorld;\n"
      "float3 Place(float3 Local, float4x4 InstanceToObject, float4x4 Transform)\n{\n\treturn mul(mul(float4(Local, 1), InstanceToObject), Transform).xyz;\n}\n"
      "float3 Run(float3 Local)\n{\n\treturn Place(Local, ObjectToWorld);\n}\n";
  for (const Finding& f : test::lint_text(code, Lang::hlsl, "lwc-float-world-position"))
    EXPECT_EQ(f.message.find("`InstanceToObject`"), std::string::npos) << f.message;
}

}  // namespace
}  // namespace lwc

namespace lwc {
namespace {

// The body of a material custom node (a `return` outside every function; Unreal pastes it into a
// generated function): its file-level declarations are that function's locals, not uniforms the
// host uploads. (Not a corpus file: a body does not compile on its own.)
TEST(WorldModel, CustomNodeBodiesDeclareLocalsNotUniforms) {
  std::string body =
      "float3 WorldPosition = PixelInput;\n"
      "float3 BoxLocal = WorldPosition - BoxCenter;\n"
      "return dot(BoxLocal, BoxLocal) < BoxRadius * BoxRadius ? 1 : 0;\n";
  auto rules = [](const std::vector<Finding>& findings) {
    std::vector<std::string> out;
    for (const Finding& f : findings) out.push_back(f.rule);
    return out;
  };
  EXPECT_EQ(rules(test::lint_text(body, Lang::hlsl)), std::vector<std::string>{"lwc-float-world-position"});
  // The same declaration in a file of functions is a uniform.
  std::string library = "float3 WorldPosition;\nfloat InBox(float3 BoxCenter) { return length(WorldPosition - BoxCenter); }\n";
  EXPECT_EQ(rules(test::lint_text(library, Lang::hlsl)), std::vector<std::string>{"lwc-uniform-world-float"});
}

}  // namespace
}  // namespace lwc
