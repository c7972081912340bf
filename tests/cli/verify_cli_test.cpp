// `lwcport verify` end to end on lavapipe: a function whose shader hangs the driver is stopped by
// the timeout with a clear error, and the other file's function is still verified.
#include <gtest/gtest.h>

#include "support.h"

namespace lwc {
namespace {

// A vertex shader with world-space findings whose main runs for hours on lavapipe: llvmpipe ends a
// loop after 65,535 trips, so every trip does 2,000 dependent square roots.
std::string hanging_shader() {
  std::string steps;
  for (int i = 0; i < 2000; ++i) steps += "d = sqrt(d + float(k));";
  return "#version 450\nlayout(location = 0) in vec3 position;\n"
         "layout(std140, binding = 0) uniform Camera { mat4 modelMatrix; mat4 viewProjection; };\n"
         "layout(location = 0) out float vDistance;\n"
         "void main() {\n  vec4 worldPosition = modelMatrix * vec4(position, 1.0);\n  float d = length(position);\n"
         "  for (uint k = 0u; k < 65535u + uint(d); ++k) { " + steps + " }\n"
         "  vDistance = d;\n  gl_Position = viewProjection * worldPosition;\n}\n";
}

TEST(VerifyCli, AHangingShaderTimesOutAndTheOtherFilesAreStillVerified) {
  std::string dir = test::scratch("verify-hang");
  test::write(dir + "/a_hangs.vert", hanging_shader());
  test::write(dir + "/b_fine.vert", test::read(test::source_dir() + "/corpus/glsl/rte_highlow.vert"));
  test::Run r = test::run(test::binary() + " verify " + dir + " --timeout 3 --format json");
  size_t hang = r.out.find("a_hangs.vert"), fine = r.out.find("b_fine.vert");
  ASSERT_NE(hang, std::string::npos) << r.out;
  ASSERT_NE(fine, std::string::npos) << r.out;
  std::string hang_part = r.out.substr(hang, fine - hang), fine_part = r.out.substr(fine);
  EXPECT_NE(hang_part.find("\"status\": \"did not run: did not finish within 3 s"), std::string::npos) << hang_part;
  EXPECT_NE(fine_part.find("\"function\": \"translateRelativeToEye\""), std::string::npos) << fine_part;
  EXPECT_NE(fine_part.find("\"status\": \"pass\""), std::string::npos) << fine_part;
  EXPECT_EQ(r.exit_code, 0);  // only the original hangs: no rewrite was shown wrong
}

}  // namespace
}  // namespace lwc
