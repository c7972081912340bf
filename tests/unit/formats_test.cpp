// Which files hold shader code, and GLSL read in place inside JavaScript and TypeScript.
#include <gtest/gtest.h>

#include <algorithm>

#include "fix/apply.h"
#include "lang/embedded.h"
#include "lang/formats.h"
#include "support.h"

namespace lwc {
namespace {

TEST(Formats, DefaultsCoverWhatEnginesShipAndAProjectCanChangeThem) {
  const FormatTable& d = FormatTable::defaults();
  for (const char* p : {"a.fxh", "b.cginc", "c.usf", "D.USH"}) EXPECT_EQ(d.for_path(p)->lang, Lang::hlsl) << p;
  for (const char* p : {"a.vsh", "b.fsh", "c.mesh", "d.task", "e.rgen", "f.rchit", "g.rmiss", "h.rahit", "i.rint", "j.rcall", "k.sc"})
    EXPECT_EQ(d.for_path(p)->lang, Lang::glsl) << p;
  EXPECT_EQ(d.for_path("shaders/tile.glsl.js")->container, Container::javascript);
  EXPECT_EQ(d.for_path("layer.ts")->container, Container::javascript);
  EXPECT_FALSE(d.for_path("x.cpp").has_value());
  EXPECT_FALSE(d.for_path("pointcloud.vs").has_value());
  FormatTable project = d;
  project.set(".vs", "glsl", "test");
  project.set(".ts", "none", "test");
  EXPECT_EQ(project.for_path("pointcloud.vs")->lang, Lang::glsl);
  EXPECT_FALSE(project.for_path("layer.ts").has_value());
  EXPECT_THROW(project.set("vs", "glsl", "test"), std::runtime_error);
  EXPECT_THROW(project.set(".vs", "metal", "test"), std::runtime_error);
}

// The stage extensions both languages use: the text decides (Diligent's and D3D samples' HLSL
// .vsh/.psh/.csh, iOS GLSL .vsh/.fsh); with no telling word, the extension's default; a project
// that names the extension has decided, whatever the text.
TEST(Formats, StageExtensionsBothLanguagesUseAreReadByTheirText) {
  const FormatTable& d = FormatTable::defaults();
  std::string hlsl = "cbuffer Camera { float4x4 ViewProj; };\nfloat4 main(float3 P : ATTRIB0) : SV_Position { return mul(float4(P, 1), ViewProj); }\n";
  std::string glsl = "#version 300 es\nin vec3 position;\nvoid main() { gl_Position = vec4(position, 1.0); }\n";
  for (const char* p : {"a.vsh", "b.psh", "c.csh", "d.fsh", "e.gsh"}) {
    EXPECT_EQ(d.for_path(p, hlsl)->lang, Lang::hlsl) << p;
    EXPECT_EQ(d.for_path(p, glsl)->lang, Lang::glsl) << p;
  }
  EXPECT_EQ(d.for_path("a.vsh", "void main() {}\n")->lang, Lang::glsl);
  EXPECT_EQ(d.for_path("b.psh", "void main() {}\n")->lang, Lang::hlsl);
  EXPECT_EQ(d.for_path("c.vert", hlsl)->lang, Lang::glsl);  // a stage only GLSL names keeps its language
  FormatTable project = d;
  project.set(".vsh", "glsl", "test");
  EXPECT_EQ(project.for_path("a.vsh", hlsl)->lang, Lang::glsl);
  // Read so, an HLSL .vsh parses and is linted as HLSL.
  int errors = 0;
  for (const Finding& f : analyze(Source("mesh.vsh", hlsl), {})) errors += f.rule == "lwc-input";
  EXPECT_EQ(errors, 0);
}

const char* kScript = R"(import {x} from './x';
const re = /`not a literal`/g;
const label = `plain text ${x}`;
export const vs = /* glsl */ `\
#version 300 es
uniform mat4 modelMatrix;
uniform vec3 cameraPosition;
${DECLARATIONS}
in vec3 position;
void main() {
  vec4 worldPosition = modelMatrix * vec4(position, ${ONE});
  gl_Position = worldPosition - vec4(cameraPosition, 0.0);
}
`;
export const fs = glsl`void main() { gl_FragColor = vec4(1.0); }`;
)";

// Vulkan's samples name HLSL stages .vert and .frag: read as GLSL they do not parse, and the note
// says what to do. GLSL that fails to parse keeps the usual hint.
TEST(Formats, HlslUnderAGlslExtensionIsToldHowToMapIt) {
  auto hint_for = [](const std::string& path, const std::string& code) {
    for (const Finding& f : analyze(Source(path, code), {}))
      if (f.rule == "lwc-input") return f.hint;
    return std::string("no note");
  };
  std::string hlsl = "cbuffer UBO : register(b0) { float4x4 mvp; };\nfloat4 main(float3 p : POSITION) : SV_POSITION { return mul(mvp, float4(p, 1)); }\n";
  EXPECT_NE(hint_for("mesh.vert", hlsl).find("reads as HLSL"), std::string::npos);
  EXPECT_EQ(hint_for("mesh.hlsl", hlsl), "no note");  // as HLSL it parses
  std::string broken_glsl = "#version 450\nvoid main() { gl_Position = vec4(1 +, 0, 0, 1); }\n";
  EXPECT_NE(hint_for("mesh.vert", broken_glsl).find("parse --verbose"), std::string::npos);
}

TEST(EmbeddedGlsl, TaggedCommentedAndVersionedLiteralsAreFound) {
  std::vector<Span> subs;
  auto literals = glsl_template_literals("layer.ts", kScript, subs);
  ASSERT_EQ(literals.size(), 2u);  // the plain-text literal and the regular expression are not GLSL
  std::string_view script = kScript;
  EXPECT_EQ(script.substr(literals[1].begin, 4), "void");
  EXPECT_EQ(subs.size(), 2u);
  std::string view = glsl_view(script, literals, subs);
  ASSERT_EQ(view.size(), script.size());
  EXPECT_EQ(view.find("import"), std::string::npos);
  EXPECT_EQ(view.find("DECLARATIONS"), std::string::npos);  // alone on its line: declarations, blank
  EXPECT_NE(view.find("vec4(position, ______)"), std::string::npos);  // inside a line: one value
  EXPECT_EQ(glsl_template_literals("tile.glsl.js", "export default `float f() { return 1.0; }`;\n").size(), 1u);
}

TEST(EmbeddedGlsl, UntaggedLiteralsAreFoundByTheirContent) {
  auto count = [](std::string_view script) { return glsl_template_literals("layer.ts", script).size(); };
  // A version line after a line continuation, a precision statement, a stage's output.
  EXPECT_EQ(count("const vs = `\\\n#version 300 es\nvoid main() {}\n`;\n"), 1u);
  EXPECT_EQ(count("const fs = `\nprecision highp float;\nvoid main() {}\n`;\n"), 1u);
  EXPECT_EQ(count("const vs = `attribute vec3 p; void foo() { gl_Position = vec4(p, 1.0); }`;\n"), 1u);
  EXPECT_EQ(count("const vs = `uniform mat4 m; in vec3 p; void main() { }`;\n"), 1u);
  // Text that only mentions GLSL's words is not GLSL.
  EXPECT_EQ(count("const html = `<div>void main</div>`;\nconst doc = `call main() to set gl_ state`;\n"), 0u);
}

TEST(EmbeddedGlsl, FindingsPointIntoTheScriptAndFixesStayInTheLiteral) {
  AnalyzeOptions o;
  Source script("layer.ts", kScript);
  auto findings = analyze(script, o);
  bool world = false;
  for (const Finding& f : findings) {
    EXPECT_NE(f.rule, "lwc-input") << f.message;
    if (f.rule == "lwc-float-world-position") {
      world = true;
      EXPECT_EQ(script.slice(f.span), "worldPosition");
      EXPECT_EQ(script.position(f.span.begin).line, 11);
      // The High/Low rewrite would add an #include at the top of the script: not offered.
      EXPECT_TRUE(f.fixes.empty());
    }
  }
  EXPECT_TRUE(world);
  EXPECT_TRUE(holds_shader_code(script, o));
  EXPECT_FALSE(holds_shader_code(Source("util.ts", "export const n = `${1}`;\n"), o));
}

// Each literal is a shader of its own: a uniform one literal uses with its translation is not
// reported in the other, which clears that translation first, though both declare the name.
TEST(EmbeddedGlsl, EachLiteralIsItsOwnShader) {
  const char* script =
      "const relativeToEye = glsl`\n"
      "uniform mat4 viewMatrix;\n"
      "in vec3 offsetFromEye;\n"
      "void main() {\n"
      "  mat4 rotationOnly = viewMatrix;\n"
      "  rotationOnly[3] = vec4(0.0, 0.0, 0.0, 1.0);\n"
      "  gl_Position = rotationOnly * vec4(offsetFromEye, 1.0);\n"
      "}`;\n"
      "const plain = glsl`\n"
      "uniform mat4 viewMatrix;\n"
      "in vec3 worldVertex;\n"
      "void main() { gl_Position = viewMatrix * vec4(worldVertex, 1.0); }`;\n";
  Source source("shaders.ts", script);
  std::vector<int> lines;
  for (const Finding& f : analyze(source, AnalyzeOptions{}))
    if (f.rule == "lwc-uniform-world-float") lines.push_back(source.position(f.span.begin).line);
  EXPECT_EQ(lines, std::vector<int>{10});
}

// A script assembles its literals into programs: a function one literal defines is known to the
// others (a uniform handed to it counts by what it does there), and a stage input holds what a
// sibling's stage output of that name holds.
TEST(EmbeddedGlsl, SiblingLiteralsAreModulesAndStages) {
  const char* script =
      "const fogModule = glsl`\n"
      "float fogAmount(vec3 eye, vec3 surfacePoint) { return 1.0 - exp(-distance(eye, surfacePoint)); }\n"
      "`;\n"
      "const vs = glsl`\n"
      "uniform mat4 modelMatrix;\n"
      "uniform mat4 viewProjectionMatrix;\n"
      "in vec3 position;\n"
      "out vec3 vPosition;\n"
      "void main() { vPosition = (modelMatrix * vec4(position, 1.0)).xyz; gl_Position = viewProjectionMatrix * vec4(vPosition, 1.0); }`;\n"
      "const fs = glsl`\n"
      "uniform vec3 eyePosition;\n"
      "in vec3 vPosition;\n"
      "out vec4 color;\n"
      "void main() { color = vec4(fogAmount(eyePosition, vPosition)); }`;\n";
  Source source("program.ts", script);
  std::vector<std::string> found;
  for (const Finding& f : analyze(source, AnalyzeOptions{}))
    if (f.rule != "lwc-input") found.push_back(std::to_string(source.position(f.span.begin).line) + " " + std::string(source.slice(f.span)));
  std::sort(found.begin(), found.end());
  EXPECT_EQ(found, (std::vector<std::string>{"11 eyePosition", "12 vPosition", "5 modelMatrix", "6 viewProjectionMatrix", "8 vPosition"}));
}

TEST(Bgfx, VaryingLinesAndSamplerMacrosParse) {
  std::string code =
      "$input a_position, a_normal\n$output v_pos\n#include <bgfx_shader.sh>\nSAMPLER2D(s_texColor, 0);\n"
      "uniform vec4 u_cameraPos;\nvoid main()\n{\n\tvec3 wpos = mul(u_model[0], vec4(a_position, 1.0)).xyz;\n"
      "\tv_pos = wpos - u_cameraPos.xyz;\n\tgl_Position = mul(u_viewProj, vec4(wpos, 1.0));\n}\n";
  Source src("vs_mesh.sc", code);
  EXPECT_EQ(parse(src, Lang::glsl).error_count, 0);
  auto findings = analyze(src, AnalyzeOptions{});
  EXPECT_TRUE(std::any_of(findings.begin(), findings.end(), [&](const Finding& f) {
    return f.rule == "lwc-float-world-position" && src.slice(f.span) == "wpos";
  }));
}

}  // namespace
}  // namespace lwc
