// `lwcport parse` and lint's lwc-input note count the same syntax errors: the same parse (the
// macros a file's includes define and the project's), each error once however many variants hold it.
#include <gtest/gtest.h>

#include <regex>

#include <nlohmann/json.hpp>

#include "support.h"

namespace lwc {
namespace {

// A qualifier macro from an include and one from the project; a missing `;`; text the parser
// cannot read; and an error in each arm of a group inside an argument list (one variant per arm).
const char* kHlsl = R"(#include "common.ush"

struct FVertexOutput
{
	INTERPOLATION_MODE float3 WorldNormal : TEXCOORD0;
	PROJECT_QUALIFIER float4 Position : SV_Position;
};

float Scale(float X, float Y) { return X * Y; }

float3 Shade(FVertexOutput In)
{
	float3 Light = In.WorldNormal * 2.0
	float Depth = ) In.Position.z;
	float Fade = Scale(Depth,
#if MOBILE
		1.0 +
#else
		2.0 *
#endif
		);
	return Light * Fade;
}
)";

const char* kGlsl = R"(#version 450
#include "common.glsl"

FLAT_VARYING in int vMaterial;
PROJECT_QUALIFIER in vec3 vWorldPos;
uniform vec3 uCameraPos;
out vec4 fragColor;

float weight(float a, float b) { return a * b; }

void main() {
  vec3 toCamera = uCameraPos - vWorldPos
  float d = length(toCamera) ];
  float w = weight(d,
#ifdef HIGH_QUALITY
    0.5 /
#else
    0.25
#endif
  );
  fragColor = vec4(vec3(w), 1.0);
}
)";

// An `#if 0` arm is no code: its text is no error. One error after it.
const char* kDisabled = "float F(float X)\n{\n#if 0\n\treturn X +;\n#else\n\treturn X * 2.0;\n#endif\n}\nfloat G(float X) { return X }\n";

struct Counted {
  int count = -1;                           // what the file's line says
  std::vector<std::pair<int, int>> listed;  // each error --verbose lists: line, column
};

Counted parse_verbose(const std::string& dir, const std::string& file) {
  test::Run r = test::run("cd " + dir + " && " + test::binary() + " parse --verbose " + file + " 2>&1");
  Counted c;
  std::smatch m;
  if (std::regex_search(r.out, m, std::regex(file + ": (\\d+) syntax error\\(s\\)"))) c.count = std::stoi(m[1]);
  else if (r.out.find("0 with syntax errors") != std::string::npos) c.count = 0;
  std::regex line(file + ":(\\d+):(\\d+): syntax error: ");
  for (auto it = std::sregex_iterator(r.out.begin(), r.out.end(), line); it != std::sregex_iterator(); ++it)
    c.listed.emplace_back(std::stoi((*it)[1]), std::stoi((*it)[2]));
  return c;
}

// Lint's syntax-error note: its count and where it points.
std::pair<int, std::pair<int, int>> lint_note(const std::string& dir, const std::string& file) {
  test::Run r = test::run("cd " + dir + " && " + test::binary() + " lint " + file + " --format json --fail-on none 2>/dev/null");
  nlohmann::json doc = nlohmann::json::parse(r.out);
  for (const auto& f : doc.at("findings")) {
    std::string message = f.at("message");
    if (f.at("rule") == "lwc-input" && message.find("syntax error") != std::string::npos)
      return {std::stoi(message), {f.at("start").at("line"), f.at("start").at("column")}};
  }
  return {0, {0, 0}};
}

TEST(SyntaxErrors, ParseAndLintCountTheSameErrors) {
  std::string dir = test::scratch("syntax-errors");
  test::write(dir + "/.lwcport.json", R"({"macros": {"PROJECT_QUALIFIER": "qualifier"}})");
  test::write(dir + "/common.ush", "#define INTERPOLATION_MODE nointerpolation\n");
  test::write(dir + "/common.glsl", "#define FLAT_VARYING flat\n");
  test::write(dir + "/a.usf", kHlsl);
  test::write(dir + "/b.frag", kGlsl);
  test::write(dir + "/c.hlsl", kDisabled);
  struct Expected {
    std::string file;
    std::vector<std::pair<int, int>> errors;
  };
  for (const Expected& e : {Expected{"a.usf", {{13, 37}, {14, 16}, {17, 7}, {19, 7}}},
                            Expected{"b.frag", {{12, 41}, {13, 30}, {16, 9}}},
                            Expected{"c.hlsl", {{9, 28}}}}) {
    SCOPED_TRACE(e.file);
    Counted parsed = parse_verbose(dir, e.file);
    EXPECT_EQ(parsed.listed, e.errors);  // the macros lines read, and each error once
    EXPECT_EQ(parsed.count, static_cast<int>(e.errors.size()));
    auto [count, at] = lint_note(dir, e.file);
    EXPECT_EQ(count, parsed.count);
    EXPECT_EQ(at, e.errors.front());
  }
  // Without the project's macro, both see one more error, on its line.
  test::write(dir + "/.lwcport.json", "{}");
  Counted parsed = parse_verbose(dir, "a.usf");
  EXPECT_EQ(parsed.count, 5);
  EXPECT_EQ(parsed.listed.front().first, 6);
  EXPECT_EQ(lint_note(dir, "a.usf").first, 5);
}

// A D3D9 effect file: its technique and sampler_state blocks are not parsed, and the note says so
// rather than sending the user to declare a macro; the shader functions around them are read.
TEST(SyntaxErrors, EffectFrameworkBlocksAreNamedAsTheCause) {
  std::string dir = test::scratch("effect-framework");
  test::write(dir + "/Mesh.fx",
              "float4x4 WorldViewProjection;\ntexture DiffuseMap;\n"
              "sampler DiffuseSampler = sampler_state { Texture = <DiffuseMap>; MinFilter = Linear; };\n"
              "float4 MeshVS(float3 Position : POSITION) : POSITION { return mul(float4(Position, 1), WorldViewProjection); }\n"
              "float4 MeshPS(float2 UV : TEXCOORD0) : COLOR0 { return tex2D(DiffuseSampler, UV); }\n"
              "technique Mesh\n{\n\tpass P0\n\t{\n\t\tVertexShader = compile vs_3_0 MeshVS();\n"
              "\t\tPixelShader = compile ps_3_0 MeshPS();\n\t}\n}\n");
  auto r = test::run("cd " + dir + " && " + test::binary() + " lint Mesh.fx --color never 2>&1");
  EXPECT_NE(r.out.find("syntax error(s) the parser could not place"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("the file holds Direct3D effect-framework blocks"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("a macro used as syntax"), std::string::npos) << r.out;
}

// A template an engine's own preprocessor fills in (`@name` placeholders): the note names them as
// the cause; an `@` inside a comment or a string is no placeholder.
TEST(SyntaxErrors, TemplatePlaceholdersAreNamedAsTheCause) {
  std::string dir = test::scratch("template-placeholders");
  test::write(dir + "/water.frag", "#version 120\n// see user@example\nuniform sampler2D normalMap;\n"
                                   "void main() { gl_FragColor = texture2D(normalMap, gl_TexCoord[@normalMapUV].xy); }\n");
  test::write(dir + "/plain.frag", "#version 120\n// mail: user@example\nvoid main() { gl_FragColor = vec4(1.0) +; }\n");
  auto r = test::run("cd " + dir + " && " + test::binary() + " lint water.frag --color never 2>&1");
  EXPECT_NE(r.out.find("the file holds `@name` placeholders"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("a macro used as syntax"), std::string::npos) << r.out;
  auto plain = test::run("cd " + dir + " && " + test::binary() + " lint plain.frag --color never 2>&1");
  EXPECT_NE(plain.out.find("syntax error(s) the parser could not place"), std::string::npos) << plain.out;
  EXPECT_EQ(plain.out.find("`@name` placeholders"), std::string::npos) << plain.out;
}

}  // namespace
}  // namespace lwc
