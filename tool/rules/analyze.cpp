#include "rules/analyze.h"

#include <fmt/format.h>

#include <algorithm>
#include <functional>
#include <mutex>
#include <set>
#include <tuple>
#include <unordered_map>

#include "lang/embedded.h"
#include "lang/lexer.h"
#include "lang/macros.h"
#include "lang/tokens.h"
#include "rules/rule.h"
#include "shaderlib/shaderlib.h"
#include "world/provenance.h"

namespace lwc {

bool AnalyzeOptions::enabled(const std::string& rule) const {
  if (ignore.count(rule)) return false;
  return select.empty() || select.count(rule);
}

std::optional<FileFormat> format_for(const Source& source, const AnalyzeOptions& options) {
  if (options.lang) return FileFormat{*options.lang, Container::shader};
  return (options.formats ? *options.formats : FormatTable::defaults()).for_path(source.path(), source.text());
}

ShaderCode shader_code(const Source& source, const AnalyzeOptions& options) {
  ShaderCode code;
  auto format = format_for(source, options);
  if (!format) return code;
  code.lang = format->lang;
  if (format->container == Container::javascript) {
    code.script = true;
    std::vector<Span> substitutions;
    code.literals = glsl_template_literals(source.path(), source.text(), substitutions);
    for (Span literal : code.literals) {
      std::vector<Span> inside;
      for (Span s : substitutions)
        if (literal.begin <= s.begin && s.end <= literal.end) inside.push_back(s);
      code.views.emplace_back(source.path(), glsl_view(source.text(), {literal}, inside));
    }
  }
  return code;
}

bool holds_shader_code(const Source& source, const AnalyzeOptions& options) {
  auto format = format_for(source, options);
  return !format || format->container != Container::javascript || !glsl_template_literals(source.path(), source.text()).empty();
}

std::optional<Lang> language_for(const Source& source, const AnalyzeOptions& options) {
  auto format = format_for(source, options);
  return format ? std::optional<Lang>(format->lang) : std::nullopt;
}

const WorldData& world_data(Lang lang, const nlohmann::json& extra_sources, bool host_rebases) {
  static std::mutex mutex;
  static std::map<std::tuple<Lang, std::string, bool>, std::unique_ptr<WorldData>> cache;
  std::lock_guard lock(mutex);
  auto& slot = cache[{lang, extra_sources.dump(), host_rebases}];
  if (!slot) slot = std::make_unique<WorldData>(WorldData::load(world_space_data(), extra_sources, lang, host_rebases));
  return *slot;
}

std::string file_era(const Source& source, const AnalyzeOptions& options) {
  std::optional<FileFormat> format = format_for(source, options);
  if (!format) return "";
  if (format->lang == Lang::glsl) return "GLSL";
  if (!is_unreal_source(source.path(), source.text())) return "HLSL";
  return std::string(era_name(infer_unreal_era(source.text())));
}

ModelContext model_context(const Source& source, Lang lang, const FileSummary* includes, bool engine_file) {
  std::optional<UnrealEra> era;
  if (lang == Lang::hlsl && is_unreal_source(source.path(), source.text())) era = infer_unreal_era(source.text());
  ModelContext context{includes, !era || *era == UnrealEra::ue4, !era, era};
  context.engine_file = engine_file;
  return context;
}

MacroTable macro_table(Lang lang, const MacroTable* included, const MacroTable& project) {
  MacroTable table = known_macros(lang);
  if (included)
    for (const auto& [name, use] : *included) table[name] = use;
  for (const auto& [name, use] : project) table[name] = use;
  return table;
}

FileSummary include_summary(const Source& source, const SyntaxTree& tree, const nlohmann::json& world_sources, bool host_rebases,
                            const ModelContext& context) {
  FileSummary summary;
  if (!tree.timed_out) summary = WorldModel(tree, world_data(tree.lang, world_sources, host_rebases), context).summary();
  learn_macros(source.text(), known_macros(tree.lang), summary.macros);
  return summary;
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

// One rule id of a `lwcport-ignore` comment, or the whole comment when it names none (a bare
// `lwcport-ignore`: every rule).
struct Suppression {
  Span span;       // the whole comment
  Span marker;     // from `lwcport-ignore` to the end of its last id
  int line;        // the line it covers
  bool whole_file;
  std::string rule;  // "" for every rule
  Span rule_span;  // the rule id inside the comment
  int ids = 1;     // how many ids the comment names (0 when bare)
  bool alone = false;  // the comment is alone on its line
  bool used = false;
};

}  // namespace

bool suppression_id_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_'; }

std::vector<Span> suppression_ids(std::string_view text, size_t from) {
  std::vector<Span> out;
  for (size_t i = from; i < text.size();) {
    while (i < text.size() && (text[i] == ' ' || text[i] == ',' || text[i] == '\t')) ++i;
    size_t b = i;
    while (i < text.size() && suppression_id_char(text[i])) ++i;
    if (i == b) break;
    out.push_back({static_cast<uint32_t>(b), static_cast<uint32_t>(i)});
  }
  return out;
}

namespace {

// `lwcport-ignore[-file|-next-line][: ID[, ID...]]` in a comment. A comment alone on its line
// covers the next line, a trailing one its own; `-next-line` always the next; `-file` the file.
std::vector<Suppression> find_suppressions(const Source& src, const std::vector<Span>& comments) {
  std::vector<Suppression> out;
  for (Span comment : comments) {
    std::string_view text = src.slice(comment);
    size_t at = text.find(kSuppressionMarker);
    if (at == std::string_view::npos || (at > 0 && suppression_id_char(text[at - 1]))) continue;
    size_t after = at + kSuppressionMarker.size();
    bool whole_file = false, next_line = false;
    if (text.substr(after).starts_with("-file")) whole_file = true, after += 5;
    else if (text.substr(after).starts_with("-next-line")) next_line = true, after += 10;
    if (after < text.size() && suppression_id_char(text[after])) continue;  // `lwcport-ignored`, `lwcport-ignore-all`: not ours
    std::string_view rest;
    if (after < text.size() && text[after] == ':') rest = text.substr(++after);
    if (size_t end = rest.find("*/"); end != std::string_view::npos) rest = rest.substr(0, end);
    Position pos = src.position(comment.begin);
    std::string_view before = src.line_text(pos.line).substr(0, src.offset(pos) - src.offset({pos.line, 1}));
    bool alone = before.find_first_not_of(" \t") == std::string_view::npos;
    int line = whole_file ? 0 : alone || next_line ? pos.line + 1 : pos.line;
    uint32_t begin = comment.begin;
    Span marker{begin + static_cast<uint32_t>(at), begin + static_cast<uint32_t>(after)};
    size_t first = out.size();
    for (Span ids : suppression_ids(rest, 0)) {
      Span rule_span{begin + static_cast<uint32_t>(after) + ids.begin, begin + static_cast<uint32_t>(after) + ids.end};
      out.push_back({comment, {}, line, whole_file, std::string(rest.substr(ids.begin, ids.end - ids.begin)), rule_span});
      marker.end = rule_span.end;
    }
    if (out.size() == first) out.push_back({comment, {}, line, whole_file, "", marker, 0});
    for (size_t k = first; k < out.size(); ++k) {
      out[k].marker = marker;
      out[k].alone = alone;
      if (out[k].ids) out[k].ids = static_cast<int>(out.size() - first);
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

// The fix for a stale suppression: the id and its separator when the comment names others; else
// the marker and its ids when the comment says something more, else the whole comment (and its
// line, when the comment is alone on it). No other word of the comment is lost.
Fix remove_suppression(const RuleInfo& rule, const Suppression& s, const std::string& text) {
  auto blank = [&](uint32_t i) { return text[i] == ' ' || text[i] == '\t'; };
  Span cut = s.rule_span;
  if (s.ids > 1) {
    // Take the separator after the id, or, for the last id, the one before it.
    uint32_t e = cut.end;
    while (e < s.span.end && (text[e] == ',' || blank(e))) ++e;
    bool last = e >= s.span.end || text.compare(e, 2, "*/") == 0 || !suppression_id_char(text[e]);
    if (!last) cut.end = e;
    else
      while (cut.begin > s.span.begin && (text[cut.begin - 1] == ',' || blank(cut.begin - 1))) --cut.begin;
    return make_fix(rule, "remove", {{"what", "`" + s.rule + "` from the comment"}}, {{cut, ""}});
  }
  // The comment's words other than the marker: its delimiters and blanks aside.
  std::string_view comment(text.data() + s.span.begin, s.span.end - s.span.begin);
  std::string others(comment.substr(0, s.marker.begin - s.span.begin));
  others += comment.substr(s.marker.end - s.span.begin);
  bool only_marker = others.find_first_not_of(" \t\r\n/*:") == std::string::npos;
  if (!only_marker) {
    cut = s.marker;
    while (cut.begin > s.span.begin + 2 && blank(cut.begin - 1)) --cut.begin;
    return make_fix(rule, "remove", {{"what", "the suppression from the comment"}}, {{cut, ""}});
  }
  cut = s.span;
  // Trailing blanks before the comment go with it; a comment alone on its line takes the line.
  while (cut.begin > 0 && blank(cut.begin - 1)) --cut.begin;
  if (s.alone) {
    if (cut.end < text.size() && text[cut.end] == '\r') ++cut.end;
    if (cut.end < text.size() && text[cut.end] == '\n') ++cut.end;
  }
  return make_fix(rule, "remove", {{"what", "the comment"}}, {{cut, ""}});
}

// Drops the findings a suppression covers, marking the suppressions used.
void suppress(std::vector<Suppression>& sups, const Source& src, std::vector<Finding>& findings) {
  if (sups.empty()) return;
  // A finding meets the suppressions of its line, and the whole-file ones by rule ("": every
  // rule), each of which is marked used once the run is over.
  std::unordered_map<int, std::vector<Suppression*>> at_line;
  std::map<std::string, std::pair<std::vector<Suppression*>, bool>, std::less<>> whole_file;  // rule -> them, used
  for (Suppression& s : sups) {
    if (s.whole_file) whole_file[s.rule].first.push_back(&s);
    else at_line[s.line].push_back(&s);
  }
  std::vector<Finding> kept;
  for (Finding& f : findings) {
    bool suppressed = false;
    for (std::string_view rule : {std::string_view(), std::string_view(f.rule)})
      if (auto it = whole_file.find(rule); it != whole_file.end()) suppressed = it->second.second = true;
    if (auto it = at_line.find(src.position(f.span.begin).line); it != at_line.end())
      for (Suppression* s : it->second)
        if (s->rule.empty() || s->rule == f.rule) suppressed = s->used = true;
    if (!suppressed) kept.push_back(std::move(f));
  }
  for (auto& [rule, them] : whole_file)
    if (them.second)
      for (Suppression* s : them.first) s->used = true;
  findings = std::move(kept);
}

// `ran`: whether a rule ran on this file (a suppression of a rule that did not is not known to be unused).
void report_unused(const std::vector<Suppression>& sups, const Source& src, const std::function<bool(const RuleInfo&)>& ran,
                   std::vector<Finding>& findings) {
  const RuleInfo* unused = find_rule(kUnusedSuppressionRule);
  if (!unused || !ran(*unused)) return;
  for (const Suppression& s : sups) {
    if (s.used) continue;
    const RuleInfo* target = find_rule(s.rule);
    if (target && !ran(*target)) continue;
    std::string why = s.rule.empty() ? "no finding here to suppress"
                      : target       ? fmt::format("no `{}` finding here to suppress", s.rule)
                                     : fmt::format("`{}` is not a lwcport rule", s.rule);
    std::string what = s.rule.empty() ? "every rule" : "`" + s.rule + "`";
    std::string removal = s.rule.empty() ? "the suppression" : what + " from the comment";
    Finding f = make_finding(*unused, s.span, {{"suppressed", what}, {"removal", removal}, {"why", why}});
    f.fixes.push_back(remove_suppression(*unused, s, src.text()));
    findings.push_back(std::move(f));
  }
}

bool overlaps(Span a, Span b) { return a.begin < b.end && b.begin < a.end; }
bool inside(Span inner, Span outer) { return outer.begin <= inner.begin && inner.end <= outer.end; }

// A finding with no rewrite of its own whose code another finding's translated-world port
// rewrites (a marker on the matrix it takes whole, a local downstream of the value it moves, the
// function returning it) gets that port too: applying either applies both.
void share_ports(const Source& source, std::vector<Finding>& findings) {
  for (Finding& f : findings) {
    if (!f.fixes.empty() || f.rule == "lwc-input") continue;
    for (const Finding& by : findings) {
      if (by.fixes.empty() || by.fixes.front().strategy != "translated") continue;
      const std::vector<Edit>& edits = by.fixes.front().edits;
      if (!std::any_of(edits.begin(), edits.end(), [&](const Edit& e) { return inside(f.span, e.span); })) continue;
      Fix shared = by.fixes.front();
      shared.reason += fmt::format("; it is the rewrite of line {}, which moves this code too", source.position(by.span.begin).line);
      f.fixes.push_back(std::move(shared));
      f.withheld.clear();
      break;
    }
  }
}

// One finding among the variants of a file: its rule and place.
using FindingKey = std::tuple<std::string, uint32_t, uint32_t>;
FindingKey key_of(const Finding& f) { return {f.rule, f.span.begin, f.span.end}; }

// What a syntax error leaves untrustworthy: a finding inside a part the parser could not read
// is dropped, and no rewrite is offered in a top-level declaration that holds an error. An error
// at one of `own_errors` (where only some variants of the file fail, so the arm of a preprocessor
// group they keep is at fault, such as a dead `#else` the engine never compiles) withholds
// nothing here: VariantMerge lets the variants that read the code cleanly decide. Returned: the
// findings with such an error in their declaration.
std::set<FindingKey> drop_what_errors_touch(const SyntaxTree& tree, std::vector<Finding>& findings, const std::set<uint32_t>& own_errors) {
  std::vector<Span> errors, broken, own_broken;
  for (int id = 0; tree.error_count > 0 && id < static_cast<int>(tree.nodes.size()); ++id) {
    const Node& n = tree.at(id);
    if (!n.error) continue;
    if (std::string_view(n.type) == "ERROR") errors.push_back(tree.span(id));
    int top = id;
    while (top >= 0 && tree.at(top).parent > 0) top = tree.at(top).parent;
    (own_errors.count(n.begin) ? own_broken : broken).push_back(tree.span(top >= 0 ? top : id));
  }
  auto in_any = [](const std::vector<Span>& spans, Span s) {
    return std::any_of(spans.begin(), spans.end(), [&](Span b) { return overlaps(s, b) || inside(s, b); });
  };
  std::vector<Finding> kept;
  std::set<FindingKey> unread;
  for (Finding& f : findings) {
    if (std::any_of(errors.begin(), errors.end(), [&](Span e) { return inside(f.span, e); })) continue;
    if (!f.fixes.empty() && in_any(broken, f.span)) {
      f.fixes.clear();
      f.withheld.push_back("the declaration around it has a syntax error (see `lwcport parse --verbose`), so a rewrite "
                           "could land in the wrong place");
    }
    if (in_any(own_broken, f.span)) unread.insert(key_of(f));
    kept.push_back(std::move(f));
  }
  findings = std::move(kept);
  return unread;
}

// The byte offsets of a tree's syntax errors.
std::set<uint32_t> error_offsets(const SyntaxTree& tree) {
  std::set<uint32_t> at;
  if (tree.error_count == 0) return at;
  for (const Node& n : tree.nodes)
    if (n.error) at.insert(n.begin);
  return at;
}

// The LWC libraries' own definitions are not migration debt: only the rules about error-free
// transformations look inside them.
void drop_library_findings(const std::vector<Span>& library, const WorldData& data, std::vector<Finding>& findings) {
  if (library.empty()) return;
  std::erase_if(findings, [&](const Finding& f) {
    if (std::find(data.library.still_checked.begin(), data.library.still_checked.end(), f.rule) != data.library.still_checked.end())
      return false;
    return std::any_of(library.begin(), library.end(), [&](Span s) { return inside(f.span, s); });
  });
}

// Code in an arm written for UE4 in a file that builds against UE5 (`#if UE4_COMPAT`) is that
// engine's code path: as for library definitions, only the error-free-transformation rules
// look inside it.
void drop_older_engine_arms(std::string_view text, const UnrealTarget& unreal, const WorldData& data, std::vector<Finding>& findings) {
  std::vector<Span> older;
  for (const EraArm& arm : era_guarded_arms(text))
    if (arm.era == UnrealEra::ue4 && unreal.era != UnrealEra::ue4) older.push_back({arm.begin, arm.end});
  drop_library_findings(older, data, findings);
}

// The variants of a file (lang/conditionals.h) report the same finding once. A rewrite is kept
// only where every variant proposes exactly it and it touches no resolved preprocessor group:
// a rewrite seen through one arm could miss what another arm holds. A variant that could not
// parse its own arm still votes, but a variant that read everything cleanly must agree, and the
// rewrite may not take away a name that variant's own arms spell (the parser may not have seen it).
class VariantMerge {
 public:
  VariantMerge(std::string_view text, std::vector<Span> regions) : text_(text), regions_(std::move(regions)) {}

  // `unread`: the findings in whose declaration the variant met a syntax error the others did not;
  // `arms`: the arms the variant keeps.
  void add(std::vector<Finding> found, const std::set<FindingKey>& unread, const std::vector<Span>& arms) {
    ++variants_;
    std::set<std::string, std::less<>> arm_names;
    if (!unread.empty())
      for (Span a : arms) arm_names.merge(identifiers(text_.substr(a.begin, a.end - a.begin)));
    for (Finding& f : found) {
      FindingKey key = key_of(f);
      bool clean = !unread.count(key);
      auto it = index_.find(key);
      if (it == index_.end()) {
        index_.emplace(key, merged_.size());
        votes_.push_back(f.fixes.empty() ? 0 : 1);
        clean_votes_.push_back(!f.fixes.empty() && clean ? 1 : 0);
        unread_names_.emplace_back(clean ? std::set<std::string, std::less<>>() : arm_names);
        merged_.push_back(std::move(f));
        continue;
      }
      if (!clean) unread_names_[it->second].insert(arm_names.begin(), arm_names.end());
      Finding& m = merged_[it->second];
      bool same = !f.fixes.empty() && !m.fixes.empty() && f.fixes.front().edits == m.fixes.front().edits;
      if (same) ++votes_[it->second];
      if (same && clean) ++clean_votes_[it->second];
    }
  }

  std::vector<Finding> take() {
    for (size_t i = 0; i < merged_.size(); ++i) {
      Finding& f = merged_[i];
      if (f.fixes.empty()) continue;
      bool touches = false, renames = false;
      for (const Fix& fix : f.fixes)
        for (const Edit& e : fix.edits) {
          for (Span r : regions_) touches = touches || overlaps(e.span, r) || (e.span.begin == e.span.end && r.begin < e.span.begin && e.span.begin < r.end);
          if (unread_names_[i].empty()) continue;
          // A name the edit takes away (renamed, or replaced by another expression).
          auto now = identifiers(e.text);
          for (const std::string& name : identifiers(text_.substr(e.span.begin, e.span.end - e.span.begin)))
            renames = renames || (!now.count(name) && unread_names_[i].count(name));
        }
      if (votes_[i] == variants_ && clean_votes_[i] > 0 && !touches && !renames) continue;
      f.fixes.clear();
      f.withheld.push_back(renames ? "a preprocessor arm that uses what the rewrite changes could not be parsed, so the rewrite "
                                     "might leave it behind"
                                   : "the code around it depends on preprocessor branches that lwcport reads one at a time "
                                     "(an #if inside a parameter list, a call or an expression), so no rewrite is sure to fit every branch");
    }
    return std::move(merged_);
  }

 private:
  std::string_view text_;
  std::vector<Span> regions_;
  std::vector<std::set<std::string, std::less<>>> unread_names_;  // per finding: names in arms a voter could not read
  int variants_ = 0;
  std::vector<Finding> merged_;
  std::vector<int> votes_, clean_votes_;
  std::map<FindingKey, size_t> index_;
};

std::string quoted_list(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "`" : ", `") + n + "`";
  return out;
}

// A rewrite of Unreal code may call only what the engine it builds against defines: one that
// needs a later era is unsafe and says so; one that needs a name Unreal does not define at all
// (only lwcport's own library does) is not offered.
void fit_fixes_to_engine(std::vector<Finding>& findings, const Source& source, const UnrealTarget& unreal, const UnrealApi& api) {
  for (Finding& f : findings) {
    std::vector<Fix> kept;
    for (Fix& fix : f.fixes) {
      std::set<std::string, std::less<>> introduced;
      for (const Edit& e : fix.edits) {
        auto before = identifiers(source.slice(e.span));
        for (const std::string& name : identifiers(e.text))
          if (!before.count(name) && api.looks_like_api(name)) introduced.insert(name);
      }
      std::vector<std::string> foreign, later;
      UnrealEra needs = UnrealEra::ue4;
      for (const std::string& name : introduced) {
        std::optional<UnrealEra> era = api.first_era(name);
        if (!era) {
          foreign.push_back(name);
        } else if (static_cast<int>(*era) > static_cast<int>(unreal.era)) {
          later.push_back(name);
          if (static_cast<int>(*era) > static_cast<int>(needs)) needs = *era;
        }
      }
      if (!foreign.empty()) {
        f.withheld.push_back(fmt::format("{} would call {}, which Unreal does not define (only lwcport's own library does)",
                                         fix.title, quoted_list(foreign)));
        continue;
      }
      if (!later.empty()) {
        std::string why = fmt::format("it needs {} ({}), and this file builds against {}", era_name(needs), quoted_list(later), unreal.describe());
        fix.reason = fix.applicability == Applicability::safe ? why : fix.reason + "; " + why;
        fix.applicability = Applicability::unsafe;
      }
      kept.push_back(std::move(fix));
    }
    f.fixes = std::move(kept);
  }
}

// GLSL in a script: a rewrite that edits outside the template literals (a library include at the
// top of the file) would break the script, and is not offered.
void keep_fixes_inside(const std::vector<Span>& literals, std::vector<Finding>& findings) {
  for (Finding& f : findings) {
    std::erase_if(f.fixes, [&](const Fix& fix) {
      bool outside = std::any_of(fix.edits.begin(), fix.edits.end(), [&](const Edit& e) {
        return std::none_of(literals.begin(), literals.end(), [&](Span l) { return l.begin <= e.span.begin && e.span.end <= l.end; });
      });
      if (outside) f.withheld.push_back(fix.title + ": it would edit the script outside the shader's template literal");
      return outside;
    });
  }
}

MacroTable macro_table(Lang lang, const AnalyzeOptions& options) {
  return lwc::macro_table(lang, options.includes ? &options.includes->macros : nullptr, options.macros);
}

// One shader: a file, or one GLSL template literal of a script (then `literal` is its span).
void analyze_unit(const Source& code, Lang lang, std::optional<Span> literal, const AnalyzeOptions& options,
                  std::vector<Finding>& findings) {
  const std::string& text = code.text();
  if (text.find_first_not_of(" \t\r\n\xEF\xBB\xBF") == std::string::npos) {
    if (!literal) findings.push_back(input_finding(Severity::note, 0, "empty file; nothing to analyse", ""));
    return;
  }
  MacroTable macros = macro_table(lang, options);
  ModelContext context = model_context(code, lang, options.includes, options.engine_file);
  std::optional<UnrealTarget> unreal;
  if (context.era) unreal = options.unreal ? UnrealTarget{*options.unreal, false} : UnrealTarget{*context.era, true};
  const WorldData& data = world_data(lang, options.world_sources, options.host_rebases);
  std::vector<Suppression> sups;
  std::optional<VariantMerge> merge;
  std::set<SyntaxError> errors;
  int too_deep = 0;
  std::optional<uint32_t> first_too_deep;
  // Every variant is parsed first: an error only some of them meet lies in an arm they keep.
  std::vector<SyntaxTree> trees;
  for (int variant = 0, variants = 1; variant < variants; ++variant) {
    trees.push_back(parse(code, lang, {&macros, variant, options.max_parse_seconds, literal ? nullptr : options.reuse}));
    if (trees.back().timed_out) {
      findings.push_back(input_finding(
          Severity::error, 0, fmt::format("the parser gave up after {:g} s (its error recovery on this file found no end); not analysed", options.max_parse_seconds),
          "look for a stray or binary byte sequence in the file, or raise \"max-parse-seconds\" in .lwcport.json"));
      return;
    }
    variants = trees.back().variants;
  }
  std::vector<std::set<uint32_t>> error_sets;
  for (const SyntaxTree& tree : trees) error_sets.push_back(error_offsets(tree));
  for (int variant = 0; variant < static_cast<int>(trees.size()); ++variant) {
    const SyntaxTree& tree = trees[static_cast<size_t>(variant)];
    std::set<uint32_t> own_errors;
    for (uint32_t at : error_sets[static_cast<size_t>(variant)])
      if (std::any_of(error_sets.begin(), error_sets.end(), [&](const std::set<uint32_t>& other) { return !other.count(at); })) own_errors.insert(at);
    add_syntax_errors(tree, errors);
    ModelContext this_variant = context;
    this_variant.reuse = literal || !options.reuse ? nullptr : options.model_reuse;
    this_variant.variant = variant;
    WorldModel world(tree, data, this_variant);
    std::vector<Finding> found;
    for (const auto& [rule, check] : checks()) {
      if (rule->applies_to(lang) && options.enabled(rule->id)) check->run(CheckContext{tree, world, *rule, found, unreal});
    }
    share_ports(code, found);
    ProvenanceTracer tracer(world);
    for (Finding& f : found)
      for (ProvenanceStep& step : tracer.trace(value_node_for(world, f.span)))
        if (!(step.span == f.span)) f.related.emplace_back(step.span, std::move(step.text));
    std::set<FindingKey> unread = drop_what_errors_touch(tree, found, own_errors);
    if (!options.lint_library) drop_library_findings(library_definitions(tree, data), data, found);
    if (!world.too_deep().empty()) {
      too_deep += static_cast<int>(world.too_deep().size());
      if (!first_too_deep) first_too_deep = tree.at(world.too_deep().front()).begin;
    }
    if (variant == 0) {
      if (options.summary_for_includers && !literal)
        *options.summary_for_includers = include_summary(code, tree, options.world_sources, options.host_rebases, {nullptr, context.names_as_evidence, context.plain_names, context.era});
      std::vector<Span> comments;
      for (int id = 0; id < static_cast<int>(tree.nodes.size()); ++id)
        if (tree.is(id, "comment")) comments.push_back(tree.span(id));
      sups = find_suppressions(code, comments);
      merge.emplace(text, tree.resolved_conditionals);
    }
    suppress(sups, code, found);
    merge->add(std::move(found), unread, tree.kept_arms);
  }
  std::vector<Finding> found = merge->take();
  if (unreal) {
    drop_older_engine_arms(text, *unreal, data, found);
    fit_fixes_to_engine(found, code, *unreal, data.unreal_api);
  }
  if (literal) keep_fixes_inside({*literal}, found);
  findings.insert(findings.end(), std::make_move_iterator(found.begin()), std::make_move_iterator(found.end()));
  if (trees.front().unterminated_comment) {
    findings.push_back(input_finding(Severity::error, *trees.front().unterminated_comment,
                                     "unterminated block comment: everything after it is a comment",
                                     "close the comment with */ (no fixes are offered in this file until then)"));
    for (Finding& f : findings) f.fixes.clear();
  } else if (!errors.empty()) {
    std::string hint = lang == Lang::glsl && reads_as_hlsl(text)
                           ? "this file reads as HLSL (`cbuffer`, `register(..)`, `SV_` semantics) but its extension says GLSL: map "
                             "the extension in .lwcport.json \"extensions\" (for example {\".frag\": \"hlsl\"}) or pass --lang hlsl"
                       : holds_template_placeholders(text)
                           ? "the file holds `@name` placeholders, which neither HLSL nor GLSL has: it is a template that an "
                             "engine's own preprocessor fills in before compiling, and lwcport reads it as written, so the "
                             "declarations around each placeholder may be missed (lint a filled-in copy to see them)"
                       : holds_effect_framework(text)
                           ? "the file holds Direct3D effect-framework blocks (`technique`/`pass`, `sampler_state`), which lwcport "
                             "does not parse; the functions around them are read as usual, and the blocks themselves only bind "
                             "shaders, textures and states (`lwcport parse --verbose` shows where each error lies)"
                           : "run `lwcport parse --verbose` on this file to see where; a macro used as syntax can cause "
                             "this (declare it in .lwcport.json \"macros\"); no fixes are offered in the declarations "
                             "that hold an error";
    findings.push_back(input_finding(Severity::note, errors.begin()->offset,
                                     fmt::format("{} syntax error(s) the parser could not place; findings next to them may be missed",
                                                 errors.size()),
                                     hint));
  }
  if (too_deep > 0) {
    findings.push_back(input_finding(Severity::note, *first_too_deep,
                                     fmt::format("expression nested too deeply to analyse ({} place(s)); it was skipped", too_deep),
                                     "split the expression"));
  }
  report_unused(sups, code, [&](const RuleInfo& r) { return options.enabled(r.id) && (r.id == kUnusedSuppressionRule || r.applies_to(lang)); },
                findings);
}

}  // namespace

void apply_suppressions(const Source& source, const std::vector<Span>& comments, const std::function<bool(const RuleInfo&)>& ran,
                        std::vector<Finding>& findings) {
  std::vector<Suppression> sups = find_suppressions(source, comments);
  suppress(sups, source, findings);
  report_unused(sups, source, ran, findings);
}

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
  std::optional<FileFormat> format = format_for(source, options);
  if (!format) {
    findings.push_back(input_finding(Severity::error, 0, "not a shader file lwcport knows (by its extension)",
                                     "pass --lang hlsl or --lang glsl, or map the extension in .lwcport.json \"extensions\""));
    return finish();
  }
  std::optional<Lang> lang = format->lang;
  const std::string& file_text = source.text();
  if (file_text.size() > options.max_bytes) {
    findings.push_back(too_large_finding(file_text.size(), options.max_bytes));
    return finish();
  }
  if (auto nul = find_binary_marker(file_text)) {
    findings.push_back(input_finding(Severity::error, *nul, "binary file (a NUL byte); skipped",
                                     "exclude it in .lwcport.json (\"exclude\") if it is not a shader"));
    return finish();
  }
  if (auto bad = find_invalid_utf8(file_text)) {
    findings.push_back(input_finding(Severity::warning, *bad,
                                     fmt::format("invalid UTF-8 (byte 0x{0:02X}); each such byte is read as one character (shown as \\x{0:02X}; U+FFFD in JSON and SARIF)",
                                                 static_cast<unsigned char>(file_text[*bad])),
                                     "save the file as UTF-8"));
  }
  // GLSL in a script is read in place: everything outside a literal becomes blank, so every
  // offset is the script's; each literal is a shader of its own, and a rewrite may only edit
  // inside it.
  ShaderCode shader = shader_code(source, options);
  if (!shader.script) {
    analyze_unit(source, *lang, std::nullopt, options, findings);
    return finish();
  }
  // A script's literals are assembled into programs by the script (shader modules): the functions
  // one defines are known to the others, as an include's are.
  std::vector<FileSummary> summaries;
  for (const Source& view : shader.views) {
    MacroTable macros = macro_table(*lang, options);
    SyntaxTree tree = parse(view, *lang, {&macros, 0, options.max_parse_seconds});
    ModelContext context;
    context.includes = options.includes;
    summaries.push_back(tree.timed_out ? FileSummary{} : WorldModel(tree, world_data(*lang, options.world_sources, options.host_rebases), context).summary());
  }
  for (size_t i = 0; i < shader.views.size(); ++i) {
    FileSummary known = options.includes ? *options.includes : FileSummary{};
    for (size_t j = 0; j < summaries.size(); ++j)
      if (j != i) known.merge(summaries[j]);
    AnalyzeOptions with_siblings = options;
    with_siblings.includes = &known;
    analyze_unit(shader.views[i], *lang, shader.literals[i], with_siblings, findings);
  }
  return finish();
}

void add_syntax_errors(const SyntaxTree& tree, std::set<SyntaxError>& errors) {
  if (tree.error_count == 0) return;
  std::vector<char> in_error(tree.nodes.size(), 0);  // inside an error node: part of that error (pre-order: parents first)
  for (size_t id = 0; id < tree.nodes.size(); ++id) {
    const Node& n = tree.nodes[id];
    if (n.parent >= 0) in_error[id] = in_error[n.parent] || tree.nodes[n.parent].error;
    if (!n.error || in_error[id]) continue;
    errors.insert({n.begin, std::string_view(n.type) == "ERROR" ? std::string("cannot parse this") : fmt::format("missing `{}`", n.type)});
  }
}

std::set<SyntaxError> syntax_errors(const Source& source, const AnalyzeOptions& options) {
  std::set<SyntaxError> errors;
  ShaderCode code = shader_code(source, options);
  if (code.empty(source)) return errors;
  MacroTable macros = macro_table(*code.lang, options);
  for (const Source* unit : code.units(source)) {
    for (int variant = 0, variants = 1; variant < variants; ++variant) {
      SyntaxTree tree = parse(*unit, *code.lang, {&macros, variant, options.max_parse_seconds});
      if (tree.timed_out) {
        errors.insert({0, fmt::format("the parser gave up after {:g} s", options.max_parse_seconds)});
        break;
      }
      variants = tree.variants;
      add_syntax_errors(tree, errors);
    }
  }
  return errors;
}

std::optional<ValueDescription> describe_value(const Source& source, const AnalyzeOptions& options, uint32_t offset) {
  std::optional<FileFormat> format = format_for(source, options);
  if (!format || format->container != Container::shader || source.text().size() > options.max_bytes) return std::nullopt;
  MacroTable macros = macro_table(format->lang, options);
  SyntaxTree tree = parse(source, format->lang, {&macros, 0, options.max_parse_seconds, options.reuse});
  if (tree.timed_out) return std::nullopt;
  ModelContext context = model_context(source, format->lang, options.includes, options.engine_file);
  if (options.reuse) context.reuse = options.model_reuse;  // the parse moved on: so does the model
  WorldModel world(tree, world_data(format->lang, options.world_sources, options.host_rebases), context);
  int node = value_node_at(world, offset);
  if (node < 0) return std::nullopt;
  Kind kind = value_kind(world, node);
  std::string text = fmt::format("`{}`: {}", tree.text(node).substr(0, 60), kind_words(kind));
  std::vector<ProvenanceStep> steps = ProvenanceTracer(world).trace(node);
  for (size_t i = 0; i < steps.size(); ++i) text += (i == 0 ? "\n\nfrom " : "\n\n← ") + steps[i].text;
  return ValueDescription{tree.span(node), kind, text};
}

}  // namespace lwc
