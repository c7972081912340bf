// The per-function harness on lavapipe: float32 originals caught at large coordinates, rewrites
// measured against the float64 reference (and against it on the inputs they inherit), edge cases.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "fix/apply.h"
#include "shaderlib/shaderlib.h"
#include "support.h"
#include "verify/double_intrinsics.h"
#include "verify/harness.h"
#include "verify/kernel.h"
#include "verify/library_accuracy.h"
#include "verify/probes.h"
#include "verify/worker.h"

namespace lwc {
namespace {

// A small harness set-up (8,192 invocations, 4 timed rounds): lwcport's library from memory,
// Unreal's engine headers from the stub.
HarnessSetup small_setup(Lang lang, const std::string& display) {
  HarnessSetup setup;
  setup.lang = lang;
  setup.display = display;
  setup.stage = Stage::fragment;
  setup.invocations = 8192;
  setup.timing.min_rounds = setup.timing.max_rounds = 4;
  setup.include = [lang](const std::string& name, const std::string&) -> std::optional<IncludedFile> {
    if (name == library_file_name(lang)) return IncludedFile{name, full_library_text(lang)};
    if (name.rfind("/Engine/", 0) == 0) return IncludedFile{name, ""};
    return std::nullopt;
  };
  return setup;
}
HarnessSetup glsl_setup() { return small_setup(Lang::glsl, "test.frag"); }

struct Driver {
  std::unique_ptr<WorkerDevice> device;
  DriverProbes probes;
};
Driver start_driver() {
  Driver d;
  std::string error;
  d.device = WorkerDevice::start(error);
  EXPECT_NE(d.device, nullptr) << error;
  if (d.device) EXPECT_EQ(probe_driver(*d.device, d.probes), "");
  return d;
}

TEST(HarnessOnLavapipe, ForwardVertexShaderOriginalFailsAndTheRewriteIsFarCloser) {
  Driver d = start_driver();
  ASSERT_NE(d.device, nullptr);
  std::string path = "corpus/glsl/forward.vert";
  Source source(path, test::read(test::source_dir() + "/" + path));
  AnalyzeOptions options;
  options.lang = Lang::glsl;
  std::string fixed = fix_source(source, options, true).text;
  ASSERT_NE(fixed, source.text());
  HarnessSetup setup = small_setup(Lang::glsl, path);
  setup.stage = Stage::vertex;
  FunctionResult r = verify_function(*d.device, d.probes, setup, "main", {{"original (float32)", source.text()}, {"fixed", fixed}});
  ASSERT_EQ(r.variants.size(), 2u);
  EXPECT_NE(r.reference.find("float64"), std::string::npos) << r.reference;
  const VariantResult &original = r.variants[0], &rewrite = r.variants[1];
  ASSERT_TRUE(original.measured) << original.status;
  ASSERT_TRUE(rewrite.measured) << rewrite.status;
  EXPECT_EQ(original.status, "fail");
  EXPECT_NE(original.worst.find("case '"), std::string::npos) << original.worst;
  EXPECT_GT(original.max_error, 100.0);              // float32 world positions: metres off
  EXPECT_LT(rewrite.max_error, 1.0);                 // translated world: below a centimetre
  EXPECT_LT(rewrite.median_error, 1e-3);
  EXPECT_GT(rewrite.ns_per_invocation, 0.0);
  EXPECT_GT(rewrite.spirv_instructions, 0);
}


TEST(HarnessOnLavapipe, EveryEdgeCaseOfTheBriefIsNamed) {
  std::vector<std::string> names = harness_case_names();
  for (const char* wanted : {"+-0", "float32 denormals", "Inf input (object origin)", "NaN input (local position)",
                             "FLWC offset larger than the tile size", "half-tile tie (2.5 * 2^21)", "2^43 - ulp cm"})
    EXPECT_NE(std::find(names.begin(), names.end(), wanted), names.end()) << wanted;
}

// A rewrite that keeps a float32 parameter is right on what it is handed: it is input-limited, its
// own error within the target, while the error against the exact position stays what float32 gives.
TEST(HarnessOnLavapipe, ARewriteThatKeepsAFloatParameterIsInputLimited) {
  Driver d = start_driver();
  ASSERT_NE(d.device, nullptr);
  std::string original = "#version 320 es\nprecision highp float;\nuniform vec3 cameraPosition;\n"
                         "vec3 toCamera(vec3 worldPosition) { return worldPosition - cameraPosition; }\nvoid main() {}\n";
  std::string rewrite = "#version 320 es\n#extension GL_GOOGLE_include_directive : require\nprecision highp float;\n"
                        "#include \"lwc_doublefloat.glsl\"\nuniform FDFVector3 cameraPosition;\n"
                        "vec3 toCamera(vec3 worldPosition) { return DFSubtractDemote(worldPosition, cameraPosition); }\nvoid main() {}\n";
  FunctionResult r = verify_function(*d.device, d.probes, glsl_setup(), "toCamera", {{"original (float32)", original}, {"DoubleFloat", rewrite}});
  ASSERT_EQ(r.variants.size(), 2u);
  const VariantResult& v = r.variants[1];
  ASSERT_TRUE(v.measured) << v.status;
  EXPECT_EQ(v.status, "input-limited") << v.worst;
  EXPECT_LE(v.own_max_error, 1.0 / 16);
  EXPECT_GT(v.max_error, 1000.0);  // float32 positions near 2^42 cm: 2^18 cm apart
  EXPECT_NE(v.worst.find("`worldPosition` by up to"), std::string::npos) << v.worst;
  EXPECT_FALSE(v.refuted());
}

// Inf and NaN must stay visible: a variant that turns them into a finite value fails on that case.
// A variant that only shares the original's float32 behaviour on an edge case (a vector of
// denormal length normalises to NaN) does not.
TEST(HarnessOnLavapipe, HidingANaNFailsAndSharingTheOriginalsEdgeBehaviourDoesNot) {
  Driver d = start_driver();
  ASSERT_NE(d.device, nullptr);
  auto shader = [](const std::string& body) {
    return "#version 320 es\nprecision highp float;\nvec3 scaled(vec3 localPosition) { " + body + " }\nvoid main() {}\n";
  };
  FunctionResult r = verify_function(*d.device, d.probes, glsl_setup(), "scaled",
                                     {{"original (float32)", shader("return normalize(localPosition) * 2.0;")},
                                      {"same edges", shader("return 2.0 * normalize(localPosition);")},
                                      {"hides NaN", shader("vec3 p = normalize(localPosition) * 2.0; return any(isnan(p)) ? vec3(0.0) : p;")}});
  ASSERT_EQ(r.variants.size(), 3u);
  EXPECT_EQ(r.variants[1].status, "pass") << r.variants[1].worst;
  EXPECT_EQ(r.variants[2].status, "fail");
  EXPECT_NE(r.variants[2].worst.find("case 'NaN input (local position)'"), std::string::npos) << r.variants[2].worst;
  EXPECT_NE(r.variants[2].worst.find("finite where the reference is not"), std::string::npos) << r.variants[2].worst;
}

// An error-free transformation's (high, low) result has no float64 reference (promoted, its low
// part is 0): it is judged by its defining property against the exact value on the CPU. Lavapipe
// folds an unprotected TwoSum's error term (fails); with `precise` it is exact (passes); a split
// that keeps its high part whole is exact but not a split; a product that halves its error term
// is off by a quarter ULP, which a float64 promotion could never see.
TEST(HarnessOnLavapipe, AnErrorFreeTransformationIsJudgedByItsDefiningPropertyAgainstAnExactValue) {
  Driver d = start_driver();
  ASSERT_NE(d.device, nullptr);
  auto two_sum = [](const char* q) {
    return fmt::format("float2 TwoSum(float A, float B)\n{{\n\t{0}float S = A + B;\n\t{0}float V = S - A;\n"
                       "\t{0}float E = (A - (S - V)) + (B - V);\n\treturn float2(S, E);\n}}\n", q);
  };
  HarnessSetup setup = small_setup(Lang::hlsl, "eft.usf");
  setup.facts.error_free = {{"TwoSum", "sum"}, {"Split", "split"}, {"Product", "product"}};
  FunctionResult sum = verify_function(*d.device, d.probes, setup, "TwoSum", {{"original (float32)", two_sum("")}, {"fixed", two_sum("precise ")}});
  EXPECT_NE(sum.reference.find("exact"), std::string::npos) << sum.reference;
  ASSERT_EQ(sum.variants.size(), 2u);
  EXPECT_EQ(sum.variants[0].status, "fail");
  EXPECT_NE(sum.variants[0].worst.find("where the exact value is"), std::string::npos) << sum.variants[0].worst;
  EXPECT_EQ(sum.variants[1].status, "pass") << sum.variants[1].worst;
  EXPECT_EQ(sum.variants[1].max_ulps, 0);

  std::string split = "float2 Split(float A)\n{\n\tprecise float T = 4097.0f * A;\n\tprecise float Hi = T - (T - A);\n"
                      "\tprecise float Lo = A - Hi;\n\treturn float2(Hi, Lo);\n}\n";
  std::string whole = "float2 Split(float A)\n{\n\treturn float2(A, 0.0f);\n}\n";
  FunctionResult halves = verify_function(*d.device, d.probes, setup, "Split", {{"original (float32)", split}, {"whole", whole}});
  ASSERT_EQ(halves.variants.size(), 2u);
  EXPECT_EQ(halves.variants[0].status, "pass") << halves.variants[0].worst;
  EXPECT_EQ(halves.variants[1].status, "fail");
  EXPECT_NE(halves.variants[1].worst.find("where a split's hold at most 12"), std::string::npos) << halves.variants[1].worst;

  std::string product = "float2 Product(float A, float B)\n{\n\tprecise float P = A * B;\n\tprecise float E = fma(A, B, -P);\n"
                        "\treturn float2(P, E * 0.5f);\n}\n";
  FunctionResult halved = verify_function(*d.device, d.probes, setup, "Product", {{"original (float32)", product}});
  ASSERT_EQ(halved.variants.size(), 1u);
  EXPECT_EQ(halved.variants[0].status, "fail");
  EXPECT_GT(halved.variants[0].max_ulps, 0);
  EXPECT_NE(halved.variants[0].worst.find("ULPs off"), std::string::npos) << halved.variants[0].worst;
}

// A bool result is a decision: differences are counted, not measured in ULPs.
TEST(HarnessOnLavapipe, BoolResultsAreComparedAsDecisions) {
  Driver d = start_driver();
  ASSERT_NE(d.device, nullptr);
  auto shader = [](const std::string& test) {
    return "#version 320 es\nprecision highp float;\nuniform vec3 cameraPosition;\n"
           "bool isNear(vec3 worldPosition) { return " + test + "; }\nvoid main() {}\n";
  };
  FunctionResult r = verify_function(*d.device, d.probes, glsl_setup(), "isNear",
                                     {{"original (float32)", shader("distance(worldPosition, cameraPosition) < 500.0")},
                                      {"always", shader("true")}});
  ASSERT_EQ(r.variants.size(), 2u);
  const VariantResult& v = r.variants[1];
  EXPECT_EQ(v.status, "fail");
  EXPECT_GT(v.mismatches, 0);
  EXPECT_EQ(v.max_ulps, 0.0);
  EXPECT_NE(v.worst.find("a different decision"), std::string::npos) << v.worst;
}

// A corpus file of Unreal code, its safe fixes applied, and a harness set-up for it.
struct CorpusFile {
  std::string original, fixed;
  HarnessSetup setup;
};
CorpusFile corpus_file(const std::string& path) {
  Source source(path, test::read(test::source_dir() + "/" + path));
  CorpusFile file{source.text(), fix_source(source, AnalyzeOptions{}, true).text, small_setup(Lang::hlsl, path)};
  file.setup.unreal = true;
  return file;
}

// The corpus-level mutant (issue 15 §3): `precise` removed from the library, so lavapipe folds
// every error term. The original (5.4 DoubleFloat code) and its reference call the library as
// much as the rewrite does. Judged blind, the correct rewrite is refuted; with the library checked
// first (as `verify` does), it is not judged and the library is named, and the reference, which
// calls the same broken functions, is not trusted.
TEST(HarnessOnLavapipe, ACorrectRewriteIsNotBlamedForAFaultInTheLibraryItCalls) {
  Driver d = start_driver();
  ASSERT_NE(d.device, nullptr);
  std::string mutated = full_library_text(Lang::hlsl);
  size_t removed = 0;
  for (size_t at; (at = mutated.find("precise ")) != std::string::npos; ++removed) mutated.erase(at, 8);
  ASSERT_GT(removed, 0u);
  LibraryCheckOptions check;
  check.langs = {Lang::hlsl};
  check.inputs = 16384;
  check.library[Lang::hlsl] = mutated;
  std::map<std::string, std::string> faults = library_faults(check_library(*d.device, d.probes, check), Lang::hlsl);
  ASSERT_TRUE(faults.count("DFAddDemote")) << faults.size();

  CorpusFile file = corpus_file("corpus/ue5.4/DistanceFieldShadowDF.usf");
  file.setup.unreal_library = mutated;
  std::vector<FileVariant> variants = {{"original (float32)", file.original, 504}, {"fixed", file.fixed, 504}};
  FunctionResult blind = verify_function(*d.device, d.probes, file.setup, "WorldOffsetFromCamera", variants);
  ASSERT_EQ(blind.variants.size(), 2u);
  EXPECT_TRUE(blind.variants[1].refuted()) << blind.variants[1].status;  // the blame the check prevents

  file.setup.library_faults = faults;
  file.setup.cache = make_variant_cache();
  FunctionResult r = verify_function(*d.device, d.probes, file.setup, "WorldOffsetFromCamera", variants);
  ASSERT_EQ(r.variants.size(), 2u);
  EXPECT_TRUE(r.reference.starts_with("no reference to trust: the original calls `DF")) << r.reference;
  EXPECT_TRUE(r.variants[1].status.starts_with("not judged: it calls `DF")) << r.variants[1].status;
  EXPECT_NE(r.variants[1].status.find("fails the DoubleFloat library's own check on this driver"), std::string::npos);
  EXPECT_FALSE(r.variants[1].refuted());
}

// A matrix demoted whole by the migration marker keeps its large translation, rounded to float32
// (the stub once returned the float4x4 without it: original and reference then agreed on a wrong
// position, and the hack passed).
TEST(HarnessOnLavapipe, AMatrixDemotedByTheMarkerKeepsItsTranslationInFloat32) {
  Driver d = start_driver();
  ASSERT_NE(d.device, nullptr);
  HarnessSetup setup = small_setup(Lang::hlsl, "Hack.usf");
  setup.unreal = true;
  setup.facts.returns["ToWorld"] = Kind::absolute;  // as lint's model says of it
  std::string code = "#include \"/Engine/Private/Common.ush\"\n"
                     "float3 ToWorld(float3 LocalPosition)\n{\n"
                     "\treturn mul(float4(LocalPosition, 1), LWCHackToFloat(GetPrimitiveData(0).LocalToWorld)).xyz;\n}\n";
  FunctionResult r = verify_function(*d.device, d.probes, setup, "ToWorld", {{"original (float32)", code, 504}});
  ASSERT_EQ(r.variants.size(), 1u);
  const VariantResult& v = r.variants[0];
  ASSERT_TRUE(v.measured) << v.status;
  EXPECT_EQ(v.status, "fail");
  EXPECT_GT(v.max_error, 1.0);       // float32 translations far out: centimetres to kilometres off
  EXPECT_LT(v.median_error, 1e4);    // but the translation is there: not the object's whole distance from the origin
}

// A result's unit comes from the model too: an output the model says is an absolute position is
// judged in centimetres whatever it is called, and a render target (SV_Target) is unitless
// whatever it was computed from.
TEST(HarnessOnLavapipe, AResultsUnitComesFromTheModelAndARenderTargetIsUnitless) {
  Driver d = start_driver();
  ASSERT_NE(d.device, nullptr);
  HarnessSetup setup = glsl_setup();
  setup.facts.globals["vP"] = Kind::absolute;
  std::string glsl = "#version 320 es\nprecision highp float;\nuniform mat4 modelMatrix;\nout vec3 vP;\n"
                     "void place(vec3 position) { vP = (modelMatrix * vec4(position, 1.0)).xyz; }\nvoid main() {}\n";
  FunctionResult placed = verify_function(*d.device, d.probes, setup, "place", {{"original (float32)", glsl}});
  ASSERT_EQ(placed.variants.size(), 1u);
  EXPECT_TRUE(placed.variants[0].world_outputs) << placed.variants[0].status;
  EXPECT_GT(placed.variants[0].max_error, 1.0);  // a float32 world position far out, in cm

  HarnessSetup hlsl = small_setup(Lang::hlsl, "Target.usf");
  hlsl.facts.parameters["Shade"] = {Kind::absolute, Kind::absolute};
  std::string target = "void Shade(float3 WorldPosition, out float4 OutColor : SV_Target0)\n{\n\tOutColor = float4(WorldPosition * 0.001f, 1);\n}\n";
  FunctionResult shaded = verify_function(*d.device, d.probes, hlsl, "Shade", {{"original (float32)", target}});
  ASSERT_EQ(shaded.variants.size(), 1u);
  EXPECT_FALSE(shaded.variants[0].world_outputs) << shaded.variants[0].worst;
}

// The UE 5.0 tile/offset vertex factory moved to DoubleFloat matrices: the low part of each
// matrix's translation reaches the shader (a GCC 12 vectoriser bug once dropped it on the host).
TEST(HarnessOnLavapipe, DoubleFloatMatrixRewriteOfATileOffsetFactoryIsSubCentimetre) {
  Driver d = start_driver();
  ASSERT_NE(d.device, nullptr);
  CorpusFile file = corpus_file("corpus/ue5.0/LWCVertexFactory.ush");
  ASSERT_NE(file.fixed, file.original);
  FunctionResult r = verify_function(*d.device, d.probes, file.setup, "TransformLocalToWorld",
                                     {{"original (float32)", file.original, 500}, {"fixed", file.fixed, 504}});
  ASSERT_EQ(r.variants.size(), 2u);
  const VariantResult &original = r.variants[0], &rewrite = r.variants[1];
  ASSERT_TRUE(original.measured) << original.status;
  ASSERT_TRUE(rewrite.measured) << rewrite.status;
  EXPECT_LT(rewrite.max_error, 0.5) << rewrite.worst;
  EXPECT_LT(rewrite.median_error, 1e-3);
  // The original's FLWC offset larger than a tile costs it precision the rewrite does not lose.
  EXPECT_GT(original.max_error, rewrite.max_error);
}

// A rewrite that keeps, inside the function, code lwcport could not port (here the kept
// `LWCHackToFloat` of an object position) carries the original's error: it is incomplete there,
// never counted as a refuted rewrite. The same variant's other functions are judged as usual.
TEST(HarnessOnLavapipe, ARewriteThatKeepsAMarkerInTheFunctionIsIncompleteNotRefuted) {
  Driver d = start_driver();
  ASSERT_NE(d.device, nullptr);
  CorpusFile file = corpus_file("corpus/ue5.0/LWCVertexFactory.ush");
  Source fixed_source("fixed", file.fixed);
  FileVariant rewrite{"fixed", file.fixed, 504, {}};
  for (int line = 1; line <= fixed_source.line_count(); ++line)
    if (fixed_source.line_text(line).find("LWCHackToFloat(") != std::string_view::npos) rewrite.hand_fixes[line] = "lwc-hack-marker";
  ASSERT_FALSE(rewrite.hand_fixes.empty());
  HarnessSetup& setup = file.setup;
  std::vector<FileVariant> variants = {{"original (float32)", file.original, 500}, rewrite};
  // The fix leaves this function as it was (its marker kept): unchanged, though the fixed file
  // builds against UE 5.4 and the original against 5.0.
  FunctionResult wind = verify_function(*d.device, d.probes, setup, "GetObjectWorldPositionForWind", variants);
  ASSERT_EQ(wind.variants.size(), 2u);
  EXPECT_EQ(wind.variants[0].status, "fail");
  EXPECT_EQ(wind.variants[1].status.rfind("unchanged: ", 0), 0u) << wind.variants[1].status;
  EXPECT_FALSE(wind.variants[1].refuted());
  FunctionResult transform = verify_function(*d.device, d.probes, setup, "TransformLocalToWorld", variants);
  EXPECT_EQ(transform.variants[1].status.find("incomplete"), std::string::npos) << transform.variants[1].status;

  // Here the fix changes what the function calls (GetWorldPosition) but keeps its marker: the
  // error it still has is what the marker keeps.
  CorpusFile material = corpus_file("corpus/ue5.0/MaterialTemplateLWC.ush");
  AnalyzeOptions translated;
  translated.strategy = Strategy::translated;
  Source material_source("corpus/ue5.0/MaterialTemplateLWC.ush", material.original);
  FileVariant ported{"translated world", fix_source(material_source, translated, true).text, 504, {}};
  Source ported_source("fixed", ported.text);
  for (int line = 1; line <= ported_source.line_count(); ++line)
    if (ported_source.line_text(line).find("LWCHackToFloat(") != std::string_view::npos) ported.hand_fixes[line] = "lwc-hack-marker";
  ASSERT_FALSE(ported.hand_fixes.empty());
  FunctionResult noise = verify_function(*d.device, d.probes, material.setup, "CalcPixelWorldPositionForNoise",
                                         {{"original (float32)", material.original, 500}, ported});
  ASSERT_EQ(noise.variants.size(), 2u);
  EXPECT_EQ(noise.variants[1].status.rfind("incomplete: line ", 0), 0u) << noise.variants[1].status;
  EXPECT_NE(noise.variants[1].status.find("lwc-hack-marker"), std::string::npos);
  EXPECT_FALSE(noise.variants[1].refuted());
}

// FDFInverseMatrix as UE 5.4's DoubleFloat.ush has it: PreTranslation is subtracted before M (and
// FDFMatrix's PostTranslation added after it). The engine's own spelling, the library's
// DFMultiplyDemote and a float32 original all go world -> local; a sign error in the library or
// in how the harness splits the matrix puts the rewrites an object's distance away.
TEST(HarnessOnLavapipe, DoubleFloatInverseMatrixSubtractsItsPreTranslationAsTheEngineDoes) {
  Driver d = start_driver();
  ASSERT_NE(d.device, nullptr);
  auto shader = [](const std::string& parameters, const std::string& body) {
    return "#include \"/Engine/Private/Common.ush\"\n"
           "float3 ToLocal(" + parameters + ") { " + body + " }\n";
  };
  HarnessSetup setup = small_setup(Lang::hlsl, "ToLocal.usf");
  setup.unreal = true;
  FunctionResult r = verify_function(
      *d.device, d.probes, setup, "ToLocal",
      {{"original (float32)", shader("float3 WorldPosition, float4x4 WorldToLocal", "return mul(float4(WorldPosition, 1), WorldToLocal).xyz;"), 427},
       {"library", shader("FDFVector3 WorldPosition, FDFInverseMatrix WorldToLocal", "return DFMultiplyDemote(WorldPosition, WorldToLocal);"), 504},
       {"engine spelling", shader("FDFVector3 WorldPosition, FDFInverseMatrix WorldToLocal",
                                  "float3 V = DFFastSubtractDemote(WorldPosition, WorldToLocal.PreTranslation); return mul(float4(V, 1), WorldToLocal.M).xyz;"), 504}});
  ASSERT_EQ(r.variants.size(), 3u);
  for (size_t i = 1; i < 3; ++i) {
    ASSERT_TRUE(r.variants[i].measured) << r.variants[i].label << ": " << r.variants[i].status;
    // Sub-millimetre typically; the worst case is a 1e4-scaled object, whose float matrix scales
    // the demoted position's rounding with it.
    EXPECT_LT(r.variants[i].median_error, 1e-3) << r.variants[i].label << ": " << r.variants[i].worst;
    EXPECT_LT(r.variants[i].max_error * 100, r.variants[0].max_error) << r.variants[i].label;
  }
}

// The rotation of an object's inverse transform is finite whatever its origin: the harness moves
// the origin out of the float matrix without letting an infinite one (the Inf input case) reach
// the rotation as 0 * inf. The rewrite that takes only the rotation (`DFToFloat3x3`) then gives
// the float32 original's result on every case.
TEST(HarnessOnLavapipe, AnInverseMatrixWithAnInfiniteOriginKeepsAFiniteRotation) {
  Driver d = start_driver();
  ASSERT_NE(d.device, nullptr);
  auto shader = [](const std::string& parameters, const std::string& body) {
    return "#include \"/Engine/Private/Common.ush\"\n"
           "float3 ToLocalDirection(" + parameters + ") { " + body + " }\n";
  };
  HarnessSetup setup = small_setup(Lang::hlsl, "ToLocalDirection.usf");
  setup.unreal = true;
  FunctionResult r = verify_function(
      *d.device, d.probes, setup, "ToLocalDirection",
      {{"original (float32)", shader("float3 WorldDirection, float4x4 WorldToLocal", "return mul(WorldDirection, (float3x3)WorldToLocal);"), 427},
       {"rotation", shader("float3 WorldDirection, FDFInverseMatrix WorldToLocal", "return mul(WorldDirection, DFToFloat3x3(WorldToLocal));"), 504}});
  ASSERT_EQ(r.variants.size(), 2u);
  EXPECT_EQ(r.variants[0].status, "pass") << r.variants[0].worst;
  EXPECT_EQ(r.variants[1].status, "pass") << r.variants[1].worst;
  EXPECT_EQ(r.variants[1].max_error, r.variants[0].max_error);
}

// Effects code calls engine helpers that have nothing to do with world space (a screen UV, a 3D
// hash, the material's shared samplers): the stub has them, so the function is judged rather than reported as not compiling; a
// file that defines one itself keeps its own.
TEST(HarnessOnLavapipe, EngineHelpersThatAreNotWorldSpaceBuildInTheStub) {
  Driver d = start_driver();
  ASSERT_NE(d.device, nullptr);
  const std::string body =
      "Texture3D Volume;\n"
      "float3 Jitter(float3 WorldPosition, float4 ScreenPosition) {\n"
      "\tuint3 Hash = Rand3DPCG16(int3(ScreenAlignedPosition(ScreenPosition) * 1024, 7));\n"
      "\tfloat3 Density = Volume.SampleLevel(Material.Clamp_WorldGroupSettings, ScreenPosition.xyz, 0).rgb;\n"
      "\treturn WorldPosition - ResolvedView.WorldCameraOrigin + float3(Hash) / 65536.0 + Density;\n}\n";
  for (const std::string& own : {std::string(), std::string("uint3 Rand3DPCG16(int3 p) { return uint3(p) * 3u; }\n")}) {
    HarnessSetup setup = small_setup(Lang::hlsl, "Jitter.usf");
    setup.unreal = true;
    FunctionResult r = verify_function(*d.device, d.probes, setup, "Jitter",
                                       {{"original (float32)", "#include \"/Engine/Private/Common.ush\"\n" + own + body, 427}});
    ASSERT_EQ(r.variants.size(), 1u);
    EXPECT_TRUE(r.variants[0].measured) << r.variants[0].status << r.variants[0].worst;
  }
}

// glslang's HLSL narrows `sqrt`, `floor`, `dot`... on doubles to float: the float64 reference calls
// double versions of its own. On lavapipe they are exact (rounding functions) or within an ulp or
// two of double (sqrt and what uses it), where the float forms are off by 2^-24.
TEST(HarnessOnLavapipe, TheHlslReferencesDoubleIntrinsicsAreDoubleAccurate) {
  Driver d = start_driver();
  ASSERT_NE(d.device, nullptr);
  const std::vector<double> xs = {1.0 + 0x1p-40, 0x1p43 - 0.5, -2.5, 2.5, 0.49999999999999994, -0.0, 0x1p52 + 1, -0x1p52 - 3,
                                  1e-300, 1e300, 3.0000000000000004, 7.25, -7.75, 0x1p24 + 0.5, 1e-7, 123456789.123};
  const char* names[] = {"sqrt", "floor", "ceil", "round", "trunc", "frac", "length3", "min", "lerp", "fmod"};
  KernelSpec spec;
  spec.lang = Lang::hlsl;
  spec.name = "double-intrinsics";
  spec.float64 = true;
  spec.in_stride = 1;
  spec.out_stride = 10;
  spec.declarations = hlsl_double_intrinsics();
  spec.body = "\tdouble x = IN(0);\n\tdouble y = IN(0) * 0.75 + 1.0;\n"
              "\tOUT(0, lwc_d_sqrt(abs(x)));\n\tOUT(1, lwc_d_floor(x));\n\tOUT(2, lwc_d_ceil(x));\n\tOUT(3, lwc_d_round(x));\n"
              "\tOUT(4, lwc_d_trunc(x));\n\tOUT(5, lwc_d_frac(x));\n\tOUT(6, lwc_d_length(double3(x, y, 1.0)));\n"
              "\tOUT(7, lwc_d_min(x, y));\n\tOUT(8, lwc_d_lerp(x, y, 0.375));\n\tOUT(9, lwc_d_fmod(x, 3.0));\n";
  CompileResult compiled = compile_kernel(spec);
  ASSERT_TRUE(compiled.ok) << format_messages(compiled);
  std::vector<double> in(kKernelGroupSize, 1.0);
  std::copy(xs.begin(), xs.end(), in.begin());
  std::vector<std::vector<uint8_t>> buffers = {to_bytes(in), std::vector<uint8_t>(in.size() * 10 * sizeof(double))};
  ASSERT_EQ(d.device->run(compiled.spirv, buffers, 1), "");
  std::vector<double> out = from_bytes<double>(buffers[1]);
  for (size_t i = 0; i < xs.size(); ++i) {
    double x = xs[i], y = x * 0.75 + 1.0;
    double want[] = {std::sqrt(std::fabs(x)), std::floor(x), std::ceil(x), std::nearbyint(x), std::trunc(x), x - std::floor(x),
                     std::sqrt(x * x + y * y + 1.0), std::min(x, y), x + (y - x) * 0.375, x - 3.0 * std::trunc(x / 3.0)};
    for (int k = 0; k < 10; ++k) {
      double got = out[i * 10 + k];
      if (k == 6 && !std::isfinite(want[k])) continue;  // 1e300 squared overflows either way
      double tolerance = k == 0 || k == 6 ? 4 * std::numeric_limits<double>::epsilon() * std::fabs(want[k]) : 0.0;
      EXPECT_LE(std::fabs(got - want[k]), tolerance) << names[k] << "(" << x << ") = " << got << ", want " << want[k];
      if (k >= 1 && k <= 4) EXPECT_EQ(std::signbit(got), std::signbit(want[k])) << names[k] << "(" << x << ")";
    }
  }
}

// An intrinsic glslang narrows that lwcport has no double version of (`ldexp`) is named: the
// function gets no verdict against a reference that is float32 in places. One it covers (`length`)
// keeps its float64 reference.
TEST(HarnessOnLavapipe, AReferenceThatWouldComputeInFloat32IsNamedNotJudged) {
  Driver d = start_driver();
  ASSERT_NE(d.device, nullptr);
  HarnessSetup setup = small_setup(Lang::hlsl, "narrow.usf");
  std::string code = "float3 CameraPosition;\n"
                     "float Far(float3 WorldPosition)\n{\n\treturn ldexp(WorldPosition.x, 2.0) + length(WorldPosition - CameraPosition);\n}\n"
                     "float Near(float3 WorldPosition)\n{\n\treturn length(WorldPosition - CameraPosition);\n}\n";
  FunctionResult far = verify_function(*d.device, d.probes, setup, "Far", {{"original (float32)", code}});
  EXPECT_NE(far.reference.find("no float64 reference: the float64 reference would compute in float32"), std::string::npos) << far.reference;
  EXPECT_NE(far.reference.find("`return ldexp("), std::string::npos) << far.reference;
  FunctionResult near = verify_function(*d.device, d.probes, setup, "Near", {{"original (float32)", code}});
  EXPECT_EQ(near.reference, "the original promoted to float64 (transcendentals in float32)");
}

// A variant in which the fix left this function and all it uses as they were (it changed another
// function of the file) is "unchanged": not a refuted rewrite, however the original fares.
TEST(HarnessOnLavapipe, AVariantThatLeavesTheFunctionAsItWasIsUnchangedNotRefuted) {
  Driver d = start_driver();
  ASSERT_NE(d.device, nullptr);
  std::string original = "#version 450\nuniform vec3 cameraPosition;\n"
                         "vec3 toCamera(vec3 worldPosition) { return worldPosition - cameraPosition; }\n"
                         "float other(float x) { return x * 2.0; }\nvoid main() {}\n";
  std::string rewrite = original;
  rewrite.replace(rewrite.find("x * 2.0"), 7, "x + x");
  FunctionResult r = verify_function(*d.device, d.probes, glsl_setup(), "toCamera", {{"original (float32)", original}, {"fixed", rewrite}});
  ASSERT_EQ(r.variants.size(), 2u);
  EXPECT_NE(r.variants[0].status, "pass") << r.variants[0].worst;  // float32 world positions
  EXPECT_TRUE(r.variants[1].status.starts_with("unchanged")) << r.variants[1].status;
  EXPECT_FALSE(r.variants[1].refuted());
  FunctionResult changed = verify_function(*d.device, d.probes, glsl_setup(), "other", {{"original (float32)", original}, {"fixed", rewrite}});
  EXPECT_FALSE(changed.variants[1].status.starts_with("unchanged")) << changed.variants[1].status;
}

// The pick is the fastest passing variant fix can write; costs within the measurement's spread
// (and 25%) are equal, identical SPIR-V always is, and then the fewest SPIR-V instructions decide,
// so a second run that measures 7% differently picks the same. Failing and unwritable variants are never picked.
TEST(Pick, CostsTheMeasurementCannotTellApartAreEqualAndFewerInstructionsDecide) {
  auto variant = [](std::string label, double ns, double spread, int instructions, std::string status = "pass", bool writable = true) {
    VariantResult v;
    v.label = std::move(label);
    v.ns_per_invocation = ns;
    v.cost_spread = spread;
    v.spirv_instructions = instructions;
    v.status = std::move(status);
    v.writable = writable;
    v.measured = true;
    return v;
  };
  FunctionResult r;
  r.variants = {variant("original (float32)", 10, 0.02, 100, "fail"), variant("translated world", 10.4, 0.03, 120),
                variant("DoubleFloat", 10.0, 0.03, 140), variant("DoubleFloat, DFFast*", 5, 0.02, 90, "pass", false)};
  pick_variant(r, 1.0 / 16);
  EXPECT_EQ(r.pick.rfind("translated world:", 0), 0u) << r.pick;
  EXPECT_NE(r.pick.find("2 run equally fast"), std::string::npos) << r.pick;
  EXPECT_FALSE(r.variants[0].pareto);
  EXPECT_TRUE(r.variants[1].pareto);
  EXPECT_TRUE(r.variants[2].pareto);
  EXPECT_FALSE(r.variants[3].pareto);
  // The other run: DoubleFloat measured 7% slower, translated world 3% faster: the same pick.
  r.variants[1].ns_per_invocation = 10.1, r.variants[2].ns_per_invocation = 10.8;
  pick_variant(r, 1.0 / 16);
  EXPECT_EQ(r.pick.rfind("translated world:", 0), 0u) << r.pick;
  // Clearly faster (by more than the spread and 25%) wins whatever its instruction count...
  r.variants[2].ns_per_invocation = 7;
  pick_variant(r, 1.0 / 16);
  EXPECT_EQ(r.pick.rfind("DoubleFloat:", 0), 0u) << r.pick;
  EXPECT_FALSE(r.variants[1].pareto);  // slower at the same error
  // ... unless it is the same SPIR-V, measured apart by noise.
  r.variants[1].spirv_hash = r.variants[2].spirv_hash = 42;
  pick_variant(r, 1.0 / 16);
  EXPECT_EQ(r.pick.rfind("translated world:", 0), 0u) << r.pick;
  EXPECT_TRUE(r.variants[1].pareto);
  r.variants[1].spirv_hash = 41;
  // A wide spread widens what counts as equal.
  r.variants[2].cost_spread = 0.5;
  pick_variant(r, 1.0 / 16);
  EXPECT_EQ(r.pick.rfind("translated world:", 0), 0u) << r.pick;
  // Nothing passing: no pick.
  for (auto& v : r.variants) v.status = "fail";
  pick_variant(r, 1.0 / 16);
  EXPECT_EQ(r.pick.rfind("none:", 0), 0u) << r.pick;
}

}  // namespace
}  // namespace lwc
