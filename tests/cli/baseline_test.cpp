// Adopting lwcport on old code (issue 17 part 2): a baseline that lets only new findings fail,
// fingerprints that survive moved lines, GitHub's line hashes, and --add-suppressions.
#include <gtest/gtest.h>

#include <filesystem>

#include <nlohmann/json.hpp>

#include "fix/suppress.h"
#include "project/baseline.h"
#include "support.h"

namespace lwc {
namespace {

namespace fs = std::filesystem;

TEST(LineHashes, MatchTheValuesGitHubsCodeQLActionPublishesInItsTests) {
  // The expected hashes are those the CodeQL action's own tests give for these inputs
  // (src/fingerprints.test.ts): the hash GitHub code scanning computes for uploaded SARIF.
  EXPECT_EQ(line_hashes(""), std::vector<std::string>{"c129715d7a2bc9a3:1"});
  EXPECT_EQ(line_hashes(" a\nb\n  \t\tc\n d"),
            (std::vector<std::string>{"271789c17abda88f:1", "54703d4cd895b18:1", "180aee12dab6264:1", "a23a3dc5e078b07b:1"}));
  std::vector<std::string> seven = {"e9496ae3ebfced30:1", "fb7c023a8b9ccb3f:1", "ce8ba1a563dcdaca:1", "e20e36e16fcb0cc8:1",
                                    "b3edc88f2938467e:1", "c8e28b0b4002a3a0:1", "c129715d7a2bc9a3:1"};
  EXPECT_EQ(line_hashes(" hello; \t\nworld!!!\n\n\n  \t\tGreetings\n End\n"), seven);
  EXPECT_EQ(line_hashes(" hello; \t\nworld!!!\r\r\r  \t\tGreetings\r End\r"), seven);
  EXPECT_EQ(line_hashes(" hello; \t\r\nworld!!!\r\n\r\n\r\n  \t\tGreetings\r\n End\r\n"), seven);
  EXPECT_EQ(line_hashes(" hello; \t\nworld!!!\r\n\n\r  \t\tGreetings\r End\r\n"), seven);
  std::string lorem;
  for (int i = 0; i < 10; ++i) lorem += "Lorem ipsum dolor sit amet.\n";
  EXPECT_EQ(line_hashes(lorem), (std::vector<std::string>{"a7f2ff13bc495cf2:1", "a7f2ff13bc495cf2:2", "a7f2ff13bc495cf2:3",
                                                           "a7f2ff13bc495cf2:4", "a7f2ff13bc495cf2:5", "a7f2ff13bc495cf2:6",
                                                           "a7f2ff1481e87703:1", "a9cf91f7bbf1862b:1", "55ec222b86bcae53:1",
                                                           "cc97dc7b1d7d8f7b:1", "c129715d7a2bc9a3:1"}));
}

TEST(Fingerprints, CountOccurrencesOfARulesTextAndIgnoreBlanks) {
  EXPECT_EQ(normalised_text("  View.\n\t WorldCameraOrigin \r\n"), "View. WorldCameraOrigin");
  auto prints = fingerprint_all({{"r", "a"}, {"r", "b"}, {"r", "a"}, {"s", "a"}});
  EXPECT_EQ(prints[0].occurrence, 0);
  EXPECT_EQ(prints[2].occurrence, 1);
  EXPECT_EQ(prints[3].occurrence, 0);
  std::set<std::string> distinct;
  for (const auto& p : prints) distinct.insert(p.fingerprint);
  EXPECT_EQ(distinct.size(), 4u);
  EXPECT_EQ(fingerprint_all({{"r", "a"}})[0].fingerprint, prints[0].fingerprint);  // the same in every run
}

TEST(AddSuppressions, TrailingCommentsJoinedIdsContinuedLinesAndScripts) {
  SuppressionSites sites;
  sites.rules_by_line = {{1, {"lwc-b", "lwc-a"}}, {2, {"lwc-c"}}, {3, {"lwc-d"}}, {4, {"lwc-e"}}};
  EXPECT_EQ(with_suppressions("float3 A;  \r\nfloat3 B; /* lwcport-ignore: lwc-x */\n#define C(x) x \\\n\tfloat3 D;", sites),
            "float3 A; // lwcport-ignore: lwc-a, lwc-b  \r\n"
            "float3 B; /* lwcport-ignore: lwc-x, lwc-c */\n"
            "#define C(x) x /* lwcport-ignore: lwc-d */ \\\n"
            "\tfloat3 D; // lwcport-ignore: lwc-e");
  SuppressionSites script;
  script.rules_by_line = {{1, {"lwc-a"}}};
  script.inside_at = {{1, 8}};
  EXPECT_EQ(with_suppressions("  vec3 p = q;`;", script), "  vec3 p /* lwcport-ignore: lwc-a */ = q;`;");
}

const char* kTwo =
    "float3 F(float3 L)\n{\n\tfloat3 W = DFDemote(DFMultiply(L, Primitive.LocalToWorld));\n\treturn W - View.WorldCameraOrigin;\n}\n";

test::Run lint_in(const std::string& dir, const std::string& args) {
  return test::run("cd " + dir + " && " + test::binary() + " lint " + args + " --color never");
}

TEST(Baseline, OnlyNewFindingsFailAndStaleEntriesAreListedAndPruned) {
  std::string dir = test::scratch("baseline");
  test::write(dir + "/src/a.usf", kTwo);
  test::write(dir + "/src/b.usf", kTwo);
  auto wrote = test::run("cd " + dir + " && " + test::binary() + " lint src --write-baseline ci/lwcport-baseline.json 2>&1");
  EXPECT_EQ(wrote.exit_code, 0) << wrote.out;
  EXPECT_NE(wrote.out.find("Wrote a baseline of 4 finding(s)"), std::string::npos) << wrote.out;
  auto doc = nlohmann::json::parse(test::read(dir + "/ci/lwcport-baseline.json"));
  ASSERT_EQ(doc["findings"].size(), 4u);
  EXPECT_EQ(doc["findings"][0]["path"], "../src/a.usf");  // relative to the baseline's folder
  EXPECT_EQ(doc.dump().find("\"line\""), std::string::npos) << "no line numbers";
  EXPECT_EQ(lint_in(dir, "src --baseline ci/lwcport-baseline.json").exit_code, 0);

  // Lines move and code elsewhere changes: still nothing new.
  test::write(dir + "/src/a.usf", std::string("// header\n\nfloat Other() { return 1; }\n") + kTwo);
  auto moved = lint_in(dir, "src --baseline ci/lwcport-baseline.json 2>&1");
  EXPECT_EQ(moved.exit_code, 0) << moved.out;
  EXPECT_NE(moved.out.find("No findings in 2 file(s)."), std::string::npos) << moved.out;
  EXPECT_NE(moved.out.find("4 known finding(s) not reported."), std::string::npos) << moved.out;

  // A new finding fails the run, alone.
  test::write(dir + "/src/a.usf", std::string("// header\n") + kTwo + "float3 G(float3 P) { return P - View.WorldViewOrigin; }\n");
  auto added = lint_in(dir, "src --baseline ci/lwcport-baseline.json --format json");
  EXPECT_EQ(added.exit_code, 1);
  auto report = nlohmann::json::parse(added.out);
  ASSERT_EQ(report["findings"].size(), 1u) << added.out;
  EXPECT_EQ(report["findings"][0]["start"]["line"], 7);
  EXPECT_EQ(report["findings"][0]["rule"], "lwc-primary-view");

  // One is fixed: its entry is stale, listed, and pruned on request.
  std::string fixed = kTwo;
  fixed.replace(fixed.find("View.WorldCameraOrigin"), 22, "View.TranslatedWorldCameraOrigin");
  test::write(dir + "/src/b.usf", fixed);
  auto stale = test::run("cd " + dir + " && " + test::binary() + " lint src/b.usf --baseline ci/lwcport-baseline.json 2>&1 >/dev/null");
  EXPECT_EQ(stale.exit_code, 0) << stale.out;
  EXPECT_NE(stale.out.find("1 entry no longer matches"), std::string::npos) << stale.out;
  EXPECT_NE(stale.out.find("../src/b.usf: lwc-primary-view: `View.WorldCameraOrigin`"), std::string::npos) << stale.out;
  // Linting another file alone does not call b.usf's entries stale.
  EXPECT_EQ(test::run("cd " + dir + " && " + test::binary() + " lint src/a.usf --baseline ci/lwcport-baseline.json --fail-on none 2>&1 >/dev/null")
                .out.find("no longer match"),
            std::string::npos);
  test::run("cd " + dir + " && " + test::binary() + " lint src --baseline ci/lwcport-baseline.json --prune-baseline > /dev/null 2>&1");
  EXPECT_EQ(nlohmann::json::parse(test::read(dir + "/ci/lwcport-baseline.json"))["findings"].size(), 3u);
  EXPECT_EQ(test::run("cd " + dir + " && " + test::binary() + " lint src --baseline ci/lwcport-baseline.json --fail-on none 2>&1 >/dev/null")
                .out.find("no longer match"),
            std::string::npos);
  // A file that is gone leaves stale entries too.
  fs::remove(dir + "/src/b.usf");
  EXPECT_NE(test::run("cd " + dir + " && " + test::binary() + " lint src --baseline ci/lwcport-baseline.json --fail-on none 2>&1 >/dev/null")
                .out.find("no longer match"),
            std::string::npos);
  // A broken baseline is a clear error.
  test::write(dir + "/bad.json", "{\"findings\": 3}");
  auto bad = test::run("cd " + dir + " && " + test::binary() + " lint src --baseline bad.json 2>&1");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.out.find("bad.json: not a lwcport baseline"), std::string::npos) << bad.out;
}

TEST(Baseline, SarifCarriesFingerprintsThatSurviveMovedLinesAndGitHubsLineHash) {
  std::string dir = test::scratch("sarif-fingerprints");
  test::write(dir + "/a.usf", kTwo);
  auto prints = [&]() {
    auto sarif = nlohmann::json::parse(lint_in(dir, "a.usf --format sarif").out);
    std::vector<nlohmann::json> out;
    for (const auto& r : sarif["runs"][0]["results"]) out.push_back(r["partialFingerprints"]);
    return out;
  };
  auto before = prints();
  ASSERT_EQ(before.size(), 2u);
  std::vector<std::string> hashes = line_hashes(kTwo);
  EXPECT_EQ(before[0]["primaryLocationLineHash"], hashes[2]);  // line 3
  EXPECT_EQ(before[1]["primaryLocationLineHash"], hashes[3]);
  test::write(dir + "/a.usf", std::string("\n\n// moved down\n") + kTwo);
  auto after = prints();
  ASSERT_EQ(after.size(), 2u);
  EXPECT_EQ(after[0]["lwcport/v1"], before[0]["lwcport/v1"]);
  EXPECT_EQ(after[1]["lwcport/v1"], before[1]["lwcport/v1"]);
  // GitHub's hash reads the line and what follows it, so it moves with the code too.
  EXPECT_EQ(after[0]["primaryLocationLineHash"], line_hashes(test::read(dir + "/a.usf"))[5]);
  EXPECT_EQ(after[0]["primaryLocationLineHash"], before[0]["primaryLocationLineHash"]);
}

TEST(AddSuppressions, EveryFindingOfTheCorpusIsSilencedAndASecondRunAddsNothing) {
  std::string dir = test::scratch("add-suppressions");
  fs::copy(test::source_dir() + "/corpus", dir + "/corpus", fs::copy_options::recursive);
  auto count_rules = [&]() {
    std::map<std::string, int> rules;
    auto report = nlohmann::json::parse(lint_in(dir, "corpus --format json --fail-on none").out);
    for (const auto& f : report["findings"]) ++rules[f["rule"].get<std::string>()];
    return rules;
  };
  std::map<std::string, int> before = count_rules();
  ASSERT_GT(before.size(), 5u);
  auto added = test::run("cd " + dir + " && " + test::binary() + " lint corpus --add-suppressions 2>&1 >/dev/null");
  EXPECT_EQ(added.exit_code, 0) << added.out;
  EXPECT_NE(added.out.find("Added a suppression comment to "), std::string::npos) << added.out;
  std::map<std::string, int> after = count_rules();
  // What remains is what no comment can silence: input problems and the corpus's own stale suppression.
  std::map<std::string, int> expected;
  for (const char* rule : {"lwc-input", "lwc-unused-suppression"})
    if (before.count(rule)) expected[rule] = before[rule];
  EXPECT_EQ(after, expected);
  auto again = test::run("cd " + dir + " && " + test::binary() + " lint corpus --add-suppressions 2>&1 >/dev/null");
  EXPECT_NE(again.out.find("Added a suppression comment to 0 line(s) in 0 file(s)."), std::string::npos) << again.out;
}

}  // namespace
}  // namespace lwc
