// The per-function harness on lavapipe: a corpus vertex shader in float32 is caught at large
// coordinates, its translated-world rewrite is measured far closer to the float64 reference.
#include <gtest/gtest.h>

#include "fix/apply.h"
#include "shaderlib/shaderlib.h"
#include "support.h"
#include "verify/harness.h"
#include "verify/probes.h"
#include "verify/worker.h"

namespace lwc {
namespace {

TEST(HarnessOnLavapipe, ForwardVertexShaderOriginalFailsAndTheRewriteIsFarCloser) {
  std::string error;
  auto device = WorkerDevice::start(error);
  ASSERT_NE(device, nullptr) << error;
  DriverProbes probes;
  ASSERT_EQ(probe_driver(*device, probes), "");
  std::string path = "corpus/glsl/forward.vert";
  Source source(path, test::read(test::source_dir() + "/" + path));
  AnalyzeOptions options;
  options.lang = Lang::glsl;
  std::string fixed = fix_source(source, options, true).text;
  ASSERT_NE(fixed, source.text());
  HarnessSetup setup;
  setup.lang = Lang::glsl;
  setup.display = path;
  setup.stage = Stage::vertex;
  setup.invocations = 8192;
  setup.repeats = 2;
  setup.include = [](const std::string& name, const std::string&) -> std::optional<std::string> {
    if (name == library_file_name(Lang::glsl)) return full_library_text(Lang::glsl);
    return std::nullopt;
  };
  FunctionResult r = verify_function(*device, probes, setup, "main", {{"original (float32)", source.text()}, {"fixed", fixed}});
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

}  // namespace
}  // namespace lwc
