// The command line's habits (issue 17 part 3): per-command help, one-line usage errors, standard
// input, --statistics, the rule pages and their links, colour variables, --config and --isolated.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <regex>

#include <nlohmann/json.hpp>

#include "core/uri.h"
#include "rules/rule.h"
#include "support.h"

namespace lwc {
namespace {

const char* kTwoFindings =
    "float3 F(float3 L)\n{\n\tfloat3 W = DFDemote(DFMultiply(L, Primitive.LocalToWorld));\n\treturn W - View.WorldCameraOrigin;\n}\n";
const char* kFusable = "float3 F(FDFVector3 P) { return DFDemote(DFAdd(P, P)); }\n";

// Standard error only (standard output dropped).
test::Run errors_of(const std::string& command) { return test::run(command + " 2>&1 >/dev/null"); }

TEST(CommandLine, EachCommandHasItsOwnHelp) {
  auto lint = test::run(test::binary() + " lint --help");
  EXPECT_EQ(lint.exit_code, 0);
  EXPECT_EQ(lint.out.rfind("usage: lwcport lint", 0), 0u) << lint.out;
  EXPECT_NE(lint.out.find("--stdin-filename"), std::string::npos);
  EXPECT_NE(lint.out.find("--statistics"), std::string::npos);
  EXPECT_EQ(lint.out.find("--diff"), std::string::npos) << "fix's options are not lint's";
  auto fix = test::run(test::binary() + " fix -h");
  EXPECT_NE(fix.out.find("--diff"), std::string::npos);
  EXPECT_EQ(test::run(test::binary() + " help fix").out, fix.out);
  EXPECT_EQ(test::run(test::binary() + " verify --help").out.find("--stdin-filename"), std::string::npos);
  auto overview = test::run(test::binary() + " --help");
  for (const char* command : {"lint", "fix", "verify", "parse", "rules", "rule", "lsp"})
    EXPECT_NE(overview.out.find(std::string("\n  ") + command + " "), std::string::npos) << command;
}

TEST(CommandLine, AMistakeIsOneLineThatPointsAtHelp) {
  struct Case {
    const char* args;
    const char* says;
  };
  for (const Case& c : {Case{"lint --bogus", "lwcport: error: unknown option --bogus (see `lwcport lint --help`)\n"},
                        Case{"lint --selct x", "lwcport: error: unknown option --selct (did you mean --select?) (see `lwcport lint --help`)\n"},
                        Case{"lint --diff", "lwcport: error: --diff is not an option of `lwcport lint` (see `lwcport lint --help`)\n"},
                        Case{"lint --jobs", "lwcport: error: --jobs needs a value (N) (see `lwcport lint --help`)\n"},
                        Case{"lint --statistics=yes", "lwcport: error: --statistics takes no value (see `lwcport lint --help`)\n"},
                        Case{"lnt", "lwcport: error: unknown command 'lnt' (did you mean lint?) (see `lwcport --help`)\n"},
                        Case{"rule", "lwcport: error: `lwcport rule` takes one rule id (see `lwcport rule --help`)\n"},
                        Case{"verify -", "lwcport: error: `lwcport verify` cannot read standard input; name the files (see `lwcport verify --help`)\n"}}) {
    auto r = errors_of(test::binary() + " " + c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args;
    EXPECT_EQ(r.out, c.says) << c.args;
  }
}

TEST(CommandLine, AShortOptionTakesItsValueAttachedOrSeparate) {
  std::string dir = test::scratch("short-options");
  test::write(dir + "/a.usf", kTwoFindings);
  auto attached = test::run("cd " + dir + " && " + test::binary() + " lint -j1 -oreport.json --format json a.usf");
  EXPECT_EQ(attached.exit_code, 1) << attached.out;
  EXPECT_EQ(nlohmann::json::parse(test::read(dir + "/report.json"))["findings"].size(), 2u);
  auto separate = test::run("cd " + dir + " && " + test::binary() + " lint -j 1 -o separate.json --format json a.usf");
  EXPECT_EQ(test::read(dir + "/separate.json"), test::read(dir + "/report.json"));
  // A flag that takes no value is not read as one with its value attached.
  EXPECT_EQ(errors_of(test::binary() + " lint -vx a.usf").out, "lwcport: error: unknown option -vx (see `lwcport lint --help`)\n");
}

TEST(CommandLine, StandardInputTakesItsNameLanguageConfigAndSuppressionsFromStdinFilename) {
  std::string dir = test::scratch("stdin");
  test::write(dir + "/a.usf", kTwoFindings);
  test::write(dir + "/sub/.lwcport.json", R"({"ignore": ["lwc-primary-view"]})");
  std::string in = " < " + dir + "/a.usf";
  auto named = test::run("cd " + dir + " && " + test::binary() + " lint - --stdin-filename sub/b.usf --format json" + in);
  auto j = nlohmann::json::parse(named.out);
  ASSERT_EQ(j["findings"].size(), 1u) << named.out;  // sub/'s config ignores lwc-primary-view
  EXPECT_EQ(j["findings"][0]["path"], "sub/b.usf");
  EXPECT_EQ(j["findings"][0]["rule"], "lwc-float-world-position");
  EXPECT_EQ(named.exit_code, 1);
  // The same text under a name with a suppression on its line: nothing left.
  std::string suppressed = kTwoFindings;
  suppressed.replace(suppressed.find("));") + 3, 0, " // lwcport-ignore: lwc-float-world-position");
  test::write(dir + "/s.usf", suppressed);
  auto quiet = test::run("cd " + dir + " && " + test::binary() + " lint - --stdin-filename sub/b.usf < s.usf");
  EXPECT_EQ(quiet.exit_code, 0) << quiet.out;
  // Without a name the language must be given.
  EXPECT_EQ(errors_of(test::binary() + " lint -" + in).exit_code, 2);
  auto by_lang = test::run(test::binary() + " lint - --lang hlsl --format json" + in);
  EXPECT_EQ(nlohmann::json::parse(by_lang.out)["findings"].size(), 2u);
  EXPECT_EQ(errors_of(test::binary() + " lint - a.usf" + in).exit_code, 2);
}

TEST(CommandLine, FixFromStandardInputWritesTheFixedTextToStandardOutputAndNothingElse) {
  std::string dir = test::scratch("stdin-fix");
  test::write(dir + "/n.usf", kFusable);
  auto r = test::run("cd " + dir + " && " + test::binary() + " fix - --stdin-filename n.usf < n.usf 2>/dev/null");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.out, "float3 F(FDFVector3 P) { return DFAddDemote(P, P); }\n");
  EXPECT_EQ(test::read(dir + "/n.usf"), kFusable);
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), {}), 1);  // no file written beside it
  // Unchanged text comes back byte for byte.
  test::write(dir + "/clean.usf", "float4 Main() : SV_Target { return 1; }\r\n");
  EXPECT_EQ(test::run("cd " + dir + " && " + test::binary() + " fix - --stdin-filename clean.usf < clean.usf 2>/dev/null").out,
            "float4 Main() : SV_Target { return 1; }\r\n");
}

TEST(CommandLine, StatisticsCountEachRulesFindingsAndFixes) {
  std::string dir = test::scratch("statistics");
  test::write(dir + "/a.usf", kTwoFindings);
  test::write(dir + "/b.usf", kFusable);
  auto findings = nlohmann::json::parse(test::run("cd " + dir + " && " + test::binary() + " lint --format json").out)["findings"];
  std::map<std::string, std::array<int, 3>> expected;  // findings, safe, unsafe
  for (const auto& f : findings) {
    auto& e = expected[f["rule"]];
    ++e[0];
    if (f.contains("fix")) ++e[f["fix"]["applicability"] == "safe" ? 1 : 2];
  }
  auto stats = nlohmann::json::parse(test::run("cd " + dir + " && " + test::binary() + " lint --statistics --format json").out);
  ASSERT_EQ(stats["statistics"].size(), expected.size()) << stats.dump();
  for (const auto& s : stats["statistics"]) {
    auto e = expected.at(s["rule"]);
    EXPECT_EQ(s["findings"], e[0]);
    EXPECT_EQ(s["safe_fixes"], e[1]);
    EXPECT_EQ(s["unsafe_fixes"], e[2]);
  }
  auto text = test::run("cd " + dir + " && " + test::binary() + " lint --statistics");
  EXPECT_EQ(text.exit_code, 1);  // the exit code still follows --fail-on
  EXPECT_NE(text.out.find("lwc-demote-fusion"), std::string::npos);
  EXPECT_EQ(text.out.find("^~"), std::string::npos) << "no finding is printed";
  EXPECT_EQ(errors_of(test::binary() + " lint --statistics --format sarif " + dir).exit_code, 2);
}

TEST(CommandLine, RulesHasAHeaderAFixColumnAndJsonAndRulePrintsThePage) {
  auto text = test::run(test::binary() + " rules");
  EXPECT_EQ(text.out.rfind("RULE ", 0), 0u) << text.out;
  EXPECT_NE(text.out.find(" FIX "), std::string::npos);
  auto json = nlohmann::json::parse(test::run(test::binary() + " rules --format json").out);
  ASSERT_EQ(json.size(), all_rules().size());
  for (const auto& r : json) {
    const RuleInfo* rule = find_rule(r["id"].get<std::string>());
    ASSERT_NE(rule, nullptr);
    EXPECT_EQ(r["fix"].is_null(), rule->fixes.empty()) << r.dump();
  }
  EXPECT_EQ(json[0]["id"], "lwc-demote-fusion");
  EXPECT_EQ(json[0]["fix"], "safe");
  for (const RuleInfo& r : all_rules())
    EXPECT_EQ(test::run(test::binary() + " rule " + r.id).out, test::read(test::source_dir() + "/docs/rules/" + r.id + ".md")) << r.id;
  EXPECT_EQ(errors_of(test::binary() + " rule lwc-no-such").exit_code, 2);
}

// A `{name}` left from a template: what a user reads must never show one.
bool has_placeholder(const std::string& text) { return std::regex_search(text, std::regex(R"(\{[a-z][a-z0-9_-]*\})")); }

TEST(CommandLine, HelpLinksLeadToPagesThatExistAndNoTextKeepsAPlaceholder) {
  std::string corpus = test::source_dir() + "/corpus";
  auto sarif = nlohmann::json::parse(test::run(test::binary() + " lint " + corpus + " --format sarif --fail-on none").out);
  const auto& driver = sarif["runs"][0]["tool"]["driver"];
  ASSERT_EQ(driver["rules"].size(), all_rules().size());
  EXPECT_TRUE(std::filesystem::is_directory(path_of_uri(driver["informationUri"].get<std::string>())));
  for (const auto& rule : driver["rules"]) {
    std::string uri = rule["helpUri"];
    EXPECT_EQ(uri.rfind("file://", 0), 0u) << uri;
    EXPECT_TRUE(std::filesystem::is_regular_file(path_of_uri(uri))) << uri;
    EXPECT_FALSE(has_placeholder(rule.dump())) << rule.dump();
  }
  size_t results = 0;
  for (const auto& r : sarif["runs"][0]["results"]) {
    ++results;
    EXPECT_FALSE(has_placeholder(r.dump())) << r.dump();
  }
  EXPECT_GT(results, 50u);
  // Every fix of every rule's examples (titles, reasons, notes, texts), unsafe ones included.
  auto json = nlohmann::json::parse(test::run(test::binary() + " lint " + corpus + " --format json --fail-on none").out);
  for (const auto& f : json["findings"]) EXPECT_FALSE(has_placeholder(f.dump())) << f.dump();
  for (const RuleInfo& r : all_rules())
    for (const auto& example : r.examples)
      if (example.contains("bad") && !r.host)  // host rules: tests/host
        for (const Finding& f : test::lint_text(example["bad"], parse_lang(example["language"].get<std::string>()).value(), r.id)) {
          EXPECT_FALSE(has_placeholder(f.message + f.hint)) << r.id << ": " << f.message;
          for (const Fix& fix : f.fixes) EXPECT_FALSE(has_placeholder(fix.title + fix.reason)) << r.id << ": " << fix.title;
        }
}

TEST(CommandLine, HelpUriBaseSendsEveryLinkToTheProjectsPages) {
  std::string dir = test::scratch("help-base");
  test::write(dir + "/.lwcport.json", R"({"help-uri-base": "https://docs.example.com/lwcport/rules"})");
  test::write(dir + "/a.usf", kTwoFindings);
  auto sarif = nlohmann::json::parse(test::run("cd " + dir + " && " + test::binary() + " lint --format sarif").out);
  const auto& driver = sarif["runs"][0]["tool"]["driver"];
  for (const auto& rule : driver["rules"])
    EXPECT_EQ(rule["helpUri"], "https://docs.example.com/lwcport/rules/" + rule["id"].get<std::string>() + ".md");
  test::write(dir + "/.lwcport.json", R"({"help-uri-base": ""})");
  auto bad = errors_of("cd " + dir + " && " + test::binary() + " lint");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.out.find("help-uri-base"), std::string::npos) << bad.out;
}

TEST(CommandLine, ColourFollowsForceColorClicolorForceAndNoColorUnderAuto) {
  std::string dir = test::scratch("colour");
  test::write(dir + "/a.usf", kTwoFindings);
  auto coloured = [&](const std::string& env, const std::string& flag = "") {
    return test::run("cd " + dir + " && env -u NO_COLOR -u FORCE_COLOR -u CLICOLOR_FORCE " + env + " " + test::binary() + " lint a.usf " + flag)
               .out.find("\x1b[") != std::string::npos;
  };
  EXPECT_FALSE(coloured(""));  // a pipe is not a terminal
  EXPECT_TRUE(coloured("FORCE_COLOR=1"));
  EXPECT_TRUE(coloured("CLICOLOR_FORCE=1"));
  EXPECT_FALSE(coloured("FORCE_COLOR=0"));
  EXPECT_FALSE(coloured("FORCE_COLOR=1", "--color never"));
  EXPECT_TRUE(coloured("NO_COLOR=1", "--color always"));
}

TEST(CommandLine, ConfigNamesOneFileForEveryFileAndIsolatedReadsNone) {
  std::string dir = test::scratch("config-flag");
  test::write(dir + "/a.usf", kTwoFindings);
  test::write(dir + "/.lwcport.json", R"({"ignore": ["lwc-primary-view"]})");
  test::write(dir + "/other/strict.json", R"({"ignore": ["lwc-float-world-position"]})");
  auto rules_of = [&](const std::string& flags) {
    std::set<std::string> rules;
    auto report = nlohmann::json::parse(test::run("cd " + dir + " && " + test::binary() + " lint a.usf --format json " + flags).out);
    for (const auto& f : report["findings"]) rules.insert(f["rule"].get<std::string>());
    return rules;
  };
  EXPECT_EQ(rules_of(""), std::set<std::string>{"lwc-float-world-position"});
  EXPECT_EQ(rules_of("--config other/strict.json"), std::set<std::string>{"lwc-primary-view"});
  EXPECT_EQ(rules_of("--isolated"), (std::set<std::string>{"lwc-float-world-position", "lwc-primary-view"}));
  EXPECT_EQ(errors_of(test::binary() + " lint --config " + dir + "/missing.json " + dir).exit_code, 2);
  EXPECT_EQ(errors_of(test::binary() + " lint --isolated --config x.json " + dir).exit_code, 2);
}

}  // namespace
}  // namespace lwc
