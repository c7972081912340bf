// The corpus goldens: `lwcport lint --format json corpus/` must report exactly what each
// corpus/<...>/<file>.expected.json (e.g. forward.vert.expected.json) says. LWCPORT_UPDATE_GOLDEN=1 rewrites them; review the
// diff before committing, a golden regenerated to match a bug is a defect.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <map>

#include <nlohmann/json.hpp>

#include "lang/syntax.h"
#include "corpus_files.h"
#include "support.h"

namespace fs = std::filesystem;

namespace lwc {
namespace {

TEST(Corpus, HasAtLeastTwentyShadersOfEveryEra) {
  auto files = test::corpus_shaders();
  EXPECT_GE(files.size(), 20u);
  for (const char* dir : {"corpus/ue4/", "corpus/ue5.0/", "corpus/ue5.4/", "corpus/d3d/", "corpus/glsl/", "corpus/negative/"})
    EXPECT_TRUE(std::any_of(files.begin(), files.end(), [&](auto& f) { return f.rfind(dir, 0) == 0; })) << dir;
}

TEST(Corpus, EveryShaderParsesWithoutSyntaxErrors) {
  auto r = test::run("cd " + test::source_dir() + " && " + test::binary() + " parse corpus");
  EXPECT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("; 0 with syntax errors;"), std::string::npos) << r.out;
}

TEST(Corpus, FindingsMatchTheGoldensExactly) {
  auto r = test::run("cd " + test::source_dir() + " && " + test::binary() + " lint corpus --format json --fail-on none");
  ASSERT_EQ(r.exit_code, 0);
  auto doc = nlohmann::json::parse(r.out);
  std::map<std::string, nlohmann::json> by_file;
  for (const auto& f : test::corpus_shaders()) by_file[f] = nlohmann::json::array();
  for (auto f : doc.at("findings")) {
    std::string path = f.at("path");
    f.erase("path");
    f.erase("fingerprint");  // the baseline's identity of a finding (docs/baseline.md), not part of the golden
    ASSERT_TRUE(by_file.count(path)) << "finding in a file that is not a corpus shader: " << path;
    by_file[path].push_back(f);
  }
  bool update = std::getenv("LWCPORT_UPDATE_GOLDEN") != nullptr;
  for (const auto& [path, findings] : by_file) {
    std::string golden = test::source_dir() + "/" + path + ".expected.json";
    nlohmann::json got = {{"findings", findings}};
    if (update) {
      test::write(golden, got.dump(2) + "\n");
      continue;
    }
    ASSERT_TRUE(fs::exists(golden)) << golden << " is missing";
    EXPECT_EQ(got, nlohmann::json::parse(test::read(golden))) << path;
  }
}

TEST(Corpus, NegativeCasesAreClean) {
  auto r = test::run("cd " + test::source_dir() + " && " + test::binary() +
                     " lint corpus/negative/NormalsAndTangents.hlsl corpus/negative/LocalSpaceMath.vert "
                     "corpus/negative/AlreadyTranslated.usf corpus/glsl/rte_highlow_precise.vert corpus/glsl/splitmodel.vert "
                     "corpus/ue5.4/TranslatedWorldVertexFactory.ush corpus/negative/OrdinaryArithmetic.usf "
                     "corpus/negative/UnrealOtherSpaces.usf corpus/negative/VertexFactoryTranslated.usf corpus/negative/NormalsOnly.vert "
                     "--color never");
  EXPECT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("No findings in 10 file(s)."), std::string::npos) << r.out;
}

}  // namespace
}  // namespace lwc
