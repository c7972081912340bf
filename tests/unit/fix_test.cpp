// The fix engine: edits, conflicts, diffs, scene profiles and the planner's decisions.
#include <gtest/gtest.h>

#include <random>
#include <sstream>

#include "fix/apply.h"
#include "fix/diff.h"
#include "fix/scene.h"
#include "support.h"

namespace lwc {
namespace {

TEST(ApplyEdits, ReplacesInsertsAndWritesTheFilesLineEnding) {
  Source lf("a.hlsl", "ab\ncd\n");
  EXPECT_EQ(apply_edits(lf, {{{3, 3}, "x\n"}, {{0, 1}, "A"}}), "Ab\nx\ncd\n");
  Source crlf("a.hlsl", "ab\r\ncd\r\n");
  EXPECT_EQ(apply_edits(crlf, {{{4, 4}, "x\n"}}), "ab\r\nx\r\ncd\r\n");
  EXPECT_THROW(apply_edits(lf, {{{0, 2}, "x"}, {{1, 3}, "y"}}), std::invalid_argument);
  EXPECT_THROW(apply_edits(lf, {{{5, 9}, "x"}}), std::invalid_argument);
}

Finding with_fix(Span edit, Applicability a) {
  Finding f;
  f.rule = "lwc-primary-view";
  Fix fix;
  fix.applicability = a;
  fix.edits = {{edit, "x"}};
  f.fixes = {fix};
  return f;
}

TEST(ChooseFixes, SkipsUnsafeUnlessAskedAndAnythingOverlappingAnEarlierChoice) {
  std::vector<Finding> findings = {with_fix({0, 4}, Applicability::safe), with_fix({2, 6}, Applicability::safe),
                                   with_fix({6, 8}, Applicability::unsafe), with_fix({4, 4}, Applicability::safe)};
  EXPECT_EQ(choose_fixes(findings, false).size(), 2u);  // {0,4} and the insertion at 4; {2,6} overlaps
  EXPECT_EQ(choose_fixes(findings, true).size(), 3u);
  // Two insertions at one offset would be ordered arbitrarily: the second waits.
  std::vector<Finding> inserts = {with_fix({3, 3}, Applicability::safe), with_fix({3, 3}, Applicability::safe)};
  inserts[1].fixes[0].edits[0].text = "y";
  EXPECT_EQ(choose_fixes(inserts, false).size(), 1u);
}

// A chain's fix (many edits) goes before a one-line fix it overlaps, whatever their order in the
// file: the chain's rewrite covers that line too, and taking the line's fix first would leave the
// chain for a later round that may no longer find it.
TEST(ChooseFixes, AWholeChainGoesBeforeTheOneLineFixesItOverlaps) {
  std::vector<Finding> findings = {with_fix({10, 14}, Applicability::safe), with_fix({0, 2}, Applicability::unsafe)};
  findings[1].fixes[0].edits.push_back({{11, 13}, "y"});
  findings[1].fixes[0].edits.push_back({{20, 22}, "z"});
  std::vector<const Fix*> chosen = choose_fixes(findings, true);
  ASSERT_EQ(chosen.size(), 1u);
  EXPECT_EQ(chosen[0]->edits.size(), 3u);
  // Without unsafe fixes the chain is not a candidate, and the line's own fix stands.
  chosen = choose_fixes(findings, false);
  ASSERT_EQ(chosen.size(), 1u);
  EXPECT_EQ(chosen[0]->edits.size(), 1u);
}

TEST(UnifiedDiff, HunksWithContextAndTheMissingFinalNewline) {
  EXPECT_EQ(unified_diff("f", "same\n", "same\n"), "");
  std::string before, after;
  for (int i = 1; i <= 12; ++i) {
    before += "l" + std::to_string(i) + "\n";
    after += (i == 2 ? "L2" : i == 11 ? "L11" : "l" + std::to_string(i)) + "\n";
  }
  EXPECT_EQ(unified_diff("f", before, after),
            "--- a/f\n+++ b/f\n"
            "@@ -1,5 +1,5 @@\n l1\n-l2\n+L2\n l3\n l4\n l5\n"
            "@@ -8,5 +8,5 @@\n l8\n l9\n l10\n-l11\n+L11\n l12\n");
  EXPECT_EQ(unified_diff("f", "a\nb", "a\nc"), "--- a/f\n+++ b/f\n@@ -1,2 +1,2 @@\n a\n-b\n\\ No newline at end of file\n+c\n\\ No newline at end of file\n");
  EXPECT_EQ(unified_diff("f", "", "x\n"), "--- a/f\n+++ b/f\n@@ -0,0 +1 @@\n+x\n");
}

// Applies a unified diff of whole lines to `before` (every line ends in "\n").
std::string patch(const std::string& before, const std::string& diff) {
  std::vector<std::string> in, out;
  std::stringstream a(before), d(diff);
  for (std::string l; std::getline(a, l);) in.push_back(l);
  size_t at = 0;  // next unread line of `in`
  std::string line;
  std::getline(d, line), std::getline(d, line);  // the ---/+++ header
  while (std::getline(d, line)) {
    if (line.rfind("@@ -", 0) == 0) {
      size_t start = std::stoul(line.substr(4));
      size_t count = line.find(',') < line.find(' ', 4) ? std::stoul(line.substr(line.find(',') + 1)) : 1;
      size_t first = count == 0 ? start : start - 1;
      while (at < first) out.push_back(in[at++]);
    } else if (line[0] == ' ') {
      EXPECT_EQ(in.at(at), line.substr(1));
      out.push_back(in[at++]);
    } else if (line[0] == '-') {
      EXPECT_EQ(in.at(at), line.substr(1));
      ++at;
    } else if (line[0] == '+') {
      out.push_back(line.substr(1));
    }
  }
  while (at < in.size()) out.push_back(in[at++]);
  std::string text;
  for (const auto& l : out) text += l + "\n";
  return text;
}

TEST(UnifiedDiff, AppliedBackItGivesTheNewTextOnRandomEdits) {
  std::mt19937 rng(7);
  for (int round = 0; round < 300; ++round) {
    std::string before, after;
    int lines = static_cast<int>(rng() % 40);
    for (int i = 0; i < lines; ++i) {
      std::string l = "line" + std::to_string(rng() % 6);  // repeats make the alignment non-trivial
      before += l + "\n";
      switch (rng() % 5) {
        case 0: break;                                  // removed
        case 1: after += "new" + std::to_string(i) + "\n" + l + "\n"; break;  // inserted before
        case 2: after += "changed" + std::to_string(i) + "\n"; break;
        default: after += l + "\n";
      }
    }
    std::string diff = unified_diff("f", before, after);
    EXPECT_EQ(patch(before, diff), after) << "round " << round << "\n" << diff;
  }
}

TEST(Scene, DistancesTakeAUnitAndPowersOfTwo) {
  EXPECT_DOUBLE_EQ(*parse_distance("100 km"), 1e7);
  EXPECT_DOUBLE_EQ(*parse_distance("2^43 cm"), 8796093022208.0);
  EXPECT_DOUBLE_EQ(*parse_distance("1/16 cm"), 0.0625);
  EXPECT_DOUBLE_EQ(*parse_distance(" 5 mm "), 0.5);
  EXPECT_FALSE(parse_distance("100"));      // no unit
  EXPECT_FALSE(parse_distance("100 feet"));
  EXPECT_FALSE(parse_distance("x km"));
}

TEST(Scene, Float32ErrorIsHalfTheSpacing) {
  EXPECT_DOUBLE_EQ(float32_error(1e5), 1.0 / 256);        // 1 km: spacing 1/128 cm
  EXPECT_DOUBLE_EQ(float32_error(1048576.0), 1.0 / 16);   // 2^20 cm: UE's 1/16 cm limit
  EXPECT_DOUBLE_EQ(float32_error(8796093022208.0), 524288.0);  // 2^43 cm: spacing 2^20
}

TEST(Scene, MalformedProfilesNameTheFileAndPosition) {
  try {
    parse_scene("{\n  \"world-extent\": \"1 km\",\n  oops\n}", "s.json");
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("s.json:3:"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parse_scene("{\"world-extent\": \"far\"}", "s.json"), std::runtime_error);
  EXPECT_THROW(parse_scene("{\"extent\": \"1 km\"}", "s.json"), std::runtime_error);
  Scene s = parse_scene(R"({"world-extent": "50 km", "overrides": [{"paths": ["sky/**"], "view-distance": "50 km"}]})", "s.json");
  EXPECT_DOUBLE_EQ(s.for_path("sky/Clouds.usf").view_distance, 5e6);
  EXPECT_DOUBLE_EQ(s.for_path("ground/Grass.usf").view_distance, SceneNumbers{}.view_distance);
}

Finding world_position_finding() {
  Finding f;
  f.rule = "lwc-float-world-position";
  f.severity = Severity::warning;
  Fix t, d;
  t.strategy = "translated";
  d.strategy = "df";
  f.fixes = {d, t};
  return f;
}

std::string planned(SceneNumbers scene, Strategy strategy, bool* not_needed = nullptr) {
  std::vector<Finding> findings = {world_position_finding()};
  plan_fixes(findings, scene, strategy);
  if (not_needed) *not_needed = findings[0].not_needed;
  return findings[0].fixes.empty() ? "none" : findings[0].fixes[0].strategy;
}

TEST(Planner, LeavesOutWhatTheSceneDoesNotNeedAndPicksTheCheapestThatMeetsTheTarget) {
  bool not_needed = false;
  EXPECT_EQ(planned({1e5, 2e5, 0.0625}, Strategy::automatic, &not_needed), "none");  // 1 km arena
  EXPECT_TRUE(not_needed);
  EXPECT_EQ(planned({5e6, 1e6, 0.0625}, Strategy::automatic, &not_needed), "translated");  // 50 km, seen to 10 km
  EXPECT_FALSE(not_needed);
  EXPECT_EQ(planned({6.4e8, 1e8, 0.0625}, Strategy::automatic), "df");  // a planet seen from orbit
  EXPECT_EQ(planned({}, Strategy::automatic), "translated");             // the default: UE's world, 2^20 cm view
  EXPECT_EQ(planned({5e6, 1e6, 0.0625}, Strategy::df), "df");
  EXPECT_EQ(planned({6.4e8, 1e8, 0.0625}, Strategy::translated), "translated");
}

TEST(Planner, NotNeededFindingsBecomeNotesWithTheirNumbers) {
  std::vector<Finding> findings = {world_position_finding()};
  plan_fixes(findings, {1e5, 2e5, 0.0625}, Strategy::automatic);
  EXPECT_EQ(findings[0].severity, Severity::note);
  EXPECT_EQ(findings[0].decision, "not needed: float32 error at the world extent 1 km is 0.00391 cm, within the precision target 0.0625 cm");
}

}  // namespace
}  // namespace lwc

namespace lwc {
namespace {

TEST(Planner, NeverWritesATranslatedRewriteItKnowsFallsShort) {
  Finding f = world_position_finding();
  std::erase_if(f.fixes, [](const Fix& fix) { return fix.strategy == "df"; });  // no DoubleFloat rewrite here
  std::vector<Finding> findings = {f};
  plan_fixes(findings, {6.4e8, 1e8, 0.0625}, Strategy::automatic);  // a planet seen from orbit
  EXPECT_TRUE(findings[0].fixes.empty());
  ASSERT_FALSE(findings[0].withheld.empty());
  EXPECT_NE(findings[0].withheld.back().find("over the precision target 0.0625 cm, and no DoubleFloat rewrite exists here"),
            std::string::npos)
      << findings[0].withheld.back();
  EXPECT_NE(findings[0].decision.find("no automatic rewrite for this site"), std::string::npos) << findings[0].decision;
}

}  // namespace
}  // namespace lwc
