// SARIF output over the whole corpus passes the OASIS 2.1.0 schema and the SARIF Multitool.
#include <gtest/gtest.h>

#include <filesystem>
#include <set>

#include <nlohmann/json.hpp>

#include "support.h"

namespace lwc {
namespace {

// The shader corpus through `lwcport lint`, or with `host`, the host corpus through `lwcport host`
// (whose fixes may edit two files: one artifact change each).
std::string corpus_sarif(bool host = false) {
  std::string out = test::scratch("sarif") + (host ? "/host.sarif" : "/corpus.sarif");
  auto r = test::run(host ? "cd " + test::source_dir() + "/corpus/host && " + test::binary() + " host . --format sarif --fail-on none --output " + out
                          : "cd " + test::source_dir() + " && " + test::binary() + " lint corpus --format sarif --fail-on none --output " + out);
  EXPECT_EQ(r.exit_code, 0) << r.out;
  return out;
}

// The 2.1.0 schema as npm ships it, pinned by tests/tools/package-lock.json (SchemaStore's rtm.5
// copy, in @microsoft/jest-sarif): the same check in every clone, with nothing read from beside it.
TEST(Sarif, CorpusPassesTheOasisSchema) {
  std::string schema = test::source_dir() + "/tests/tools/node_modules/@microsoft/jest-sarif/lib/schemas/sarif-2.1.0-rtm.5.json";
  for (bool host : {false, true}) {
    auto r = test::run("node " + test::source_dir() + "/tests/tools/validate-sarif.js " + schema + " " + corpus_sarif(host) + " 2>&1");
    EXPECT_EQ(r.exit_code, 0) << schema << "\n" << r.out;
    EXPECT_NE(r.out.find("valid"), std::string::npos) << r.out;
  }
}

// A host fix that edits a header: one artifact change per file, the finding's own first. Run in
// corpus/host, every header under it is the project's (include/ue_mini.h too).
TEST(Sarif, HostFixThatEditsTwoFilesHasAnArtifactChangeForEach) {
  nlohmann::json log = nlohmann::json::parse(test::read(corpus_sarif(true)));
  std::set<std::string> headers;
  for (const auto& result : log["runs"][0]["results"]) {
    if (!result.contains("fixes")) continue;
    const auto& changes = result["fixes"][0]["artifactChanges"];
    EXPECT_EQ(changes[0]["artifactLocation"]["uri"], result["locations"][0]["physicalLocation"]["artifactLocation"]["uri"]) << result.dump();
    ASSERT_LE(changes.size(), 2u) << result.dump();
    if (changes.size() == 2) headers.insert(changes[1]["artifactLocation"]["uri"].get<std::string>());
  }
  EXPECT_EQ(headers, (std::set<std::string>{"header/SkyUniforms.h", "include/ue_mini.h"}));
}

TEST(Sarif, CorpusPassesTheMultitoolWithNoErrorsOrWarnings) {
  std::string tool = test::source_dir() + "/tests/tools/node_modules/@microsoft/sarif-multitool-linux/Sarif.Multitool";
  std::string log = test::scratch("multitool") + "/validation.sarif";
  auto r = test::run(tool + " validate " + corpus_sarif() + " --level \"Error;Warning;Note\" --output " + log + " --log ForceOverwrite 2>&1");
  EXPECT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("Analysis completed successfully"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find(": error SARIF"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find(": warning SARIF"), std::string::npos) << r.out;
  // Its own log proves it ran its rules: notes (advice) are allowed, nothing stronger.
  auto results = nlohmann::json::parse(test::read(log))["runs"][0]["results"];
  EXPECT_FALSE(results.empty());
  for (const auto& res : results) EXPECT_EQ(res.value("level", "warning"), "note") << res.dump();
}

TEST(Sarif, CarriesRuleMetadataAndEveryFinding) {
  auto sarif = nlohmann::json::parse(test::read(corpus_sarif()));
  auto json = nlohmann::json::parse(
      test::run("cd " + test::source_dir() + " && " + test::binary() + " lint corpus --format json --fail-on none").out);
  const auto& run = sarif["runs"][0];
  EXPECT_EQ(run["results"].size(), json["findings"].size());
  EXPECT_EQ(run["tool"]["driver"]["rules"].size(), 21u);
  for (const auto& rule : run["tool"]["driver"]["rules"]) {
    std::string id = rule["id"];
    EXPECT_NE(rule["helpUri"].get<std::string>().find("docs/rules/" + id + ".md"), std::string::npos);
    EXPECT_TRUE(rule["fullDescription"]["text"].is_string());
  }
  const auto& first = run["results"][0];
  EXPECT_EQ(first["locations"][0]["physicalLocation"]["artifactLocation"]["uriBaseId"], "SRCROOT");
  EXPECT_EQ(run["columnKind"], "unicodeCodePoints");
}

}  // namespace
}  // namespace lwc
