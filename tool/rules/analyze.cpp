#include "rules/analyze.h"

#include <fmt/format.h>

#include <mutex>

#include "rules/rule.h"
#include "shaderlib/shaderlib.h"

namespace lwc {

bool AnalyzeOptions::enabled(const std::string& rule) const {
  if (ignore.count(rule)) return false;
  return select.empty() || select.count(rule);
}

std::optional<Lang> language_for(const Source& source, const AnalyzeOptions& options) {
  return options.lang ? options.lang : lang_from_path(source.path());
}

const WorldData& world_data(Lang lang, const nlohmann::json& extra_sources) {
  static std::mutex mutex;
  static std::map<std::pair<Lang, std::string>, std::unique_ptr<WorldData>> cache;
  std::lock_guard lock(mutex);
  auto& slot = cache[{lang, extra_sources.dump()}];
  if (!slot) slot = std::make_unique<WorldData>(WorldData::load(world_space_data(), extra_sources, lang));
  return *slot;
}

std::vector<std::string> include_paths(std::string_view text) {
  std::vector<std::string> out;
  size_t i = 0;
  while (i < text.size()) {
    size_t end = text.find('\n', i);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(i, end - i);
    i = end + 1;
    size_t k = line.find_first_not_of(" \t");
    if (k == std::string_view::npos || line[k] != '#') continue;
    k = line.find_first_not_of(" \t", k + 1);
    if (k == std::string_view::npos || line.substr(k, 7) != "include") continue;
    size_t open = line.find_first_of("\"<", k + 7);
    if (open == std::string_view::npos) continue;
    size_t close = line.find(line[open] == '"' ? '"' : '>', open + 1);
    if (close != std::string_view::npos) out.emplace_back(line.substr(open + 1, close - open - 1));
  }
  return out;
}

Finding input_finding(Severity severity, uint32_t offset, std::string message, std::string hint) {
  Finding f;
  f.rule = kInputRule;
  f.severity = severity;
  f.span = {offset, offset};
  f.message = std::move(message);
  f.hint = std::move(hint);
  return f;
}

Finding too_large_finding(size_t bytes, size_t limit) {
  return input_finding(Severity::error, 0, fmt::format("file is {} bytes, over the {}-byte limit; skipped", bytes, limit),
                       "raise \"max-file-bytes\" in .lwcport.json if this file really is a shader");
}

namespace {

// One `lwcport-ignore` comment and the rule ids it names.
struct Suppression {
  Span span;       // the whole comment
  int line;        // the line it covers
  bool whole_file;
  std::string rule;
  Span rule_span;  // the rule id inside the comment
  int ids = 1;     // how many ids the comment names
  bool alone = false;  // the comment is alone on its line
  bool used = false;
};

std::vector<Suppression> find_suppressions(const SyntaxTree& tree) {
  std::vector<Suppression> out;
  const Source& src = *tree.source;
  for (int id = 0; id < static_cast<int>(tree.nodes.size()); ++id) {
    if (!tree.is(id, "comment")) continue;
    std::string_view text = tree.text(id);
    for (auto [marker, whole_file] : {std::pair{std::string_view("lwcport-ignore-file:"), true},
                                      std::pair{std::string_view("lwcport-ignore:"), false}}) {
      size_t at = text.find(marker);
      if (at == std::string_view::npos) continue;
      std::string_view rest = text.substr(at + marker.size());
      size_t end = rest.find("*/");
      if (end != std::string_view::npos) rest = rest.substr(0, end);
      Position pos = src.position(tree.at(id).begin);
      // A comment alone on its line covers the next line; a trailing one covers its own.
      std::string_view before = src.line_text(pos.line).substr(0, src.offset(pos) - src.offset({pos.line, 1}));
      bool alone = before.find_first_not_of(" \t") == std::string_view::npos;
      size_t i = 0, first = out.size();
      uint32_t rest_begin = tree.at(id).begin + static_cast<uint32_t>(at + marker.size());
      while (i < rest.size()) {
        while (i < rest.size() && (rest[i] == ' ' || rest[i] == ',' || rest[i] == '\t')) ++i;
        size_t b = i;
        while (i < rest.size() && (std::isalnum(static_cast<unsigned char>(rest[i])) || rest[i] == '-' || rest[i] == '_')) ++i;
        if (i == b) break;
        Suppression sup{tree.span(id), alone ? pos.line + 1 : pos.line, whole_file, std::string(rest.substr(b, i - b)),
                        {rest_begin + static_cast<uint32_t>(b), rest_begin + static_cast<uint32_t>(i)}};
        sup.alone = alone;
        out.push_back(sup);
      }
      for (size_t k = first; k < out.size(); ++k) out[k].ids = static_cast<int>(out.size() - first);
      break;
    }
  }
  return out;
}

// One instance of each check, built once; checks are immutable, so threads share them.
const std::vector<std::pair<const RuleInfo*, std::unique_ptr<Check>>>& checks() {
  static const auto all = [] {
    std::vector<std::pair<const RuleInfo*, std::unique_ptr<Check>>> out;
    for (const RuleInfo& rule : all_rules()) {
      auto factory = check_factories().find(rule.id);
      if (factory != check_factories().end()) out.emplace_back(&rule, factory->second(rule));  // driver rules have none
    }
    return out;
  }();
  return all;
}

// The fix for a stale suppression: the id and its separator when the comment names others, else
// the whole comment (and its line, when the comment is alone on it).
Fix remove_suppression(const RuleInfo& rule, const Suppression& s, const SyntaxTree& tree) {
  const std::string& text = tree.source->text();
  Span cut = s.rule_span;
  if (s.ids > 1) {
    // Take the separator after the id, or, for the last id, the one before it.
    uint32_t e = cut.end;
    while (e < s.span.end && (text[e] == ',' || text[e] == ' ' || text[e] == '\t')) ++e;
    bool last = e >= s.span.end || text.compare(e, 2, "*/") == 0 || !(std::isalnum(static_cast<unsigned char>(text[e])) || text[e] == '-');
    if (!last) cut.end = e;
    else
      while (cut.begin > s.span.begin && (text[cut.begin - 1] == ',' || text[cut.begin - 1] == ' ' || text[cut.begin - 1] == '\t')) --cut.begin;
    return make_fix(rule, "remove", {{"what", "`" + s.rule + "` from the comment"}}, {{cut, ""}});
  }
  cut = s.span;
  // Trailing blanks before the comment go with it; a comment alone on its line takes the line.
  while (cut.begin > 0 && (text[cut.begin - 1] == ' ' || text[cut.begin - 1] == '\t')) --cut.begin;
  if (s.alone) {
    if (cut.end < text.size() && text[cut.end] == '\r') ++cut.end;
    if (cut.end < text.size() && text[cut.end] == '\n') ++cut.end;
  }
  return make_fix(rule, "remove", {{"what", "the comment"}}, {{cut, ""}});
}

void apply_suppressions(const SyntaxTree& tree, const AnalyzeOptions& options, std::vector<Finding>& findings) {
  std::vector<Suppression> sups = find_suppressions(tree);
  if (sups.empty()) return;
  const Source& src = *tree.source;
  std::vector<Finding> kept;
  for (Finding& f : findings) {
    int line = src.position(f.span.begin).line;
    bool suppressed = false;
    for (Suppression& s : sups) {
      if (s.rule == f.rule && (s.whole_file || s.line == line)) suppressed = s.used = true;
    }
    if (!suppressed) kept.push_back(std::move(f));
  }
  findings = std::move(kept);
  const RuleInfo* unused = find_rule(kUnusedSuppressionRule);
  if (!unused || !options.enabled(unused->id)) return;
  for (const Suppression& s : sups) {
    if (s.used) continue;
    const RuleInfo* target = find_rule(s.rule);
    // A suppression of a rule that did not run this time is not known to be unused.
    if (target && (!options.enabled(target->id) || !target->applies_to(tree.lang))) continue;
    std::string why = target ? fmt::format("no `{}` finding here to suppress", s.rule)
                             : fmt::format("`{}` is not a lwcport rule", s.rule);
    Finding f = make_finding(*unused, s.span, {{"rule", s.rule}, {"why", why}});
    f.fixes.push_back(remove_suppression(*unused, s, tree));
    findings.push_back(std::move(f));
  }
}

}  // namespace

std::vector<Finding> analyze(const Source& source, const AnalyzeOptions& options) {
  // The library lwcport writes beside fixed files is its own tested code, not the user's.
  if (is_written_library(source.text())) return {};
  std::vector<Finding> findings;
  auto finish = [&]() {
    std::vector<Finding> kept;
    for (Finding& f : findings) {
      if (!options.enabled(f.rule)) continue;
      if (auto it = options.severity.find(f.rule); it != options.severity.end()) f.severity = it->second;
      kept.push_back(std::move(f));
    }
    sort_findings(kept);
    plan_fixes(kept, options.scene, options.strategy);
    return kept;
  };
  std::optional<Lang> lang = language_for(source, options);
  if (!lang) {
    findings.push_back(input_finding(Severity::error, 0, "not a shader file lwcport knows (by its extension)",
                                     "pass --lang hlsl or --lang glsl to choose the language"));
    return finish();
  }
  const std::string& text = source.text();
  if (text.size() > options.max_bytes) {
    findings.push_back(too_large_finding(text.size(), options.max_bytes));
    return finish();
  }
  if (auto nul = find_binary_marker(text)) {
    findings.push_back(input_finding(Severity::error, *nul, "binary file (a NUL byte); skipped",
                                     "exclude it in .lwcport.json (\"exclude\") if it is not a shader"));
    return finish();
  }
  if (auto bad = find_invalid_utf8(text)) {
    findings.push_back(input_finding(Severity::warning, *bad,
                                     fmt::format("invalid UTF-8 (byte 0x{:02X}); analysed as bytes, columns on this line may be off",
                                                 static_cast<unsigned char>(text[*bad])),
                                     "save the file as UTF-8"));
  }
  if (text.find_first_not_of(" \t\r\n\xEF\xBB\xBF") == std::string::npos) {
    findings.push_back(input_finding(Severity::note, 0, "empty file; nothing to analyse", ""));
    return finish();
  }
  SyntaxTree tree = parse(source, *lang);
  if (tree.unterminated_comment) {
    findings.push_back(input_finding(Severity::error, *tree.unterminated_comment,
                                     "unterminated block comment: everything after it is a comment",
                                     "close the comment with */ (no fixes are offered in this file until then)"));
  } else if (tree.error_count > 0) {
    findings.push_back(input_finding(Severity::note, tree.first_error,
                                     fmt::format("{} syntax error(s) the parser could not place; findings next to them may be missed",
                                                 tree.error_count),
                                     "lwcport does not expand macros: a macro used as syntax can cause this; no fixes are offered in this file until it parses"));
  }
  WorldModel world(tree, world_data(*lang, options.world_sources), options.includes);
  for (const auto& [rule, check] : checks()) {
    if (rule->applies_to(*lang) && options.enabled(rule->id)) check->run(CheckContext{tree, world, *rule, findings});
  }
  // Where the parser lost its way, a rewrite may land in the wrong place: none is offered.
  if (tree.unterminated_comment || tree.error_count > 0) {
    for (Finding& f : findings) f.fixes.clear();
  }
  if (!world.too_deep().empty()) {
    findings.push_back(input_finding(Severity::note, tree.at(world.too_deep().front()).begin,
                                     fmt::format("expression nested too deeply to analyse ({} place(s)); it was skipped",
                                                 world.too_deep().size()),
                                     "split the expression"));
  }
  apply_suppressions(tree, options, findings);
  return finish();
}

}  // namespace lwc
