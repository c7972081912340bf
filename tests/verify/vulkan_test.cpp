// The Vulkan runner on lavapipe (a real driver, on the CPU): shaders run, buffers round-trip, and
// the hazard the whole library guards against is visible: without `precise` the driver folds
// TwoSum's error term to zero; with it, the error term is exact.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "verify/compile.h"
#include "verify/kernel.h"
#include "verify/vulkan.h"

namespace lwc {
namespace {

std::vector<uint32_t> compute_spirv(const std::string& glsl) {
  CompileInput in;
  in.lang = Lang::glsl;
  in.stage = Stage::compute;
  in.name = "probe.comp";
  in.text = glsl;
  in.spirv = true;
  CompileResult r = compile_shader(in);
  EXPECT_TRUE(r.ok) << format_messages(r);
  return r.spirv;
}

// TwoSum over pairs (a, b): writes (s, e) with s + e == a + b exactly when the steps are kept.
std::string two_sum_shader(const char* qualifier) {
  return std::string("#version 450\nlayout(local_size_x = 64) in;\n"
                     "layout(std430, binding = 0) readonly buffer In { vec2 ab[]; };\n"
                     "layout(std430, binding = 1) writeonly buffer Out { vec2 se[]; };\n"
                     "void main() {\n  uint i = gl_GlobalInvocationID.x;\n  float a = ab[i].x, b = ab[i].y;\n  ") +
         qualifier + " float s = a + b;\n  " + qualifier + " float v = s - a;\n  " + qualifier +
         " float e = (a - (s - v)) + (b - v);\n  se[i] = vec2(s, e);\n}\n";
}

class OnLavapipe : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string error;
    device_ = ComputeDevice::open(error);
    ASSERT_NE(device_, nullptr) << error;
  }
  // Runs TwoSum on 64 pairs (1, tiny) and returns the error terms.
  std::vector<float> error_terms(const char* qualifier) {
    std::vector<float> in;
    for (int i = 0; i < 64; ++i) in.push_back(1.0f), in.push_back(std::ldexp(1.0f + i / 64.0f, -30));
    std::vector<std::vector<uint8_t>> buffers = {to_bytes(in), std::vector<uint8_t>(64 * 2 * sizeof(float))};
    std::string why = device_->run(compute_spirv(two_sum_shader(qualifier)), buffers, 1);
    EXPECT_EQ(why, "");
    std::vector<float> out = from_bytes<float>(buffers[1]), errors;
    for (size_t i = 0; i < 64; ++i) errors.push_back(out[2 * i + 1]);
    return errors;
  }
  std::unique_ptr<ComputeDevice> device_;
};

TEST_F(OnLavapipe, TheCpuDeviceIsChosenAndHasFloat64) {
  EXPECT_NE(device_->name().find("llvmpipe"), std::string::npos) << device_->name();
  EXPECT_TRUE(device_->supports_float64());
}

TEST_F(OnLavapipe, PreciseKeepsTheTwoSumErrorTermExact) {
  std::vector<float> errors = error_terms("precise");
  for (int i = 0; i < 64; ++i) EXPECT_EQ(errors[i], std::ldexp(1.0f + i / 64.0f, -30)) << i;
}

TEST_F(OnLavapipe, WithoutPreciseTheDriverFoldsTheErrorTermToZero) {
  // LWC-BRIEF §5, measured: llvmpipe simplifies (a - (s - (s - a))) when it may reassociate.
  for (float e : error_terms("")) EXPECT_EQ(e, 0.0f);
}

TEST_F(OnLavapipe, TimingsAreRecordedPerRepeat) {
  std::vector<std::vector<uint8_t>> buffers = {std::vector<uint8_t>(64 * 8), std::vector<uint8_t>(64 * 8)};
  DispatchTiming timing;
  EXPECT_EQ(device_->run(compute_spirv(two_sum_shader("precise")), buffers, 1, 5, &timing), "");
  EXPECT_EQ(timing.dispatch_seconds.size(), 5u);
  EXPECT_GT(timing.pipeline_seconds, 0.0);
}

TEST(ComputeDeviceOpen, WithoutADriverTheErrorNamesThePackagesToInstall) {
  // The loader reads VK_ICD_FILENAMES when the instance is created: point it at nothing.
  const char* saved = std::getenv("VK_ICD_FILENAMES");
  std::string restore = saved ? saved : "";
  ::setenv("VK_ICD_FILENAMES", "/nonexistent/lwcport_icd.json", 1);
  std::string error;
  auto device = ComputeDevice::open(error);
  if (saved) ::setenv("VK_ICD_FILENAMES", restore.c_str(), 1);
  else ::unsetenv("VK_ICD_FILENAMES");
  EXPECT_EQ(device, nullptr);
  EXPECT_NE(error.find("mesa-vulkan-drivers"), std::string::npos) << error;
}

// glslang cannot set up a stage's built-ins below the version that has the stage, and for a text
// without `#version` (its default is 110) it then printed all of them to standard output, into a
// JSON report. A stage without `#version` now gets a version that has it; explicit versions that
// lack the stage are glslang's own errors.
TEST(Compile, AVersionWithoutTheStageIsRefusedAndNothingReachesStandardOutput) {
  auto compile = [](Stage stage, const std::string& text) {
    CompileInput in;
    in.lang = Lang::glsl;
    in.stage = stage;
    in.name = "old.glsl";
    in.text = text;
    return compile_shader(in);
  };
  testing::internal::CaptureStdout();
  CompileResult geometry = compile(Stage::geometry, "#version 110\nvoid main() {}\n");
  CompileResult es_compute = compile(Stage::compute, "#version 300 es\nlayout(local_size_x = 1) in;\nvoid main() {}\n");
  CompileResult tess = compile(Stage::tess_control, "#version 320 es\nlayout(vertices = 3) out;\nvoid main() {}\n");
  CompileResult unversioned = compile(Stage::compute, "layout(local_size_x = 1) in;\nvoid main() {}\n");
  CompileResult mesh = compile(Stage::mesh, "void main() {}\n");
  CompileResult geometry_unversioned = compile(Stage::geometry, "layout(points) in;\nlayout(points, max_vertices = 1) out;\nvoid main() {}\n");
  EXPECT_EQ(testing::internal::GetCapturedStdout(), "");
  ASSERT_FALSE(geometry.ok);
  EXPECT_NE(geometry.messages.at(0).text.find("geometry shaders require"), std::string::npos);
  ASSERT_FALSE(es_compute.ok);
  EXPECT_NE(es_compute.messages.at(0).text.find("compute shaders require"), std::string::npos);
  EXPECT_TRUE(tess.ok) << format_messages(tess);
  EXPECT_TRUE(unversioned.ok) << format_messages(unversioned);
  EXPECT_FALSE(mesh.ok);  // needs its extension; an error, not a dump
  EXPECT_TRUE(geometry_unversioned.ok) << format_messages(geometry_unversioned);
}

}  // namespace
}  // namespace lwc
