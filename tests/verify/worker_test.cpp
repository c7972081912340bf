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

// Kernels kept after their run are timed against each other in rounds: a kernel doing about 20
// times the work costs clearly more, the same kernel kept twice costs the same within the stated
// spread, and the run's results came back untouched by the keeping.
TEST(DriverProcess, KeptKernelsAreTimedInInterleavedRounds) {
  std::string error;
  auto device = WorkerDevice::start(error);
  ASSERT_NE(device, nullptr) << error;
  std::string heavy = "float x = IN(0);\nfor (int k = 0; k < 200; ++k) x = sqrt(x + 1.0);\nOUT(0, x);";
  std::vector<uint64_t> kept;
  for (const std::string& body : {std::string(kDouble), std::string(kDouble), heavy}) {
    std::vector<float> in(kCount, 3.0f);
    std::vector<std::vector<uint8_t>> buffers = {to_bytes(in), std::vector<uint8_t>(kCount * sizeof(float))};
    uint64_t id = 0;
    ASSERT_EQ(device->run(kernel(body), buffers, kCount / kKernelGroupSize, 1, nullptr, &id), "");
    if (body == kDouble) EXPECT_EQ(from_bytes<float>(buffers[1])[7], 6.0f);
    kept.push_back(id);
  }
  TimingPlan plan;
  InterleavedTiming t;
  ASSERT_EQ(device->time_interleaved(kept, plan, t), "");
  ASSERT_EQ(t.seconds.size(), 3u);
  EXPECT_GE(t.rounds, plan.min_rounds);
  EXPECT_LE(t.rounds, plan.max_rounds);
  for (const auto& samples : t.seconds) EXPECT_EQ(samples.size(), static_cast<size_t>(t.rounds));
  double light = median_of(t.seconds[0]), again = median_of(t.seconds[1]), heavier = median_of(t.seconds[2]);
  EXPECT_GT(heavier, 4 * std::max(light, again));
  // Kept kernels are timed once: asking again is an error, not a stale figure.
  EXPECT_NE(device->time_interleaved(kept, plan, t), "");
}

// A kernel kept by a driver process that was restarted since (a crash, a timeout) is not timed as
// whatever the new process holds under the same number.
TEST(DriverProcess, KernelsKeptBeforeARestartAreNotTimed) {
  std::string error;
  auto device = WorkerDevice::start(error, 2.0);
  ASSERT_NE(device, nullptr) << error;
  std::vector<float> in(kCount, 1.0f);
  std::vector<std::vector<uint8_t>> buffers = {to_bytes(in), std::vector<uint8_t>(kCount * sizeof(float))};
  uint64_t before = 0;
  ASSERT_EQ(device->run(kernel(kDouble), buffers, kCount / kKernelGroupSize, 1, nullptr, &before), "");
  std::string step = "x = sqrt(x + float(k));", body = "float x = IN(0);\nfor (uint k = 0u; k < 65535u + uint(IN(0)); ++k) {";
  for (int i = 0; i < 2000; ++i) body += step;
  std::vector<float> out;
  ASSERT_NE(run(*device, body + "}\nOUT(0, x);", out), "");  // times out: the process is replaced
  uint64_t after = 0;
  ASSERT_EQ(device->run(kernel(kDouble), buffers, kCount / kKernelGroupSize, 1, nullptr, &after), "");
  InterleavedTiming t;
  EXPECT_NE(device->time_interleaved({before}, TimingPlan{}, t).find("restarted"), std::string::npos);
  EXPECT_EQ(device->time_interleaved({after}, TimingPlan{}, t), "");
}

// The median's 95% interval: order statistics around the middle; tight for steady samples, wide
// for scattered ones, and 1 (nothing known) for too few.
TEST(Timing, MedianSpreadIsTheWidthOfTheMediansInterval) {
  EXPECT_EQ(median_of({3, 1, 2}), 2);
  EXPECT_EQ(median_of({4, 1, 3, 2}), 2.5);
  EXPECT_EQ(median_spread({1, 1, 1}), 1);
  EXPECT_EQ(median_spread(std::vector<double>(15, 2.0)), 0);
  std::vector<double> steady, scattered;
  for (int i = 0; i < 31; ++i) {
    steady.push_back(100 + i % 3);
    scattered.push_back(50 + 100 * ((i * 7) % 31) / 31.0);
  }
  EXPECT_LT(median_spread(steady), 0.03);
  EXPECT_GT(median_spread(scattered), 0.3);
}

}  // namespace
}  // namespace lwc
