#pragma once
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/finding.h"
#include "lang/syntax.h"
#include "world/model.h"

namespace lwc {

// One rule as described by its rules/<id>.json file.
struct RuleInfo {
  std::string id;
  std::string name;
  Severity severity = Severity::warning;
  std::vector<Lang> languages;  // the shader languages it checks; none for a host rule
  bool host = false;            // checks C++ host code ("c++"; lwcport host, tool/host)
  std::string summary;
  std::string message;    // a template: {name} placeholders filled by the check
  std::string hint;       // a template too
  std::string rationale;
  // The migration report's estimate: minutes a rendering engineer needs to fix one site by hand,
  // and what that work is (the basis the report states).
  double effort_minutes = 0;
  std::string effort_by_hand;
  nlohmann::json data;
  nlohmann::json examples;
  // The rule's rewrites by kind: {"title", "applicability", "reason"} templates.
  std::map<std::string, nlohmann::json, std::less<>> fixes;
  // The hazard depends on the scene's size: the planner may find it not needed (docs/scenes.md).
  bool scene_dependent = false;

  bool applies_to(Lang lang) const;
};

// Every rule, sorted by id. Throws std::runtime_error on malformed rule data (a build defect).
const std::vector<RuleInfo>& all_rules();
// The page that documents a rule (SARIF's helpUri, the editor's code description): `base` then
// `<id>.md` when the project sets "help-uri-base", else the page installed with the tool as a
// file: URI; "" when there is none (no link is better than a dead one).
std::string rule_doc_url(std::string_view id, std::string_view base = "");
// The documentation installed with the tool, as a file: URI of its folder; "" when not found.
std::string docs_url();
// A rule's page, docs/rules/<id>.md as embedded at build time; empty for an unknown id.
std::string_view rule_page(std::string_view id);
const RuleInfo* find_rule(std::string_view id);
// The "world-space" object of rules/world-space.json.
const nlohmann::json& world_space_data();
// The "host-world" object of rules/host-world.json: what the host rules know of C++ code.
const nlohmann::json& host_world_data();
// "hlsl, glsl" or "c++": the languages a rule checks, for listings.
std::vector<std::string> language_names(const RuleInfo& rule);

using Vars = std::map<std::string, std::string>;
// Replaces each {key} in a template with its value; unknown keys stay as written.
// Longest value a message quotes, and the most text one rewrite may write (bytes): what lwcport
// prints for a finding never grows with the length of its line.
constexpr size_t kMaxQuoted = 400;
constexpr size_t kMaxFixText = 4096;
std::string expand(std::string_view tmpl, const Vars& vars);
// A value quoted as expand() quotes it: at most kMaxQuoted bytes, the start and the end of a longer
// one around an ellipsis. For code a check quotes in a text of its own (why a rewrite is withheld).
std::string shortened(std::string_view value);

// A finding of a rule at a span, its message and hint filled from vars.
Finding make_finding(const RuleInfo& rule, Span span, const Vars& vars);
// A fix of one of the rule's kinds (rules/<id>.json "fixes"), its texts filled from vars.
Fix make_fix(const RuleInfo& rule, std::string_view kind, const Vars& vars, std::vector<Edit> edits);

struct CheckContext {
  const SyntaxTree& tree;
  const WorldModel& world;
  const RuleInfo& rule;
  std::vector<Finding>& out;
  std::optional<UnrealTarget> unreal;  // Unreal code: the engine era it builds against

  // Reports the rule at a span, its message and hint filled from vars.
  Finding& report(Span span, const Vars& vars) const;
  // Adds a candidate rewrite of the rule's kind (rules/<id>.json "fixes") to a finding; null
  // when its edits would copy more than kMaxFixText bytes (a pathological expression: the
  // finding says so instead, and output stays linear in the input).
  Fix* fix(Finding& finding, std::string_view kind, const Vars& vars, std::vector<Edit> edits) const;
  // True when a rewrite of that kind writing `bytes` bytes is past kMaxFixText; the finding then
  // says why it has none. fix() asks; a check asks first where building the text costs as much.
  bool too_long(Finding& finding, std::string_view kind, size_t bytes) const;
};

// A check: the code half of a rule (its data half is rules/<id>.json).
class Check {
 public:
  virtual ~Check() = default;
  virtual void run(const CheckContext& ctx) const = 0;
};

// Check factories by rule id (checks.cpp registers each one).
using CheckFactory = std::unique_ptr<Check> (*)(const RuleInfo&);
const std::map<std::string_view, CheckFactory>& check_factories();

// Ids of the rules that are not checks over the tree but come from the driver.
inline constexpr std::string_view kInputRule = "lwc-input";
inline constexpr std::string_view kUnusedSuppressionRule = "lwc-unused-suppression";

}  // namespace lwc
