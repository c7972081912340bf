// Every rule's bad/good examples (rules/<id>.json) run here, so rule data and checks agree.
#include <gtest/gtest.h>

#include <filesystem>

#include "fix/apply.h"
#include "rules/rule.h"
#include "support.h"

namespace lwc {
namespace {

class RuleExamples : public ::testing::TestWithParam<std::string> {};

TEST_P(RuleExamples, BadExamplesFindExactlyTheExpectedSpotsAndGoodOnesNothing) {
  const RuleInfo* rule = find_rule(GetParam());
  ASSERT_NE(rule, nullptr);
  ASSERT_FALSE(rule->examples.empty());
  bool has_bad = false, has_good = false;
  for (const auto& ex : rule->examples) {
    Lang lang = *parse_lang(ex.at("language").get<std::string>());
    bool bad = ex.contains("bad");
    std::string code = ex.at(bad ? "bad" : "good").get<std::string>();
    std::vector<std::pair<int, int>> got;
    Source src("example", code);
    for (const Finding& f : test::lint_text(code, lang))
      if (f.rule == rule->id) {
        Position p = src.position(f.span.begin);
        got.emplace_back(p.line, p.column);
      }
    std::vector<std::pair<int, int>> want;
    if (bad)
      for (const auto& pos : ex.at("expect")) want.emplace_back(pos.at(0).get<int>(), pos.at(1).get<int>());
    EXPECT_EQ(got, want) << rule->id << (bad ? " bad" : " good") << " example:\n" << code;
    (bad ? has_bad : has_good) = true;
  }
  EXPECT_TRUE(has_bad) << rule->id << " needs a bad example";
  EXPECT_TRUE(has_good) << rule->id << " needs a good example";
}

// A bad example with "fixed" shows the rule's rewrite: `fix` (every rule on, as a user runs it)
// must produce exactly that text, and the fixed text must be clean of the rule.
TEST_P(RuleExamples, FixedExamplesAreWhatFixWritesAndLintClean) {
  const RuleInfo* rule = find_rule(GetParam());
  ASSERT_NE(rule, nullptr);
  size_t fixed_examples = 0;
  for (const auto& ex : rule->examples) {
    if (!ex.contains("fixed")) continue;
    ++fixed_examples;
    AnalyzeOptions options;
    options.lang = *parse_lang(ex.at("language").get<std::string>());
    bool unsafe = ex.value("unsafe", false);
    Source src("example", ex.at("bad").get<std::string>());
    FixOutcome out = fix_source(src, options, unsafe);
    EXPECT_EQ(out.text, ex.at("fixed").get<std::string>()) << rule->id;
    for (const Finding& f : out.remaining)
      EXPECT_NE(f.rule, rule->id) << "the fixed example still has: " << f.message;
    // And fixing it again changes nothing.
    EXPECT_EQ(fix_source(Source("example", out.text), options, unsafe).text, out.text) << rule->id;
  }
  if (!rule->fixes.empty()) EXPECT_GT(fixed_examples, 0u) << rule->id << " has fixes but no example of one";
}

std::vector<std::string> rule_ids() {
  std::vector<std::string> ids;
  for (const RuleInfo& r : all_rules())
    if (!r.host) ids.push_back(r.id);  // host rules' examples need Clang: tests/host
  return ids;
}

INSTANTIATE_TEST_SUITE_P(AllRules, RuleExamples, ::testing::ValuesIn(rule_ids()), [](const auto& info) {
  std::string name = info.param;
  for (char& c : name)
    if (c == '-') c = '_';
  return name;
});

TEST(RuleRegistry, EveryRuleHasACheckOrIsADriverRuleAndADocsPage) {
  for (const RuleInfo& r : all_rules()) {
    bool driver = r.id == kInputRule || r.id == kUnusedSuppressionRule;
    EXPECT_EQ(check_factories().count(r.id) == 1, !driver && !r.host) << r.id;  // host checks: tests/host
    std::string page = test::source_dir() + "/docs/rules/" + r.id + ".md";
    ASSERT_TRUE(std::filesystem::exists(page)) << page;
    std::string text = test::read(page);
    EXPECT_NE(text.find(r.id), std::string::npos) << page;
    EXPECT_NE(text.find(r.summary), std::string::npos) << page << " should state the rule's summary";
  }
  for (const auto& [id, factory] : check_factories()) EXPECT_NE(find_rule(id), nullptr) << id << " has no rule data";
  EXPECT_EQ(all_rules().size(), 21u);
}

}  // namespace
}  // namespace lwc
