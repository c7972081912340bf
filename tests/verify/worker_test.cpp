// The driver in its own process: a shader that hangs lavapipe, or crashes it, costs that kernel
// only. The hang and the crash are real (nested loops of 2^48 steps per invocation; a store through a
// null-page device address), and the kernel after
// each one runs on a fresh driver process with the right answer.
#include <gtest/gtest.h>

#include "verify/compile.h"
#include "verify/kernel.h"
#include "verify/worker.h"

namespace lwc {
namespace {

std::vector<uint32_t> kernel(const std::string& body) {
  KernelSpec spec;
  spec.lang = Lang::glsl;
  spec.name = "worker-test.comp";
  spec.body = body;
  spec.in_stride = 1;
  spec.out_stride = 1;
  CompileResult r = compile_kernel(spec);
  EXPECT_TRUE(r.ok) << format_messages(r);
  return r.spirv;
}

constexpr size_t kCount = 4096;
const char* kDouble = "OUT(0, IN(0) * 2.0);";

// Runs `body` on 0..kCount-1; returns the error and the output.
std::string run(WorkerDevice& device, const std::string& body, std::vector<float>& out) {
  std::vector<float> in(kCount);
  for (size_t i = 0; i < kCount; ++i) in[i] = static_cast<float>(i);
  std::vector<std::vector<uint8_t>> buffers = {to_bytes(in), std::vector<uint8_t>(kCount * sizeof(float))};
  std::string why = device.run(kernel(body), buffers, kCount / kKernelGroupSize);
  out = from_bytes<float>(buffers[1]);
  return why;
}

void expect_doubled(WorkerDevice& device) {
  std::vector<float> out;
  ASSERT_EQ(run(device, kDouble, out), "");
  for (size_t i = 0; i < kCount; ++i) ASSERT_EQ(out[i], 2.0f * static_cast<float>(i)) << i;
}

TEST(DriverProcess, RunsKernelsAndReadsTheirResultsBack) {
  std::string error;
  auto device = WorkerDevice::start(error);
  ASSERT_NE(device, nullptr) << error;
  EXPECT_NE(device->name().find("llvmpipe"), std::string::npos) << device->name();
  expect_doubled(*device);
  expect_doubled(*device);
}

TEST(DriverProcess, AHangingShaderTimesOutAndTheNextKernelStillRuns) {
  std::string error;
  auto device = WorkerDevice::start(error, 2.0);
  ASSERT_NE(device, nullptr) << error;
  // The trip count comes from the buffer, so the compiler cannot shorten the loop.
  std::vector<float> out;
  // llvmpipe ends any loop after 65,535 trips, so each trip does 2,000 dependent square roots:
  // about 2^37 per invocation, far past the 2 s limit on lavapipe.
  std::string step = "x = sqrt(x + float(k));";
  std::string body = "float x = IN(0);\nfor (uint k = 0u; k < 65535u + uint(IN(0)); ++k) {";
  for (int i = 0; i < 2000; ++i) body += step;
  std::string why = run(*device, body + "}\nOUT(0, x);", out);
  EXPECT_NE(why.find("did not finish within 2 s"), std::string::npos) << why;
  expect_doubled(*device);
}

TEST(DriverProcess, AShaderThatCrashesTheDriverIsReportedAndTheNextKernelStillRuns) {
  std::string error;
  auto device = WorkerDevice::start(error, 30.0);
  ASSERT_NE(device, nullptr) << error;
  // lavapipe bounds-checks buffer accesses, but not a store through a raw device address.
  CompileInput in;
  in.lang = Lang::glsl;
  in.stage = Stage::compute;
  in.name = "crash.comp";
  in.spirv = true;
  in.text = "#version 450\n#extension GL_EXT_buffer_reference : require\n"
            "#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require\n"
            "layout(local_size_x = 64) in;\nlayout(buffer_reference, std430) buffer Cell { float value; };\n"
            "layout(std430, binding = 0) buffer In { float x[]; };\n"
            "void main() { Cell(uint64_t(0x10u + uint(x[gl_GlobalInvocationID.x] >= 0.0))).value = 1.0; }\n";
  CompileResult crash = compile_shader(in);
  ASSERT_TRUE(crash.ok) << format_messages(crash);
  std::vector<std::vector<uint8_t>> buffers = {std::vector<uint8_t>(kCount * sizeof(float))};
  std::string why = device->run(crash.spirv, buffers, kCount / kKernelGroupSize);
  EXPECT_NE(why.find("the driver crashed running this kernel"), std::string::npos) << why;
  EXPECT_NE(why.find("signal"), std::string::npos) << why;
  expect_doubled(*device);
}

}  // namespace
}  // namespace lwc
