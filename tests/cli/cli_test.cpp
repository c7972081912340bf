// End-to-end: the lwcport binary, its formats, exit codes, options, config and suppressions.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "support.h"

namespace lwc {
namespace {

const char* kBad =
    "float3 F(float3 L)\n{\n\tfloat3 W = mul(float4(L, 1), Primitive.LocalToWorld).xyz;\n\treturn W - View.WorldCameraOrigin;\n}\n";

test::Run lint(const std::string& dir, const std::string& args) {
  return test::run("cd " + dir + " && " + test::binary() + " lint " + args + " 2>/dev/null");
}

TEST(Cli, TextFormatHasPositionSourceLineCaretAndHint) {
  std::string dir = test::scratch("text");
  test::write(dir + "/a.usf", kBad);
  auto r = lint(dir, "a.usf --color never");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.out.find("a.usf:4:13: error: `View.WorldCameraOrigin` is absolute world space"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("[lwc-primary-view]\n    4 | \treturn W - View."), std::string::npos) << r.out;
  // The caret line keeps the tab so it lines up under the span, and spans its 22 characters.
  EXPECT_NE(r.out.find("      | \t" + std::string(11, ' ') + "^" + std::string(21, '~') + "\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("= help: use `PrimaryView.WorldCameraOrigin`"), std::string::npos);
  EXPECT_NE(r.out.find("Found 3 finding(s) in 1 file(s): 2 error(s), 1 warning(s), 0 note(s)."), std::string::npos);
  EXPECT_EQ(r.out.find("\x1b["), std::string::npos);
  EXPECT_NE(lint(dir, "a.usf --color always").out.find("\x1b[1;31merror:"), std::string::npos);
}

TEST(Cli, ExitCodesFollowFailOn) {
  std::string dir = test::scratch("exit");
  test::write(dir + "/note.usf", "float3 F(FDFVector3 P) { return DFDemote(DFAdd(P, P)); }\n");
  test::write(dir + "/clean.glsl", "void main() {}\n");
  EXPECT_EQ(lint(dir, "clean.glsl").exit_code, 0);
  EXPECT_EQ(lint(dir, "note.usf").exit_code, 0);  // notes do not fail by default
  EXPECT_EQ(lint(dir, "note.usf --fail-on note").exit_code, 1);
  EXPECT_EQ(lint(dir, "note.usf --fail-on none").exit_code, 0);
  EXPECT_EQ(lint(dir, "note.usf --fail-on bogus").exit_code, 2);
  EXPECT_EQ(lint(dir, "--select no-such-rule note.usf").exit_code, 2);
  EXPECT_EQ(test::run(test::binary() + " frobnicate 2>/dev/null").exit_code, 2);
}

TEST(Cli, SelectIgnoreAndLangOverride) {
  std::string dir = test::scratch("select");
  test::write(dir + "/a.txt", kBad);
  auto all = nlohmann::json::parse(lint(dir, "a.txt --lang hlsl --format json").out);
  EXPECT_EQ(all["findings"].size(), 2u);  // W, and View.WorldCameraOrigin
  auto only = nlohmann::json::parse(lint(dir, "a.txt --lang hlsl --format json --select lwc-primary-view").out);
  ASSERT_EQ(only["findings"].size(), 1u);
  EXPECT_EQ(only["findings"][0]["rule"], "lwc-primary-view");
  auto ignored = nlohmann::json::parse(lint(dir, "a.txt --lang=hlsl --format=json --ignore lwc-primary-view").out);
  ASSERT_EQ(ignored["findings"].size(), 1u);
  EXPECT_EQ(ignored["findings"][0]["rule"], "lwc-float-world-position");
  // Without --lang, an unknown extension is a clear per-file error.
  auto unknown = nlohmann::json::parse(lint(dir, "a.txt --format json").out);
  EXPECT_EQ(unknown["findings"][0]["rule"], "lwc-input");
}

TEST(Cli, JsonFormatIsDocumented) {
  std::string dir = test::scratch("json");
  test::write(dir + "/a.usf", kBad);
  auto doc = nlohmann::json::parse(lint(dir, "a.usf --format json").out);
  EXPECT_EQ(doc["version"], 1);
  EXPECT_EQ(doc["tool"]["name"], "lwcport");
  EXPECT_EQ(doc["files"], 1);
  EXPECT_EQ(doc["summary"]["error"], 2);  // the primitive's matrix used as a float, and View's camera origin
  EXPECT_EQ(doc["summary"]["warning"], 1);
  EXPECT_EQ(doc["findings"][1]["rule"], "lwc-large-world-member");
  const auto& f = doc["findings"][2];
  EXPECT_EQ(f["path"], "a.usf");
  EXPECT_EQ(f["rule"], "lwc-primary-view");
  EXPECT_EQ(f["start"], (nlohmann::json{{"line", 4}, {"column", 13}}));
  EXPECT_EQ(f["end"], (nlohmann::json{{"line", 4}, {"column", 35}}));
  EXPECT_TRUE(f["message"].is_string() && f["hint"].is_string());
}

TEST(Cli, GithubAnnotations) {
  std::string dir = test::scratch("github");
  test::write(dir + "/a,b.usf", kBad);
  auto r = lint(dir, "a,b.usf --format github");
  EXPECT_NE(r.out.find("::error file=a%2Cb.usf,line=4,col=13,endLine=4,endColumn=35,title=lwc-primary-view::`View.WorldCameraOrigin`"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("::warning file=a%2Cb.usf,line=3,col=9,"), std::string::npos) << r.out;
}

TEST(Cli, ConfigFoundUpwardSetsSeverityExcludesAndWorldSources) {
  std::string dir = test::scratch("config");
  test::write(dir + "/.lwcport.json", R"({
    "severity": {"lwc-float-world-position": "error"},
    "exclude": ["generated/", "*.skip.usf"],
    "world-sources": [{"match": "MyObjectToWorld", "kind": "world-matrix", "languages": ["hlsl"]}]
  })");
  test::write(dir + "/src/a.usf", "float3 F(float3 L) { float3 P = mul(float4(L, 1), MyObjectToWorld).xyz; return 0; }\n");
  test::write(dir + "/src/generated/b.usf", kBad);
  test::write(dir + "/src/c.skip.usf", kBad);
  auto doc = nlohmann::json::parse(lint(dir, "src --format json").out);
  EXPECT_EQ(doc["files"], 1);
  ASSERT_EQ(doc["findings"].size(), 1u);
  EXPECT_EQ(doc["findings"][0]["path"], "src/a.usf");
  EXPECT_EQ(doc["findings"][0]["severity"], "error");

  test::write(dir + "/.lwcport.json", R"({"severity": {"lwc-nope": "error"}})");
  auto r = test::run("cd " + dir + " && " + test::binary() + " lint src 2>&1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.out.find(".lwcport.json: unknown rule id \"lwc-nope\""), std::string::npos) << r.out;
  test::write(dir + "/.lwcport.json", "{ \"exclude\": [1, }");
  r = test::run("cd " + dir + " && " + test::binary() + " lint src 2>&1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.out.find(".lwcport.json: invalid JSON at byte"), std::string::npos) << r.out;
}

// Every value of .lwcport.json is checked before any work: the file, the key and why, exit 2.
TEST(Cli, AConfigValueOfTheWrongTypeOrMeaningStopsTheRunWithItsReason) {
  std::string dir = test::scratch("bad-config");
  test::write(dir + "/a.usf", "float3 F() { return View.WorldCameraOrigin; }\n");
  const std::pair<const char*, const char*> cases[] = {
      {R"({"world-sources": [{"match": "X.Y", "kind": "absolute-position", "languages": [5]}]})", "world-sources[0]: unknown language 5"},
      {R"({"world-sources": [{"match": "X.Y", "kind": "absolute-position", "languages": ["metal"]}]})", "unknown language \"metal\""},
      {R"({"world-sources": [{"match": "", "kind": "absolute-position"}]})", "\"match\" must be a non-empty path pattern"},
      {R"({"world-sources": [{"match": "A", "kind": "absolute-position", "langs": ["hlsl"]}]})", "unknown key \"langs\""},
      {R"({"world-sources": [{"match": "A", "kind": "far-away"}]})", "unknown world-space kind \"far-away\""},
      {R"({"max-file-bytes": 0})", "\"max-file-bytes\" must be a positive integer"},
      {R"({"max-parse-seconds": 0})", "\"max-parse-seconds\" must be a number of seconds above 0"},
      {R"({"virtual-roots": {"Engine": "Shaders"}})", "a prefix starts and ends with '/'"},
      {R"({"world-sources": [{"match": "View..Origin", "kind": "absolute-position"}]})", "\"View..Origin\" can match nothing: an empty name"},
      {R"({"world-sources": [{"match": "View.Camera Origin", "kind": "absolute-position"}]})", "holds ' ', which no name has"},
      {R"({"world-sources": [{"match": "GetPos(Id).X", "kind": "absolute-position"}]})", "a call is written `Name(..)`"},
      {R"({"exclude": ["../Generated/**"]})", "exclude pattern \"../Generated/**\" can match nothing"},
      {R"({"exclude": [""]})", "\"exclude\" holds an empty pattern"},
      {R"({"defines": ["X"]})", "\"defines\" must map macro names to values"},
      {R"({"defines": {"X": [1]}})", "the value of \"X\" must be a string, a number or a boolean"},
      {R"({"overrides": [{"defines": {"X": 1}}]})", "overrides[0] needs \"files\" and \"defines\""},
      {R"({"overrides": [{"files": [], "defines": {}}]})", "overrides[0]: \"files\" must be a non-empty array of patterns"},
      {R"({"overrides": [{"files": ["a.usf"], "defines": {}, "severity": {}}]})", "overrides[0]: unknown key \"severity\""},
  };
  for (const auto& [config, why] : cases) {
    test::write(dir + "/.lwcport.json", config);
    auto r = test::run("cd " + dir + " && " + test::binary() + " lint a.usf 2>&1");
    EXPECT_EQ(r.exit_code, 2) << config << "\n" << r.out;
    EXPECT_NE(r.out.find(".lwcport.json: "), std::string::npos) << r.out;
    EXPECT_NE(r.out.find(why), std::string::npos) << config << "\n" << r.out;
  }
}

// Settings that are valid but look wrong are warned about once, and the run goes on.
TEST(Cli, AnIncludeDirThatIsNotThereIsAWarning) {
  std::string dir = test::scratch("config-warning");
  test::write(dir + "/a.usf", "float F(float3 P) { return P.x; }\n");
  std::string outside = test::scratch("config-warning-engine");
  test::write(dir + "/.lwcport.json", R"({"include-dirs": ["Shaders/Shared", "/", ")" + outside + R"(", ")" + dir +
              R"(", "../)" + std::filesystem::path(outside).filename().string() + R"("], "virtual-roots": {"/Engine/": ")" + outside + R"("}})");
  auto r = test::run("cd " + dir + " && " + test::binary() + " lint a.usf 2>&1");
  EXPECT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find(".lwcport.json: include dir \"Shaders/Shared\" is not a folder here"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("include dir \"/\" is the file system's root"), std::string::npos) << r.out;
  // An absolute folder outside the project is warned (one machine's layout); the project's own
  // folder by its absolute path, and a relative folder outside, are not.
  EXPECT_NE(r.out.find("include dir \"" + outside + "\" is an absolute path outside the project"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("virtual root \"/Engine/\" is an absolute path outside the project"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("include dir \"" + dir + "\""), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("include dir \"../"), std::string::npos) << r.out;
  // A plugin's virtual root may name the engine's folder beside it; one that is not there is warned.
  test::write(dir + "/.lwcport.json", R"({"virtual-roots": {"/Engine/": "../)" + std::filesystem::path(outside).filename().string() +
              R"(/", "/Plugin/Gone/": "../no-such-plugin/Shaders/"}})");
  r = test::run("cd " + dir + " && " + test::binary() + " lint a.usf 2>&1");
  EXPECT_EQ(r.exit_code, 0) << r.out;
  EXPECT_EQ(r.out.find("virtual root \"/Engine/\""), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("virtual root \"/Plugin/Gone/\" is not a folder here"), std::string::npos) << r.out;
}

TEST(Cli, IncludesTeachDeclarationsAndMissingOnesAreFine) {
  std::string dir = test::scratch("includes");
  test::write(dir + "/.lwcport.json", R"({"virtual-roots": {"/Engine/": "engine"}, "include-dirs": ["shared"]})");
  test::write(dir + "/engine/Private/Scene.ush", "float3 GetPivot() { return mul(float4(0, 0, 0, 1), Primitive.LocalToWorld).xyz; }\n");
  test::write(dir + "/shared/Helpers.ush", "float3 GetAnchor() { return EyePosW; }\n");
  test::write(dir + "/a.usf",
              "#include \"/Engine/Private/Scene.ush\"\n#include \"Helpers.ush\"\n#include \"/Engine/Missing.ush\"\n"
              "float F() { float3 P = GetPivot(); float3 Q = GetAnchor(); return 0; }\n");
  auto doc = nlohmann::json::parse(lint(dir, "a.usf --format json").out);
  ASSERT_EQ(doc["findings"].size(), 2u) << doc.dump(2);
  EXPECT_EQ(doc["findings"][0]["start"]["column"], 20);
  EXPECT_EQ(doc["findings"][1]["start"]["column"], 43);
}

// An engine function whose position UE5 takes in translated world keeps that contract where the
// engine's own folder defines it (the UE4 engine a plugin builds against today); a function of the
// project's own header under an engine name takes what its declaration says. A value named as
// translated is not taken for UE4 code's absolute point.
TEST(Cli, AnEngineFunctionKeepsItsUe5ContractWhereTheEngineFolderDefinesIt) {
  std::string dir = test::scratch("engine-contracts");
  test::write(dir + "/.lwcport.json", R"({"unreal": "5.4", "virtual-roots": {"/Engine/": "Engine/Shaders"}})");
  test::write(dir + "/Engine/Shaders/Private/Lights.ush",
              "float GetLocalLightAttenuation(float3 WorldPosition, float R) { return length(WorldPosition) * R; }\n"
              "float ShadowRayTraceThroughCulledObjects(float3 WorldRayStart, float3 WorldRayEnd) { return length(WorldRayEnd - WorldRayStart); }\n");
  test::write(dir + "/Plugin/Shaders/Own.ush", "float GetCloudVolumetricShadow(float3 WorldPosition) { return WorldPosition.z; }\n");
  test::write(dir + "/Plugin/Shaders/a.usf",
              "#include \"/Engine/Private/Lights.ush\"\n#include \"Own.ush\"\n"
              "float F(float3 L, float3 TranslatedWorldPosition) {\n"
              "  float3 P = mul(float4(L, 1), Primitive.LocalToWorld).xyz;\n"
              "  return GetLocalLightAttenuation(P, 1) + GetCloudVolumetricShadow(P) + ShadowRayTraceThroughCulledObjects(L, P)\n"
              "       + GetLocalLightAttenuation(TranslatedWorldPosition, 1);\n}\n");
  auto doc = nlohmann::json::parse(lint(dir, "Plugin/Shaders/a.usf --format json --fail-on none").out);
  std::vector<std::string> got;
  for (const auto& f : doc["findings"])
    if (f["rule"] == "lwc-translated-parameter")
      got.push_back(std::to_string(f["start"]["line"].get<int>()) + ":" + std::to_string(f["start"]["column"].get<int>()));
  // `L` is what UE4 code hands a UE4 engine function: an absolute point, whatever it is called.
  EXPECT_EQ(got, (std::vector<std::string>{"5:35", "5:108", "5:111"})) << doc.dump(2);
}

// The engine's own file defines the engine's function: in UE4 its `WorldPosition` held an absolute
// point (whatever it is called), so porting the engine's shaders moves it to translated world
// with its uses. A project's own copy of the function takes what it declares, and is left alone.
TEST(Cli, TheEnginesOwnDefinitionOfAnEngineFunctionTakesItsUe4Contract) {
  std::string dir = test::scratch("engine-definitions");
  test::write(dir + "/.lwcport.json", R"({"unreal": "5.4"})");
  std::string lights =
      "float GetLocalLightAttenuation(float3 WorldPosition, float3 LightPosition, float InvRadius)\n"
      "{\n\treturn saturate(1 - length(LightPosition - WorldPosition) * InvRadius) * length(WorldPosition - View.WorldCameraOrigin);\n}\n";
  test::write(dir + "/Engine/Shaders/Private/Lights.ush", lights);
  test::write(dir + "/Plugin/Shaders/Lights.ush", lights);
  auto doc = nlohmann::json::parse(lint(dir, "Engine/Shaders/Private/Lights.ush Plugin/Shaders/Lights.ush --format json --fail-on none").out);
  std::vector<std::string> got;
  for (const auto& f : doc["findings"])
    if (f["rule"] == "lwc-float-world-position")
      got.push_back(f["path"].get<std::string>() + ":" + std::to_string(f["start"]["line"].get<int>()) + " " +
                    (f.contains("fix") ? f["fix"]["title"].get<std::string>() : "no fix"));
  EXPECT_EQ(got, (std::vector<std::string>{"Engine/Shaders/Private/Lights.ush:1 compute `TranslatedWorldPosition` in translated world "
                                           "(camera-relative) and follow its uses, into `GetLocalLightAttenuation`"}))
      << doc.dump(2);
}

// A file that is both a lint target and an include is parsed once, and its summary is the same
// whichever way it was made: linting the includer alone or with its includes gives the same.
TEST(Cli, AnIncludeThatIsAlsoATargetTeachesWhatItTeachesAlone) {
  std::string dir = test::scratch("include-targets");
  test::write(dir + "/Defs.ush", "#define SCENE_INLINE\n");
  test::write(dir + "/Scene.ush",
              "#include \"Defs.ush\"\nSCENE_INLINE float3 GetPivot() { return mul(float4(0, 0, 0, 1), Primitive.LocalToWorld).xyz; }\n");
  test::write(dir + "/a.usf", "#include \"Scene.ush\"\nfloat F() { float3 P = GetPivot(); return P.x; }\n");
  auto in_a = [](const std::string& out) {
    std::vector<std::string> got;
    nlohmann::json doc = nlohmann::json::parse(out);
    for (const auto& f : doc["findings"])
      if (f["path"] == "a.usf") got.push_back(f["rule"].get<std::string>() + " " + std::to_string(f["start"]["column"].get<int>()));
    return got;
  };
  std::vector<std::string> alone = in_a(lint(dir, "a.usf --format json --fail-on none").out);
  EXPECT_EQ(alone, (std::vector<std::string>{"lwc-float-world-position 7", "lwc-float-world-position 20"}));
  EXPECT_EQ(in_a(lint(dir, ". --format json --fail-on none --jobs 1").out), alone);
  EXPECT_EQ(in_a(lint(dir, ". --format json --fail-on none --jobs 2").out), alone);
}

// Bytes that are not UTF-8, in a source and in its name: every format still writes valid output,
// one column per such byte (as an editor shows it), escaped in text, U+FFFD in JSON and SARIF.
TEST(Cli, BytesThatAreNotUtf8NeverAbortAnOutput) {
  std::string dir = test::scratch("not-utf8");
  test::write(dir + "/caf\xE9.usf",
              "// \xA9 Epic\nfloat3 F() { /*\xE9*/ float3 P = mul(float4(0, 0, 0, 1), Primitive.LocalToWorld).xyz; return P; }\n");
  for (const char* format : {"json", "sarif", "github", "text"}) {
    auto r = lint(dir, std::string(". --fail-on none --format ") + format);
    EXPECT_EQ(r.exit_code, 0) << format;
  }
  nlohmann::json doc = nlohmann::json::parse(lint(dir, ". --fail-on none --format json").out);
  std::vector<std::string> got;
  for (const auto& f : doc["findings"])
    got.push_back(f["path"].get<std::string>() + " " + std::to_string(f["start"]["line"].get<int>()) + ":" +
                  std::to_string(f["start"]["column"].get<int>()));
  EXPECT_EQ(got, (std::vector<std::string>{"caf\uFFFD.usf 1:4", "caf\uFFFD.usf 2:8", "caf\uFFFD.usf 2:27", "caf\uFFFD.usf 2:55"}));
  nlohmann::json sarif = nlohmann::json::parse(lint(dir, ". --fail-on none --format sarif").out);
  EXPECT_EQ(sarif["runs"][0]["results"].size(), 4u);
  std::string text = lint(dir, ". --fail-on none").out;
  EXPECT_NE(text.find("caf\\xE9.usf:2:27:"), std::string::npos) << text;
  EXPECT_NE(text.find("/*\\xE9*/ float3 P"), std::string::npos) << text;
  EXPECT_NE(text.find("| " + std::string(29, ' ') + "^"), std::string::npos) << text;  // under P, past the 4-wide escape
}

TEST(Cli, SuppressionsOnTheLineAboveAndForTheFileAndUnusedOnes) {
  std::string dir = test::scratch("suppress");
  test::write(dir + "/a.usf",
              "// lwcport-ignore-file: lwc-hack-marker\n"
              "float3 F(float3 L)\n{\n"
              "\t// lwcport-ignore: lwc-primary-view\n"
              "\tfloat3 C = View.WorldCameraOrigin; // lwcport-ignore: lwc-float-world-position\n"
              "\tfloat3 D = View.PreViewTranslation; /* lwcport-ignore: lwc-tile-offset, lwc-primary-view */\n"
              "\treturn LWCHackToFloat(C + D); // lwcport-ignore: no-such-rule\n}\n");
  auto doc = nlohmann::json::parse(lint(dir, "a.usf --format json").out);
  std::vector<std::string> got;
  for (const auto& f : doc["findings"])
    got.push_back(std::to_string(f["start"]["line"].get<int>()) + " " + f["rule"].get<std::string>() + " " +
                  f["message"].get<std::string>().substr(0, 30));
  EXPECT_EQ(got, (std::vector<std::string>{
                     "6 lwc-float-world-position variable `D` (float3) holds th",
                     "6 lwc-unused-suppression unused suppression of `lwc-til",
                     "7 lwc-unused-suppression unused suppression of `no-such",
                 }));
}

// Every suppression a finding meets is used, not only the first: two for the whole file, two on its line.
TEST(Cli, EverySuppressionAFindingMeetsIsUsed) {
  std::string dir = test::scratch("suppress-all");
  test::write(dir + "/a.usf",
              "// lwcport-ignore-file: lwc-primary-view\n"
              "// lwcport-ignore-file: lwc-primary-view, lwc-tile-offset\n"
              "float3 F() { return View.WorldCameraOrigin; }\n"
              "float3 G() { return View.WorldViewOrigin; } // lwcport-ignore: lwc-hack-marker, lwc-primary-view /* lwcport-ignore */\n");
  auto doc = nlohmann::json::parse(lint(dir, "a.usf --format json --fail-on none --select lwc-primary-view,lwc-tile-offset,lwc-hack-marker,lwc-unused-suppression").out);
  std::vector<std::string> got;
  for (const auto& f : doc["findings"]) got.push_back(std::to_string(f["start"]["line"].get<int>()) + " " + f["message"].get<std::string>());
  EXPECT_EQ(got, (std::vector<std::string>{"2 unused suppression of `lwc-tile-offset`: no `lwc-tile-offset` finding here to suppress",
                                           "4 unused suppression of `lwc-hack-marker`: no `lwc-hack-marker` finding here to suppress"}))
      << doc.dump(1);
}

TEST(Cli, BareAndNextLineSuppressionsAndUnknownIds) {
  std::string dir = test::scratch("suppress-forms");
  test::write(dir + "/a.usf",
              "float3 F(float3 L)\n{\n"
              "\tfloat3 C = View.WorldCameraOrigin; // lwcport-ignore\n"           // every rule on its line
              "\tfloat3 D = C; // lwcport-ignore-next-line: lwc-primary-view\n"   // trailing, yet the next line
              "\tfloat3 E = View.WorldViewOrigin;\n"
              "\t// lwcport-ignore-next-line\n"                                    // every rule on the next line
              "\tfloat3 G = E - View.WorldViewOrigin;\n"
              "\treturn G; // lwcport-ignore\n"                                    // nothing here: unused
              "}\n"
              "// lwcport-ignored is a word, not a suppression\n");
  auto doc = nlohmann::json::parse(lint(dir, "a.usf --format json --fail-on none").out);
  std::vector<std::string> got;
  for (const auto& f : doc["findings"])
    got.push_back(std::to_string(f["start"]["line"].get<int>()) + " " + f["rule"].get<std::string>() + " " + f["message"].get<std::string>());
  EXPECT_EQ(got, (std::vector<std::string>{
                     "4 lwc-float-world-position variable `D` (float3) holds an absolute world position in float32: far from the origin its "
                     "spacing grows (1/8 cm at 10 km, 1 cm at 100 km, 2^20 cm at UE's world limit), so positions jitter and differences "
                     "taken from it lose their digits",
                     "5 lwc-float-world-position variable `E` (float3) holds an absolute world position in float32: far from the origin its "
                     "spacing grows (1/8 cm at 10 km, 1 cm at 100 km, 2^20 cm at UE's world limit), so positions jitter and differences "
                     "taken from it lose their digits",
                     "8 lwc-unused-suppression unused suppression of every rule: no finding here to suppress",
                 }))
      << doc.dump(1);
}

TEST(Cli, RemovingAStaleSuppressionKeepsTheCommentsOtherWords) {
  std::string dir = test::scratch("suppress-words");
  test::write(dir + "/a.usf",
              "float F(float X)\n{\n"
              "\treturn X; // keep: fog is clamped here. lwcport-ignore: lwc-primary-view\n"
              "}\n"
              "// lwcport-ignore-file: lwc-tile-offset, lwc-not-a-rule\n"
              "float G() { return 1; } /* lwcport-ignore */\n");
  auto diff = test::run("cd " + dir + " && " + test::binary() + " fix a.usf && cat a.usf");
  EXPECT_EQ(diff.out.substr(diff.out.find("float F")),
            "float F(float X)\n{\n"
            "\treturn X; // keep: fog is clamped here.\n"
            "}\n"
            "float G() { return 1; }\n")
      << diff.out;
}

TEST(Cli, OutputIsIdenticalForAnyJobCount) {
  std::string corpus = test::source_dir() + "/corpus";
  auto one = test::run("cd " + test::source_dir() + " && " + test::binary() + " lint corpus --format json --jobs 1 --fail-on none");
  auto many = test::run("cd " + test::source_dir() + " && " + test::binary() + " lint corpus --format json --jobs 8 --fail-on none");
  EXPECT_EQ(one.exit_code, 0);
  EXPECT_EQ(one.out, many.out);
}

TEST(Cli, RulesListsEveryRule) {
  auto r = test::run(test::binary() + " rules");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* id : {"lwc-primary-view", "lwc-float-world-position", "lwc-uniform-world-float", "lwc-hack-marker",
                         "lwc-tile-offset", "lwc-fast-twosum-order", "lwc-missing-precise", "lwc-demote-fusion",
                         "lwc-translated-world", "lwc-unused-suppression", "lwc-input"})
    EXPECT_NE(r.out.find(id), std::string::npos) << id;
}

}  // namespace
}  // namespace lwc

namespace lwc {
namespace {

test::Run run_with_stderr(const std::string& dir, const std::string& args) {
  return test::run("cd " + dir + " && " + test::binary() + " " + args + " 2>&1");
}

TEST(Cli, APathThatYieldsNoShaderIsAnErrorNotASilentPass) {
  std::string dir = test::scratch("no-shader");
  test::write(dir + "/docs/readme.md", "# notes\n");
  test::write(dir + "/scripts/util.ts", "export const n = `${1}`;\n");
  test::write(dir + "/shaders/ok.glsl", "void main() {}\n");
  auto r = run_with_stderr(dir, "lint docs scripts shaders typo --fail-on none --color never");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.out.find("lwcport: error: docs: no shader file in it"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("lwcport: error: scripts: no shader file in it"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("lwcport: error: typo: no such file or folder"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("shaders:"), std::string::npos) << r.out;
  EXPECT_EQ(run_with_stderr(dir, "lint shaders").exit_code, 0);
  // parse says what it skipped, and why.
  auto p = run_with_stderr(dir, "parse docs scripts shaders --verbose");
  EXPECT_NE(p.out.find("docs/readme.md: skipped: not a shader extension"), std::string::npos) << p.out;
  EXPECT_NE(p.out.find("scripts/util.ts: skipped: no shader code in it"), std::string::npos) << p.out;
  EXPECT_NE(p.out.find("Parsed 1 file(s)"), std::string::npos) << p.out;
}

TEST(Cli, AProjectMapsItsOwnExtensions) {
  std::string dir = test::scratch("extensions");
  test::write(dir + "/pointcloud.vs", "uniform mat4 modelMatrix;\nin vec3 position;\nvoid main() {\n  vec4 worldPosition = modelMatrix * vec4(position, 1.0);\n  gl_Position = worldPosition;\n}\n");
  EXPECT_EQ(run_with_stderr(dir, "lint .").exit_code, 2);
  test::write(dir + "/.lwcport.json", R"({"extensions": {".vs": "glsl"}})");
  auto r = run_with_stderr(dir, "lint . --color never --fail-on none");
  EXPECT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("pointcloud.vs:4:8: warning: variable `worldPosition`"), std::string::npos) << r.out;
  test::write(dir + "/.lwcport.json", R"({"extensions": {".vs": "metal"}})");
  auto bad = run_with_stderr(dir, "lint .");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.out.find("format must be hlsl, glsl, glsl-in-js or none"), std::string::npos) << bad.out;
}

TEST(Cli, AnUnmappedExtensionWhoseFilesReadAsShaderCodeIsNamedOnce) {
  std::string dir = test::scratch("unmapped");
  const char* hlsl = "cbuffer View : register(b0) { float4x4 World; float3 EyePosW; };\nfloat4 Main(float4 P : POSITION) : SV_Target { return P; }\n";
  test::write(dir + "/shaders/a.shader", hlsl);
  test::write(dir + "/shaders/b.shader", "// only a comment\n");
  test::write(dir + "/shaders/c.shader", hlsl);
  test::write(dir + "/shaders/ok.hlsl", "float4 Tint(float4 C) { return C; }\n");
  test::write(dir + "/src/upload.cpp", std::string("// copies the cbuffer: float4 EyePos : SV_Target\n") + hlsl);
  auto r = run_with_stderr(dir, "lint . --color never --fail-on none");
  EXPECT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("shaders/a.shader:1:1: note: this file reads as HLSL (`cbuffer`"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("it and 2 more `.shader` files are not linted [lwc-input]"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(R"(add "extensions": {".shader": "hlsl"} to .lwcport.json)"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("c.shader"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("upload.cpp"), std::string::npos) << r.out;
  // Said to be no shader: silent. Mapped: linted.
  test::write(dir + "/.lwcport.json", R"({"extensions": {".shader": "none"}})");
  EXPECT_EQ(run_with_stderr(dir, "lint . --color never --fail-on none").out.find(".shader"), std::string::npos);
  test::write(dir + "/.lwcport.json", R"({"extensions": {".shader": "hlsl"}})");
  auto mapped = run_with_stderr(dir, "lint . --color never --fail-on none");
  EXPECT_NE(mapped.out.find("shaders/a.shader:1:40: warning: uniform `World`"), std::string::npos) << mapped.out;
  EXPECT_EQ(mapped.out.find("reads as"), std::string::npos) << mapped.out;
}

TEST(Cli, UnityShaderLabFilesAreNotTakenForPlainShaderCode) {
  std::string dir = test::scratch("shaderlab");
  test::write(dir + "/Lit.shader",
              "Shader \"Custom/Lit\" { SubShader { Pass { HLSLPROGRAM\ncbuffer UnityPerDraw { float4x4 unity_ObjectToWorld; };\n"
              "float4 frag(float4 P : SV_POSITION) : SV_Target { return P; }\nENDHLSL } } }\n");
  test::write(dir + "/Common.hlsl", "float4 Tint(float4 C) { return C; }\n");
  auto r = run_with_stderr(dir, "lint . --color never --fail-on none");
  EXPECT_EQ(r.out.find("Lit.shader"), std::string::npos) << r.out;
}

TEST(Cli, AHostThatRebasesPositionsLeavesOnlyWhatTheShaderMakesAbsoluteAgain) {
  std::string dir = test::scratch("host-rebases");
  test::write(dir + "/obj.vert",
              "#version 450\nuniform mat4 modelMatrix;\nuniform mat4 viewProjection;\nuniform vec3 cameraPosition;\nuniform vec3 renderOrigin;\n"
              "in vec3 position;\nout float fade;\nvoid main() {\n  vec4 worldPosition = modelMatrix * vec4(position, 1.0);\n"
              "  fade = length(worldPosition.xyz - cameraPosition) / 1000.0;\n  vec3 geo = worldPosition.xyz + renderOrigin;\n"
              "  fade += sin(geo.x);\n  gl_Position = viewProjection * worldPosition;\n}\n");
  auto plain = run_with_stderr(dir, "lint . --color never --fail-on none");
  EXPECT_NE(plain.out.find("obj.vert:2:14: warning: uniform `modelMatrix`"), std::string::npos) << plain.out;
  EXPECT_NE(plain.out.find("obj.vert:9:8: warning: variable `worldPosition`"), std::string::npos) << plain.out;
  // The host subtracts its render origin first: the conventional names hold relative data.
  test::write(dir + "/.lwcport.json", R"({"host-rebases": true})");
  auto rebased = run_with_stderr(dir, "lint . --color never --fail-on none");
  EXPECT_NE(rebased.out.find("No findings in 1 file(s)"), std::string::npos) << rebased.out;
  // The origin itself is absolute, as the project says: adding it back makes an absolute point.
  test::write(dir + "/.lwcport.json", R"({"host-rebases": true, "world-sources": [{"match": "renderOrigin", "kind": "absolute-position"}]})");
  auto origin = run_with_stderr(dir, "lint . --color never --fail-on none");
  EXPECT_NE(origin.out.find("obj.vert:11:8: warning: variable `geo`"), std::string::npos) << origin.out;
  EXPECT_EQ(origin.out.find("worldPosition`"), std::string::npos) << origin.out;
  test::write(dir + "/.lwcport.json", R"({"host-rebases": "yes"})");
  auto bad = run_with_stderr(dir, "lint .");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.out.find("\"host-rebases\" must be true or false"), std::string::npos) << bad.out;
}

}  // namespace
}  // namespace lwc
