#include "rules/rule.h"

#include <filesystem>

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

#include "core/embedded.h"
#include "core/uri.h"

namespace lwc {

bool RuleInfo::applies_to(Lang lang) const {
  return std::find(languages.begin(), languages.end(), lang) != languages.end();
}

namespace {

struct Loaded {
  std::vector<RuleInfo> rules;
  nlohmann::json world_space;
  nlohmann::json host_world;
};

RuleInfo parse_rule(std::string_view file, const nlohmann::json& j) {
  auto fail = [&](const std::string& what) { throw std::runtime_error("rules/" + std::string(file) + ": " + what); };
  RuleInfo r;
  for (const char* key : {"id", "name", "severity", "languages", "summary", "message", "hint", "rationale", "effort", "examples"})
    if (!j.contains(key)) fail(std::string("missing \"") + key + "\"");
  r.id = j.at("id").get<std::string>();
  if (std::string(file) != r.id + ".json") fail("file name must be the rule id");
  r.name = j.at("name").get<std::string>();
  if (!parse_severity(j.at("severity").get<std::string>(), r.severity)) fail("bad severity");
  for (const auto& l : j.at("languages")) {
    if (l == "c++") {
      r.host = true;
      continue;
    }
    auto lang = parse_lang(l.get<std::string>());
    if (!lang) fail("unknown language " + l.dump());
    r.languages.push_back(*lang);
  }
  r.summary = j.at("summary").get<std::string>();
  r.message = j.at("message").get<std::string>();
  r.hint = j.at("hint").get<std::string>();
  r.rationale = j.at("rationale").get<std::string>();
  const nlohmann::json& effort = j.at("effort");
  if (!effort.contains("minutes") || !effort.at("minutes").is_number() || !effort.contains("by-hand"))
    fail("\"effort\" needs \"minutes\" (per site fixed by hand) and \"by-hand\" (what that takes)");
  r.effort_minutes = effort.at("minutes").get<double>();
  r.effort_by_hand = effort.at("by-hand").get<std::string>();
  r.data = j.value("data", nlohmann::json::object());
  r.examples = j.at("examples");
  r.scene_dependent = j.value("scene-dependent", false);
  const nlohmann::json fixes = j.value("fixes", nlohmann::json::object());
  for (const auto& [kind, fix] : fixes.items()) {
    for (const char* key : {"title", "applicability", "reason"})
      if (!fix.contains(key)) fail("fix \"" + kind + "\" misses \"" + key + "\"");
    std::string a = fix.at("applicability").get<std::string>();
    if (a != "safe" && a != "unsafe") fail("fix \"" + kind + "\": applicability must be safe or unsafe");
    r.fixes.emplace(kind, fix);
  }
  return r;
}

const Loaded& loaded() {
  static const Loaded data = [] {
    Loaded l;
    for (const EmbeddedFile& f : embedded_rule_files()) {
      nlohmann::json j = nlohmann::json::parse(f.text);
      if (j.contains("world-space")) l.world_space = j.at("world-space");
      else if (j.contains("host-world")) l.host_world = j.at("host-world");
      else if (j.contains("macros")) continue;  // lang/macros.cpp reads it
      else l.rules.push_back(parse_rule(f.name, j));
    }
    std::sort(l.rules.begin(), l.rules.end(), [](const RuleInfo& a, const RuleInfo& b) { return a.id < b.id; });
    return l;
  }();
  return data;
}

}  // namespace

const std::vector<RuleInfo>& all_rules() { return loaded().rules; }

const RuleInfo* find_rule(std::string_view id) {
  for (const RuleInfo& r : all_rules())
    if (r.id == id) return &r;
  return nullptr;
}

const nlohmann::json& world_space_data() { return loaded().world_space; }
const nlohmann::json& host_world_data() { return loaded().host_world; }

std::vector<std::string> language_names(const RuleInfo& rule) {
  std::vector<std::string> out;
  for (Lang l : rule.languages) out.emplace_back(lang_name(l));
  if (rule.host) out.emplace_back("c++");
  return out;
}

// Appends a value quoted in a message, at most kMaxQuoted bytes: the start and the end of a longer one
// around an ellipsis (cut at UTF-8 boundaries), so a finding's text never grows with its line.
static void append_shortened(std::string& out, std::string_view value) {
  if (value.size() <= kMaxQuoted) {
    out += value;
    return;
  }
  out += value.substr(0, utf8_char_start(value, kMaxQuoted * 2 / 3));
  out += " \u2026 ";
  out += value.substr(utf8_char_start(value, value.size() - kMaxQuoted / 4));
}

std::string shortened(std::string_view value) {
  std::string out;
  append_shortened(out, value);
  return out;
}

std::string expand(std::string_view tmpl, const Vars& vars) {
  std::string out;
  size_t i = 0;
  while (i < tmpl.size()) {
    size_t open = tmpl.find('{', i);
    if (open == std::string_view::npos) break;
    size_t close = tmpl.find('}', open);
    if (close == std::string_view::npos) break;
    out.append(tmpl.substr(i, open - i));
    auto it = vars.find(std::string(tmpl.substr(open + 1, close - open - 1)));
    if (it != vars.end()) append_shortened(out, it->second);
    else out.append(tmpl.substr(open, close - open + 1));
    i = close + 1;
  }
  out.append(tmpl.substr(i));
  return out;
}

Finding make_finding(const RuleInfo& rule, Span span, const Vars& vars) {
  Finding f;
  f.rule = rule.id;
  f.severity = rule.severity;
  f.span = span;
  f.message = expand(rule.message, vars);
  f.hint = expand(rule.hint, vars);
  return f;
}

Fix make_fix(const RuleInfo& rule, std::string_view kind, const Vars& vars, std::vector<Edit> edits) {
  auto it = rule.fixes.find(kind);
  if (it == rule.fixes.end()) throw std::logic_error(rule.id + ": no fix of kind " + std::string(kind));
  const nlohmann::json& j = it->second;
  Fix f;
  f.title = expand(j.at("title").get<std::string>(), vars);
  f.applicability = j.at("applicability") == "safe" ? Applicability::safe : Applicability::unsafe;
  f.reason = expand(j.at("reason").get<std::string>(), vars);
  f.strategy = j.value("strategy", "");
  f.edits = std::move(edits);
  return f;
}

Finding& CheckContext::report(Span span, const Vars& vars) const { return out.emplace_back(make_finding(rule, span, vars)); }

bool CheckContext::too_long(Finding& finding, std::string_view kind, size_t bytes) const {
  if (bytes <= kMaxFixText) return false;
  Fix f = make_fix(rule, kind, {}, {});
  finding.withheld.push_back(fmt::format("{}{}the rewrite would write {} bytes of this expression again; split the expression, or port it "
                                         "by hand", f.strategy, f.strategy.empty() ? "" : ": ", bytes));
  return true;
}

namespace {

// Text that can be stored to: a name, then members and indices (`A.B[i].C`).
bool lvalue_text(std::string_view text) {
  size_t i = 0;
  auto word = [&] {
    size_t start = i;
    while (i < text.size() && (std::isalnum(static_cast<unsigned char>(text[i])) || text[i] == '_')) ++i;
    return i > start && !std::isdigit(static_cast<unsigned char>(text[start]));
  };
  if (!word()) return false;
  while (i < text.size()) {
    if (text[i] == '.') {
      ++i;
      if (!word()) return false;
    } else if (text[i] == '[') {
      int depth = 0;
      for (; i < text.size(); ++i) {
        depth += text[i] == '[' ? 1 : text[i] == ']' ? -1 : 0;
        if (depth == 0) break;
      }
      if (i++ >= text.size()) return false;
    } else {
      return false;
    }
  }
  return true;
}

// An edit that replaces what an assignment (or ++/--) stores into, or the object of a member or
// element stored into, with text that cannot be stored to: a rewrite that would not compile.
bool replaces_store_target(const SyntaxTree& tree, const Edit& e) {
  if (lvalue_text(e.text)) return false;
  // Nodes are in pre-order, so by their start: the nodes that start where the edit does.
  auto first = std::lower_bound(tree.nodes.begin(), tree.nodes.end(), e.span.begin, [](const Node& n, uint32_t b) { return n.begin < b; });
  for (auto it = first; it != tree.nodes.end() && it->begin == e.span.begin; ++it) {
    if (it->end != e.span.end) continue;
    int node = static_cast<int>(it - tree.nodes.begin());
    for (int parent = tree.at(node).parent; parent >= 0; node = parent, parent = tree.at(node).parent) {
      std::string_view type = tree.at(parent).type;
      bool object = (type == "field_expression" || type == "subscript_expression") && tree.child_by_field(parent, "argument") == node;
      if (object || type == "parenthesized_expression") continue;
      if (type == "assignment_expression") return tree.child_by_field(parent, "left") == node;
      return type == "update_expression";
    }
  }
  return false;
}

// The same edit twice is one edit; an edit inside another whose text already carries it (a call
// rewritten whole around an argument renamed before: the outer text holds the inner span's text
// with the inner edits made) is part of that one. Both go; any other overlap stays, and is refused.
void merge_carried_edits(std::string_view source, std::vector<Edit>& edits) {
  // By where they start, the longer first; the edits keep their order.
  std::vector<size_t> order(edits.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    const Span x = edits[a].span, y = edits[b].span;
    return x.begin != y.begin ? x.begin < y.begin : x.end != y.end ? x.end > y.end : a < b;
  });
  std::vector<bool> gone(edits.size(), false);
  for (size_t k = 1; k < order.size(); ++k)
    if (edits[order[k]] == edits[order[k - 1]]) gone[order[k]] = true;
  for (size_t o = 0; o < order.size(); ++o) {
    const Edit& outer = edits[order[o]];
    if (gone[order[o]] || !outer.path.empty() || outer.span.end > source.size()) continue;
    std::vector<size_t> inner;
    for (size_t i = o + 1; i < order.size() && edits[order[i]].span.begin < outer.span.end; ++i) {
      const Edit& e = edits[order[i]];
      if (!gone[order[i]] && e.path.empty() && e.span.end <= outer.span.end && !(e.span == outer.span)) inner.push_back(order[i]);
    }
    if (inner.empty()) continue;
    // The outer span's text with the inner edits made, back to front (where they overlap each
    // other the rewrite is refused anyway).
    std::string text(source.substr(outer.span.begin, outer.span.end - outer.span.begin));
    bool disjoint = true;
    for (size_t k = inner.size(); k-- > 0 && disjoint;) {
      const Edit& e = edits[inner[k]];
      if (k + 1 < inner.size() && e.span.end > edits[inner[k + 1]].span.begin) disjoint = false;
      else text.replace(e.span.begin - outer.span.begin, e.span.end - e.span.begin, e.text);
    }
    if (disjoint && outer.text.find(text) != std::string::npos)
      for (size_t i : inner) gone[i] = true;
  }
  size_t k = 0;
  edits.erase(std::remove_if(edits.begin(), edits.end(), [&](const Edit&) { return gone[k++]; }), edits.end());
}

}  // namespace

Fix* CheckContext::fix(Finding& finding, std::string_view kind, const Vars& vars, std::vector<Edit> edits) const {
  merge_carried_edits(tree.source->text(), edits);
  size_t bytes = 0;
  for (const Edit& e : edits) bytes += e.text.size();
  if (too_long(finding, kind, bytes)) return nullptr;
  // A rewrite never turns what the code stores into into an expression.
  for (const Edit& e : edits)
    if (e.path.empty() && replaces_store_target(tree, e)) {
      Fix f = make_fix(rule, kind, {}, {});
      finding.withheld.push_back(fmt::format("{}{}the rewrite would store into `{}`, which is not a place: it is withheld", f.strategy,
                                             f.strategy.empty() ? "" : ": ", e.text.size() > 60 ? e.text.substr(0, 57) + "..." : e.text));
      return nullptr;
    }
  // A rewrite whose edits overlap cannot be applied as one: it is withheld, never half applied.
  std::vector<Span> spans;
  for (const Edit& e : edits) spans.push_back(e.span);
  std::sort(spans.begin(), spans.end(), [](Span a, Span b) { return a.begin != b.begin ? a.begin < b.begin : a.end < b.end; });
  for (size_t i = 1; i < spans.size(); ++i)
    if (spans[i].begin < spans[i - 1].end || (spans[i].begin == spans[i - 1].begin && spans[i].end == spans[i - 1].end)) {
      Fix f = make_fix(rule, kind, {}, {});
      finding.withheld.push_back(fmt::format("{}{}lwcport's rewrite edits one place twice here; it is withheld (please report this file)",
                                             f.strategy, f.strategy.empty() ? "" : ": "));
      return nullptr;
    }
  return &finding.fixes.emplace_back(make_fix(rule, kind, vars, std::move(edits)));
}

std::string_view rule_page(std::string_view id) {
  for (const EmbeddedFile& f : embedded_rule_pages())
    if (f.name.size() == id.size() + 3 && f.name.substr(0, id.size()) == id && f.name.substr(id.size()) == ".md") return f.text;
  return {};
}

namespace {

// The documentation installed with the tool: PREFIX/share/doc/lwcport beside the binary's prefix,
// else the source tree's docs/ it was built from; "" when neither holds the rule pages.
const std::string& installed_docs() {
  static const std::string dir = [] {
    std::error_code ec;
    std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    std::vector<std::filesystem::path> candidates;
    if (!ec) candidates.push_back(exe.parent_path().parent_path() / "share/doc/lwcport");
    candidates.push_back(std::filesystem::path(LWCPORT_SOURCE_DIR) / "docs");
    for (const auto& c : candidates)
      if (std::filesystem::is_regular_file(c / "rules" / (std::string(kInputRule) + ".md"), ec)) return c.lexically_normal().string();
    return std::string();
  }();
  return dir;
}

}  // namespace

std::string rule_doc_url(std::string_view id, std::string_view base) {
  if (!base.empty()) return std::string(base) + std::string(id) + ".md";
  if (installed_docs().empty()) return "";
  return "file://" + uri_encode(installed_docs() + "/rules/" + std::string(id) + ".md");
}

std::string docs_url() { return installed_docs().empty() ? "" : "file://" + uri_encode(installed_docs() + "/"); }

}  // namespace lwc
