// lwcport's DoubleFloat library on lavapipe against a double-double reference: the good library
// meets every published bound, and the known-bad variants are caught (LWC-BRIEF §4-§5).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <regex>

#include "shaderlib/shaderlib.h"
#include "verify/library_accuracy.h"
#include "verify/probes.h"
#include "verify/worker.h"

namespace lwc {
namespace {

class LibraryOnLavapipe : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    std::string error;
    device_ = WorkerDevice::start(error).release();
    ASSERT_NE(device_, nullptr) << error;
    ASSERT_EQ(probe_driver(*device_, probes_), "");
  }
  static void TearDownTestSuite() { delete device_; }

  // One operation checked in one language.
  static OpMeasurement check_one(LibraryOp op, Lang lang = Lang::glsl) {
    LibraryCheckOptions options;
    options.langs = {lang};
    options.ops = {std::move(op)};
    LibraryAccuracy result = check_library(*device_, probes_, options);
    return result.ops.at(0).by_lang.at(lang);
  }
  static const LibraryOp& library_op(const std::string& call, InputFamily inputs) {
    for (const LibraryOp& op : library_ops())
      if (op.call == call && op.inputs == inputs) return op;
    throw std::runtime_error("no library op " + call);
  }

  static WorkerDevice* device_;
  static DriverProbes probes_;
};
WorkerDevice* LibraryOnLavapipe::device_ = nullptr;
DriverProbes LibraryOnLavapipe::probes_;

TEST_F(LibraryOnLavapipe, ProbesFindReassociationUnfusedFmaAndKeptDenormals) {
  // lavapipe (llvmpipe, LLVM 15) as measured in LWC-BRIEF §5.
  EXPECT_EQ(probes_.reassociated, DriverProbes::kInputs);
  EXPECT_EQ(probes_.fma_fused, 0);
  EXPECT_TRUE(probes_.keeps_denormals());
}

TEST_F(LibraryOnLavapipe, EveryOperationMeetsItsBoundInBothLanguages) {
  LibraryCheckOptions options;
  LibraryAccuracy result = check_library(*device_, probes_, options);
  EXPECT_FALSE(result.failed());
  for (Lang lang : {Lang::glsl, Lang::hlsl}) {
    EXPECT_TRUE(result.contraction_losses.at(lang).empty());
    EXPECT_EQ(result.error_free_functions_checked.at(lang), 6);  // DFFastToTranslatedWorld's precise steps among them
  }
  for (const OpReport& r : result.ops)
    for (const auto& [lang, m] : r.by_lang) {
      EXPECT_GE(m.inputs, 100000u);
      if (r.op->bound.kind != Bound::none && !r.op->needs_fused_fma)
        EXPECT_EQ(m.status, "pass") << r.op->call << " " << lang_name(lang) << ": " << m.worst;
      if (r.op->bound.kind == Bound::exact && !r.op->needs_fused_fma) EXPECT_EQ(m.max_relative, 0.0) << r.op->call;
    }
}

TEST_F(LibraryOnLavapipe, FmaProductIsReportedNotFailedWhereFmaIsNotFused) {
  OpMeasurement m = check_one(library_op("DFTwoProductFMA(a, b)", InputFamily::product));
  EXPECT_NE(m.status.find("reported: needs a fused fma"), std::string::npos) << m.status;
  EXPECT_GT(m.max_relative, 0.5 * 0x1p-24);  // the error term is lost: float32 accuracy only
}

// Products whose operand is beyond Dekker's split limit (4097 * A overflows) come out NaN even when
// the result fits: counted apart as outside the domain, every other input still judged.
TEST_F(LibraryOnLavapipe, DekkerProductsBeyondTheSplitLimitAreCountedOutsideTheDomain) {
  OpMeasurement m = check_one(library_op("DFMultiply(A, B)", InputFamily::product));
  EXPECT_EQ(m.status, "pass") << m.worst;
  EXPECT_EQ(m.beyond_split_limit.inputs, 256u);
  EXPECT_EQ(m.beyond_split_limit.misses, 256u);
  EXPECT_NE(m.beyond_split_limit.example.find("beyond Dekker's split limit"), std::string::npos) << m.beyond_split_limit.example;
  EXPECT_NE(m.beyond_split_limit.example.find("nan"), std::string::npos) << m.beyond_split_limit.example;
  EXPECT_EQ(m.denormal_range.inputs, 0u);
  EXPECT_LT(m.max_relative, 5 * 0x1p-48);  // the judged inputs keep the published 5u^2
}

// A driver that flushes denormals (NVIDIA's, measured: RESULTS.md session 26) loses the error
// terms of the 'denormal low parts' case, far below any world value: those inputs are counted apart
// there, and judged where the probe saw denormals kept.
TEST_F(LibraryOnLavapipe, DenormalLowPartsAreOutsideTheDomainOnlyWhereTheDriverFlushes) {
  const LibraryOp& add = library_op("DFAdd(A, B)", InputFamily::sum);
  OpMeasurement kept = check_one(add);
  EXPECT_EQ(kept.status, "pass") << kept.worst;
  EXPECT_EQ(kept.denormal_range.inputs, 0u);

  DriverProbes flushing = probes_;
  flushing.denormals_kept = 0;
  LibraryCheckOptions options;
  options.langs = {Lang::glsl};
  options.ops = {add};
  OpMeasurement flushed = check_library(*device_, flushing, options).ops.at(0).by_lang.at(Lang::glsl);
  EXPECT_EQ(flushed.status, "pass") << flushed.worst;
  EXPECT_EQ(flushed.denormal_range.inputs, 256u);
  EXPECT_EQ(flushed.denormal_range.misses, 0u);  // lavapipe keeps them: nothing missed, only not judged
  EXPECT_EQ(flushed.inputs, kept.inputs);
  EXPECT_EQ(flushed.worst.find("denormal"), std::string::npos) << flushed.worst;
}

// A shader's own TwoSum gets the same operands, the same way.
TEST(FloatOperands, DenormalLowPartsAreLeftOutOnlyWhereTheDriverFlushes) {
  std::vector<std::string> names = adversarial_case_names(InputFamily::sum);
  int denormal = static_cast<int>(std::find(names.begin(), names.end(), "denormal low parts") - names.begin());
  ASSERT_LT(denormal, static_cast<int>(names.size()));
  auto count = [&](bool flushes) {
    std::vector<FloatOperands> ops = float_operands(InputFamily::sum, 16384, flushes);
    return std::count_if(ops.begin(), ops.end(), [&](const FloatOperands& o) { return o.case_index == denormal; });
  };
  EXPECT_EQ(count(false), 256);
  EXPECT_EQ(count(true), 0);
}

TEST_F(LibraryOnLavapipe, LibraryWithoutPreciseIsCaughtByTheSpirvAndTheNumbers) {
  LibraryCheckOptions options;
  options.langs = {Lang::glsl, Lang::hlsl};
  options.library[Lang::glsl] = std::regex_replace(full_library_text(Lang::glsl), std::regex("LWC_PRECISE "), "");
  options.library[Lang::hlsl] = std::regex_replace(full_library_text(Lang::hlsl), std::regex("precise "), "");
  options.ops = {library_op("DFTwoSum(a, b)", InputFamily::sum), library_op("DFAdd(A, B)", InputFamily::sum)};
  LibraryAccuracy result = check_library(*device_, probes_, options);
  EXPECT_TRUE(result.failed());
  for (Lang lang : {Lang::glsl, Lang::hlsl}) {
    ASSERT_FALSE(result.contraction_losses.at(lang).empty());
    EXPECT_NE(result.contraction_losses.at(lang).front().find("0 of"), std::string::npos);
    for (const OpReport& r : result.ops) EXPECT_EQ(r.by_lang.at(lang).status, "fail") << r.op->call;
  }
}

TEST_F(LibraryOnLavapipe, FastTwoSumWithTheOperandsSwappedIsCaught) {
  LibraryOp swapped = library_op("DFFastTwoSum(a, b)", InputFamily::ordered);
  swapped.call = "DFFastTwoSum(b, a)";  // |b| <= |a|: the precondition is broken
  OpMeasurement m = check_one(swapped);
  EXPECT_EQ(m.status, "fail");
  EXPECT_NE(m.worst.find("case '"), std::string::npos) << m.worst;
  EXPECT_NE(m.worst.find("expected"), std::string::npos) << m.worst;
}

TEST_F(LibraryOnLavapipe, SloppyAddWhereTheAccurateBoundIsNeededIsCaughtOnTheCounterexample) {
  LibraryOp sloppy = library_op("DFFastAdd(A, B)", InputFamily::opposite);
  sloppy.bound = library_op("DFAdd(A, B)", InputFamily::sum).bound;
  OpMeasurement m = check_one(sloppy, Lang::hlsl);
  EXPECT_EQ(m.status, "fail");
  EXPECT_NE(m.worst.find("sloppy-add counterexample"), std::string::npos) << m.worst;
  EXPECT_GT(m.max_relative, 0.05);  // off by a unit in 2k + 1, k <= 7
}

// Faults injected into the library text, as a bug in it would look: each must make the operation
// that depends on it fail, in both languages, on inputs chosen for that fault.
TEST_F(LibraryOnLavapipe, MutantsOfTheLibraryAreEachCaughtNamingTheOperation) {
  struct Mutant {
    const char* name;
    const char* from;
    const char* to;
    std::vector<std::pair<std::string, InputFamily>> caught_by;
    const char* glsl_from = nullptr;  // where the GLSL library spells the fault differently
    const char* glsl_to = nullptr;
  };
  auto matrix_op = [](const char* prefix) {
    for (const LibraryOp& op : library_ops())
      if (op.call.rfind(prefix, 0) == 0) return op.call;
    return std::string(prefix);
  };
  const Mutant mutants[] = {
      {"split constant 4096", "4097.0 * A", "4096.0 * A",
       {{"DFTwoProductDekker(a, b)", InputFamily::product}, {"DFMultiply(A, B)", InputFamily::product}}},
      {"product's error term dropped", "Cl3 = C.Low + Cl2;", "Cl3 = Cl2;", {{"DFMultiply(A, B)", InputFamily::product}}},
      {"DFDemote returns High", "return V.High + V.Low; }", "return V.High; }", {{"DFDemote(A)", InputFamily::uncanonical}}},
      {"tile size 2^20", "#define LWC_DF_TILE_SIZE 2097152.0", "#define LWC_DF_TILE_SIZE 1048576.0",
       {{"DFFromTileOffset(a, b)", InputFamily::tile_offset}, {"DFToTileOffset(A, Tile, Offset)", InputFamily::world}}},
      {"pair + float drops A.Low", "V = A.Low + S.Low;", "V = S.Low;", {{"DFAdd(A, b)", InputFamily::sum}}},
      {"DFSubtract adds", "return DFAdd(A, DFNegate(B)); }", "return DFAdd(A, B); }",
       {{"DFSubtract(A, B)", InputFamily::sum}}},
      {"pair * float drops A.Low * B", "Cl2 = A.Low * B;", "Cl2 = A.Low * 0.0;", {{"DFMultiply(A, b)", InputFamily::product}}},
      {"pair / float drops the product's low part", "Dt = Dh - P.Low;", "Dt = Dh;", {{"DFDivide(A, b)", InputFamily::quotient}}},
      {"pair / pair drops the low difference", "D = Ph + Dl;", "D = Ph;", {{"DFDivide(A, B)", InputFamily::quotient}}},
      {"AddDemote drops the lows", "R = S.High + (S.Low + (A.Low + B.Low));", "R = S.High + S.Low;",
       {{"DFAddDemote(A, B)", InputFamily::sum}, {"DFSubtractDemote(A, B)", InputFamily::sum}}},
      {"AddDemote (pair + float) drops A.Low", "R = S.High + (S.Low + A.Low);", "R = S.High + S.Low;", {{"DFAddDemote(A, b)", InputFamily::sum}}},
      {"MultiplyDemote drops the cross terms", "R = C.High + (C.Low + (A.High * B.Low + A.Low * B.High));", "R = C.High + C.Low;",
       {{"DFMultiplyDemote(A, B)", InputFamily::product}}},
      {"MultiplyDemote (pair * float) drops A.Low * B", "R = C.High + (C.Low + A.Low * B);", "R = C.High + C.Low;",
       {{"DFMultiplyDemote(A, b)", InputFamily::product}}},
      {"DivideDemote drops the correction", "R = Th + ((A.High - P.High) - P.Low + A.Low) / B;", "R = Th;",
       {{"DFDivideDemote(A, b)", InputFamily::quotient}}},
      {"local subtraction drops the lows", "R = H + L;", "R = H;",
       {{"DFFastLocalSubtractDemote(A, B)", InputFamily::close}, {matrix_op("DFFastToTranslatedWorld("), InputFamily::opposite}}},
      {"translated world drops the view translation's low", "L = WorldPos.Low + PreViewTranslation.Low;", "L = WorldPos.Low;",
       {{matrix_op("DFFastToTranslatedWorld("), InputFamily::opposite}}},
      {"FDFMatrix's PostTranslation applied before M", "mul(float4(P, 1.0), M.M).xyz)", "mul(float4(P + M.PostTranslation, 1.0), M.M).xyz - M.PostTranslation)",
       {{matrix_op("MakeDFScalar(DFMultiply("), InputFamily::sum}}, "(M.M * vec4(P, 1.0)).xyz)",
       "(M.M * vec4(P + M.PostTranslation, 1.0)).xyz - M.PostTranslation)"},
      {"FDFInverseMatrix's PreTranslation subtracted after M", "mul(float4(DFSubtractDemote(P, M.PreTranslation), 1.0), M.M).xyz",
       "mul(float4(DFDemote(P), 1.0), M.M).xyz - M.PreTranslation", {{matrix_op("DFMultiplyDemote(MakeDFVector3("), InputFamily::sum}},
       "(M.M * vec4(DFSubtractDemote(P, M.PreTranslation), 1.0)).xyz", "(M.M * vec4(DFDemote(P), 1.0)).xyz - M.PreTranslation"},
      {"local to translated world rounds the view translation first", "Offset = DFAddDemote(PreViewTranslation, LocalToWorld.PostTranslation);",
       "Offset = DFDemote(PreViewTranslation) + LocalToWorld.PostTranslation;",
       {{matrix_op("DFTransformLocalToTranslatedWorld("), InputFamily::opposite}}},
      {"tile rounded down, not to the nearest", "Tile = floor(V.High / LWC_DF_TILE_SIZE + 0.5);", "Tile = floor(V.High / LWC_DF_TILE_SIZE);",
       {{"DFToTileOffset(A, Tile, Offset)", InputFamily::world}}},
  };
  for (const Mutant& mutant : mutants) {
    LibraryCheckOptions options;
    options.inputs = 16384;
    for (Lang lang : {Lang::glsl, Lang::hlsl}) {
      std::string text = full_library_text(lang);
      const char* from = lang == Lang::glsl && mutant.glsl_from ? mutant.glsl_from : mutant.from;
      const char* to = lang == Lang::glsl && mutant.glsl_to ? mutant.glsl_to : mutant.to;
      size_t replaced = 0;
      for (size_t at = 0; (at = text.find(from, at)) != std::string::npos; ++replaced, at += std::strlen(to)) text.replace(at, std::strlen(from), to);
      ASSERT_GT(replaced, 0u) << mutant.name << ": the fault is not in the " << lang_name(lang) << " library";
      options.library[lang] = text;
    }
    for (const auto& [call, family] : mutant.caught_by) options.ops.push_back(library_op(call, family));
    LibraryAccuracy result = check_library(*device_, probes_, options);
    EXPECT_TRUE(result.failed()) << mutant.name;
    for (const OpReport& r : result.ops)
      for (const auto& [lang, m] : r.by_lang)
        EXPECT_EQ(m.status, "fail") << mutant.name << " survives in " << r.op->call << " (" << lang_name(lang) << "): " << m.worst;
  }
}

}  // namespace
}  // namespace lwc
