// analyze(): what it makes of files the parser reads in variants or with syntax errors.
#include <gtest/gtest.h>

#include "cli/report.h"
#include "fix/apply.h"
#include "rules/rule.h"
#include "support.h"

namespace lwc {
namespace {

size_t count(const std::vector<Finding>& findings, const std::string& rule) {
  size_t n = 0;
  for (const Finding& f : findings) n += f.rule == rule;
  return n;
}

// UE4 code with preprocessor groups inside a parameter list and an expression: every arm is
// analysed, one variant at a time.
const char* kArms = R"(float3 CameraOffset(
#if USE_TRANSLATED
	float3 TranslatedPos
#else
	float3 WorldPos
#endif
	)
{
#if USE_TRANSLATED
	return TranslatedPos - View.TranslatedWorldCameraOrigin;
#else
	return WorldPos - View.WorldCameraOrigin;
#endif
}
float3 ToView(float3 WorldPos)
{
	return WorldPos
#if USE_VIEW_ORIGIN
		- View.WorldViewOrigin
#else
		- View.WorldCameraOrigin
#endif
		;
}
)";

// lwc-missing-precise tells verify which operation an error-free transformation computes, so the
// harness can judge it against the exact value; a high/low difference is not error-free.
TEST(Facts, AnErrorFreeTransformationNamesItsOperation) {
  std::string code = test::read(test::source_dir() + "/corpus/ue5.4/DoubleFloatHelpers.ush") +
                     "float2 Product(float A, float B)\n{\n\tfloat P = A * B;\n\tfloat E = fma(A, B, -P);\n\treturn float2(P, E);\n}\n"
                     "float2 Fast(float A, float B)\n{\n\tfloat S = A + B;\n\tfloat E = B - (S - A);\n\treturn float2(S, E);\n}\n"
                     "float Diff(float aHigh, float aLow, float bHigh, float bLow)\n{\n\tfloat H = aHigh - bHigh;\n"
                     "\tfloat L = aLow - bLow;\n\treturn H + L;\n}\n";
  AnalyzeOptions options;
  options.lang = Lang::hlsl;
  std::map<std::string, std::string> operations;  // the finding's line -> operation ("" for none)
  Source source("helpers.ush", code);
  for (const Finding& f : analyze(source, options))
    if (f.rule == "lwc-missing-precise")
      operations[source.text().substr(f.span.begin, f.span.end - f.span.begin)] = f.facts.count("error-free") ? f.facts.at("error-free") : "";
  EXPECT_EQ(operations["(A - (S - V)) + (B - V)"], "sum");
  EXPECT_EQ(operations["A - Hi"], "split");
  EXPECT_EQ(operations["fma(A, B, -P)"], "product");
  EXPECT_EQ(operations["B - (S - A)"], "fast-sum");
  EXPECT_EQ(operations["H + L"], "");
  EXPECT_EQ(operations.size(), 5u);
}

TEST(Variants, FindingsInEveryArmAreReportedOnce) {
  auto findings = test::lint_text(kArms, Lang::hlsl, "lwc-primary-view");
  ASSERT_EQ(count(findings, "lwc-primary-view"), 3u);
  // In the function body the grammar reads the group itself: the finding and its rewrite are the
  // same in both variants. Inside the expression each arm is read in one variant only: found, but
  // no rewrite is sure to fit the other arm.
  EXPECT_EQ(findings[0].fixes.size(), 1u);
  for (size_t i : {1, 2}) {
    EXPECT_TRUE(findings[i].fixes.empty());
    ASSERT_FALSE(findings[i].withheld.empty());
    EXPECT_NE(findings[i].withheld.back().find("preprocessor branches"), std::string::npos);
  }
  EXPECT_EQ(count(test::lint_text(kArms, Lang::hlsl), "lwc-input"), 0u);
}

TEST(Variants, ASuppressionUsedInOneArmIsNotUnused) {
  std::string code = std::string(kArms);
  code.replace(code.find("- View.WorldViewOrigin"), 0, "// lwcport-ignore: lwc-primary-view\n\t\t");
  auto findings = test::lint_text(code, Lang::hlsl);
  EXPECT_EQ(count(findings, "lwc-unused-suppression"), 0u);
  EXPECT_EQ(count(findings, "lwc-primary-view"), 2u);
}

// An arm the engine never builds may not parse (a `;` missing before `#endif`): only the variant
// that keeps it meets the error, so the variants that read the code cleanly decide the rewrite,
// unless the broken arm spells a name the rewrite takes away.
TEST(Variants, AnArmThatDoesNotParseLeavesTheRewritesAroundIt) {
  auto fog = [](const std::string& broken_arm) {
    return "float3 Fog(float3 P)\n{\n\tfloat3 ToCamera = P - View.WorldCameraOrigin;\n#if USE_EXPOSURE\n"
           "\tconst float Exposure = 1.0f;\n#else\n\tconst float Exposure = " + broken_arm + "\n#endif\n"
           "\treturn ToCamera * Exposure;\n}\n";
  };
  auto found = test::lint_text(fog("2.0f"), Lang::hlsl);
  ASSERT_EQ(count(found, "lwc-primary-view"), 1u);
  ASSERT_EQ(count(found, "lwc-input"), 1u);
  for (const Finding& f : found)
    if (f.rule == "lwc-primary-view") EXPECT_EQ(f.fixes.size(), 1u);
  for (const Finding& f : test::lint_text(fog("View.PreExposure"), Lang::hlsl)) {
    if (f.rule != "lwc-primary-view") continue;
    EXPECT_TRUE(f.fixes.empty());
    ASSERT_FALSE(f.withheld.empty());
    EXPECT_NE(f.withheld.back().find("could not be parsed"), std::string::npos);
  }
}

TEST(SyntaxErrors, OnlyTheBrokenDeclarationLosesItsRewrites) {
  std::string code =
      "float3 Broken(float3 P) { return P - View.WorldCameraOrigin +* ; }\n"
      "float3 Fine(float3 P) { return P - View.WorldCameraOrigin; }\n";
  auto findings = test::lint_text(code, Lang::hlsl);
  ASSERT_EQ(count(findings, "lwc-input"), 1u);
  int with_fix = 0, without = 0;
  for (const Finding& f : findings) {
    if (f.rule != "lwc-primary-view") continue;
    (f.fixes.empty() ? without : with_fix) += 1;
    if (f.fixes.empty()) {
      ASSERT_FALSE(f.withheld.empty());
      EXPECT_NE(f.withheld.back().find("syntax error"), std::string::npos);
    }
  }
  EXPECT_EQ(with_fix, 1);
  EXPECT_LE(without, 1);
}

}  // namespace
}  // namespace lwc

namespace lwc {
namespace {

std::vector<Finding> lint_unreal(const std::string& code, std::optional<UnrealEra> era, const std::string& rule = "") {
  AnalyzeOptions o;
  o.unreal = era;
  if (!rule.empty()) o.select = {rule};
  return analyze(Source("Test.usf", code), o);
}

TEST(UnrealEras, ARewriteCallsOnlyWhatTheEngineDefines) {
  // UE 5.4's DoubleFloat.ush has no DFDivideDemote (lwcport's own library does): no rewrite.
  std::string divide = "float3 F(FDFVector3 A, float3 B) { return DFDemote(DFDivide(A, B)); }\n";
  auto f = lint_unreal(divide, UnrealEra::ue5_4, "lwc-demote-fusion");
  ASSERT_EQ(f.size(), 1u);
  EXPECT_TRUE(f[0].fixes.empty());
  ASSERT_FALSE(f[0].withheld.empty());
  EXPECT_NE(f[0].withheld.back().find("`DFDivideDemote`, which Unreal does not define"), std::string::npos) << f[0].withheld.back();
  // DFAddDemote is the engine's own.
  std::string add = "float3 F(FDFVector3 A, float3 B) { return DFDemote(DFAdd(A, B)); }\n";
  auto g = lint_unreal(add, UnrealEra::ue5_4, "lwc-demote-fusion");
  ASSERT_EQ(g.size(), 1u);
  ASSERT_EQ(g[0].fixes.size(), 1u);
  EXPECT_EQ(g[0].fixes[0].applicability, Applicability::safe);
}

TEST(UnrealEras, MessagesNameTheEngineEraAndItsTypes) {
  std::string code = "float3 F(float3 P) { return P - View.WorldCameraOrigin; }\n";
  auto ue50 = lint_unreal(code, UnrealEra::ue5_0, "lwc-primary-view");
  ASSERT_EQ(ue50.size(), 1u);
  EXPECT_NE(ue50[0].message.find("a tile/offset `FLWCVector3` member"), std::string::npos) << ue50[0].message;
  EXPECT_NE(ue50[0].message.find("does not compile in UE 5.0-5.3"), std::string::npos);
  // The DoubleFloat rewrite needs UE 5.4: unsafe in a 5.0-5.3 project.
  ASSERT_EQ(ue50[0].fixes.size(), 1u);
  EXPECT_EQ(ue50[0].fixes[0].applicability, Applicability::unsafe);
  EXPECT_NE(ue50[0].fixes[0].reason.find("it needs UE 5.4+ (`DFSubtractDemote`)"), std::string::npos) << ue50[0].fixes[0].reason;
  auto ue4 = lint_unreal(code, std::nullopt, "lwc-primary-view");
  ASSERT_EQ(ue4.size(), 1u);
  EXPECT_NE(ue4[0].message.find("stops compiling when this code moves to UE5"), std::string::npos) << ue4[0].message;
  auto ue54 = lint_unreal("float3 F(float3 P) { return P - View.ClipToWorld[3].xyz; }\n", UnrealEra::ue5_4, "lwc-primary-view");
  ASSERT_EQ(ue54.size(), 1u);
  EXPECT_NE(ue54[0].message.find("a DoubleFloat `FDFMatrix` member"), std::string::npos) << ue54[0].message;
}

TEST(UnrealEras, SettingsAndInference) {
  EXPECT_EQ(parse_unreal_era("4"), UnrealEra::ue4);
  EXPECT_EQ(parse_unreal_era("4.27"), UnrealEra::ue4);
  EXPECT_EQ(parse_unreal_era("5.0"), UnrealEra::ue5_0);
  EXPECT_EQ(parse_unreal_era("5.3"), UnrealEra::ue5_0);
  EXPECT_EQ(parse_unreal_era("5.4"), UnrealEra::ue5_4);
  EXPECT_EQ(parse_unreal_era("5.6"), UnrealEra::ue5_4);
  EXPECT_FALSE(parse_unreal_era("6").has_value());
  EXPECT_FALSE(parse_unreal_era("5.x").has_value());
  EXPECT_EQ(infer_unreal_era("FLWCVector3 P; FDFVector3 Q = DFFromTileOffset_Hack(P);"), UnrealEra::ue5_0);
  EXPECT_EQ(infer_unreal_era("float3 P = DFDemote(PrimaryView.WorldCameraOrigin);"), UnrealEra::ue5_4);
  EXPECT_EQ(infer_unreal_era("// LWCHackToFloat(X) in a comment\nfloat3 P = View.WorldCameraOrigin;"), UnrealEra::ue4);
}

TEST(LibraryDefinitions, TheLibrariesOwnDefinitionsAreNotDebt) {
  std::string library =
      "FLWCVector3 LWCAddOffset(FLWCVector3 V, float3 O) { return MakeLWCVector3(V.Tile, V.Offset + O); }\n"
      "float3 DFHackToFloatHelper(FDFVector3 V) { return V.High + V.Low; }\n";
  EXPECT_TRUE(lint_unreal(library, UnrealEra::ue5_4).empty());
  std::string user = library + "float3 UserCode(FLWCVector3 P) { return LWCToFloat(P); }\n";
  auto f = lint_unreal(user, UnrealEra::ue5_4, "lwc-tile-offset");
  ASSERT_EQ(f.size(), 2u);  // FLWCVector3 and LWCToFloat in UserCode only
  AnalyzeOptions lint_it;
  lint_it.unreal = UnrealEra::ue5_4;
  lint_it.lint_library = true;
  lint_it.select = {"lwc-tile-offset"};
  EXPECT_GT(analyze(Source("Test.usf", user), lint_it).size(), 2u);
}

}  // namespace
}  // namespace lwc

namespace lwc {
namespace {

TEST(UnrealEras, AnArmForAnOlderEngineIsThatEnginesCode) {
  std::string code =
      "float3 Reconstruct(float3 ScreenVector, float Depth)\n{\n"
      "#if UE4_COMPAT\n\tfloat3 WorldPosition = ScreenVector * Depth + View.WorldCameraOrigin;\n"
      "#else\n\tfloat3 WorldPosition = ScreenVector * Depth + LWCHackToFloat(PrimaryView.WorldCameraOrigin);\n#endif\n"
      "\treturn WorldPosition;\n}\n";
  auto findings = lint_unreal(code, UnrealEra::ue5_4);
  for (const Finding& f : findings) EXPECT_NE(f.rule, "lwc-primary-view") << f.message;
  EXPECT_TRUE(std::any_of(findings.begin(), findings.end(), [](const Finding& f) { return f.rule == "lwc-hack-marker"; }));
  auto arms = era_guarded_arms(code);
  ASSERT_EQ(arms.size(), 2u);
  EXPECT_EQ(arms[0].era, UnrealEra::ue4);
  EXPECT_EQ(arms[1].era, UnrealEra::ue5_0);
  auto major = era_guarded_arms("#if ENGINE_MAJOR_VERSION >= 5\nA\n#else\nB\n#endif\n#ifndef UE5_ONLY\nC\n#endif\n");
  ASSERT_EQ(major.size(), 3u);
  EXPECT_EQ(major[0].era, UnrealEra::ue5_0);
  EXPECT_EQ(major[1].era, UnrealEra::ue4);
  EXPECT_EQ(major[2].era, UnrealEra::ue4);
}

// A CRLF file's '\r' and a comment after the condition are not part of it (a plugin saved on
// Windows kept its UE4 tessellation arm in the findings); tessellation is UE4's alone.
TEST(EraArms, CrlfCommentsAndTheTessellationSwitch) {
  auto arms = era_guarded_arms("#if USING_TESSELLATION\r\nA\r\n#endif // USING_TESSELLATION\r\n"
                               "#if UE4_COMPAT // the old path\r\nB\r\n#else\r\nC\r\n#endif\r\n"
                               "#if ENGINE_MAJOR_VERSION >= 5 /* UE5 */\r\nD\r\n#endif\r\n");
  ASSERT_EQ(arms.size(), 4u);
  EXPECT_EQ(arms[0].era, UnrealEra::ue4);
  EXPECT_EQ(arms[1].era, UnrealEra::ue4);
  EXPECT_EQ(arms[2].era, UnrealEra::ue5_0);
  EXPECT_EQ(arms[3].era, UnrealEra::ue5_0);
}

}  // namespace
}  // namespace lwc

namespace lwc {
namespace {

TEST(TileOffset, NeverRenamesIntoAnExistingOverload) {
  std::string code =
      "float3 ToFloat(FDFVector3 V) { return DFDemote(V); }\n"
      "float3 ToFloat(FLWCVector3 V) { return LWCToFloat(V); }\n"
      "float3 Use(FLWCVector3 P) { return ToFloat(P); }\n";
  auto findings = lint_unreal(code, UnrealEra::ue5_4, "lwc-tile-offset");
  ASSERT_EQ(findings.size(), 3u);
  // The overload's own type: no rewrite, and why.
  EXPECT_TRUE(findings[0].fixes.empty());
  ASSERT_FALSE(findings[0].withheld.empty());
  EXPECT_NE(findings[0].withheld[0].find("would define it a second time"), std::string::npos);
  // Elsewhere the renames stay, unsafe: they compile only together with a hand port.
  for (size_t i : {1, 2}) {
    ASSERT_EQ(findings[i].fixes.size(), 1u);
    EXPECT_EQ(findings[i].fixes[0].applicability, Applicability::unsafe);
  }
}

// What one finding says never grows with its line: 2,000 findings on one line each quote a
// bounded window of it, and a rewrite that would copy the whole expression again is withheld
// with the reason (else the report is quadratic in the line).
TEST(BoundedWork, AFindingOnAHugeLineStaysSmall) {
  std::string code = "float3 F() { return View.WorldCameraOrigin";
  for (int i = 1; i < 2000; ++i) code += " + View.WorldCameraOrigin";
  code += "; }\n";
  Source src("huge.usf", code);
  std::vector<Finding> findings = analyze(src, {});
  ASSERT_EQ(count(findings, "lwc-primary-view"), 2000u);
  size_t withheld = 0;
  for (const Finding& f : findings) {
    EXPECT_LT(f.message.size(), 1200u);
    for (const Fix& fix : f.fixes) {
      size_t bytes = 0;
      for (const Edit& e : fix.edits) bytes += e.text.size();
      EXPECT_LE(bytes, kMaxFixText);
    }
    for (const std::string& why : f.withheld) withheld += why.find("split the expression") != std::string::npos;
    ReportedFinding r = locate(src, f);
    EXPECT_LE(r.line_text.size(), 240u);
    EXPECT_EQ(r.line_column + static_cast<int>(r.line_text.size()) > r.start.column, true);
  }
  EXPECT_GT(withheld, 1000u);
}

// Nor does why a rewrite is withheld: the use it names is quoted as a message quotes it (a chain of
// products of a matrix the rewrite cannot demote: each use is the chain so far).
TEST(BoundedWork, WhyARewriteIsWithheldStaysSmallOnAHugeLine) {
  std::string code = "float4x4 F() { return View.WorldToClip";
  for (int i = 1; i < 2000; ++i) code += " * View.WorldToClip";
  code += "; }\n";
  std::vector<Finding> findings = analyze(Source("huge.usf", code), {});
  ASSERT_EQ(count(findings, "lwc-primary-view"), 2000u);
  size_t quoted = 0;
  for (const Finding& f : findings)
    for (const std::string& why : f.withheld) {
      EXPECT_LT(why.size(), kMaxQuoted + 300) << why.substr(0, 200);
      quoted += why.find("and this use (`View.WorldToClip * View.WorldToClip") != std::string::npos;
    }
  EXPECT_GT(quoted, 1000u);
}

// Nesting 100,000 deep (parentheses, calls, braces, #if groups): analysed without a crash; the
// bench (tests/bench/scaling.sh) shows the time grows linearly.
TEST(BoundedWork, DeepNestingIsAnalysedWithoutACrash) {
  const int n = 100000;
  std::string parens = "float F() { return " + std::string(n, '(') + "1" + std::string(n, ')') + "; }\n";
  std::string calls = "float F() { return ";
  for (int i = 0; i < n; ++i) calls += "f(";
  calls += "1" + std::string(n, ')') + "; }\n";
  std::string braces = "void F() " + std::string(n, '{') + std::string(n, '}') + "\n";
  std::string ifs;
  for (int i = 0; i < n; ++i) ifs += "#if A\n";
  ifs += "float x;\n";
  for (int i = 0; i < n; ++i) ifs += "#endif\n";
  for (const std::string& code : {parens, calls, braces, ifs}) {
    std::vector<Finding> findings = analyze(Source("deep.usf", code), {});
    FixOutcome fixed = fix_source(Source("deep.usf", code), {}, true);
    EXPECT_EQ(fixed.text.size() >= code.size() / 2, true);
  }
}

// The parser's budget: a file it cannot finish in time is one clear error, the run goes on.
TEST(BoundedWork, AParseOverItsBudgetIsAnErrorNotAHang) {
  std::string code;
  for (int i = 0; i < 20000; ++i) code += "float3 F" + std::to_string(i) + "(float3 P) { return P - View.WorldCameraOrigin; }\n";
  for (const char* path : {"slow.usf", "slow.vert", "slow.glsl.js"}) {
    AnalyzeOptions options;
    options.max_parse_seconds = 1e-6;
    std::string text = std::string(path).ends_with(".js") ? "const s = /* glsl */`" + code + "`;\n" : code;
    std::vector<Finding> findings = analyze(Source(path, text), options);
    ASSERT_FALSE(findings.empty()) << path;
    bool gave_up = false;
    for (const Finding& f : findings) gave_up |= f.rule == "lwc-input" && f.message.find("the parser gave up") != std::string::npos;
    EXPECT_TRUE(gave_up) << path;
  }
}

}  // namespace
}  // namespace lwc
