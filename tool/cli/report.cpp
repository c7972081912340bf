#include "cli/report.h"

#include <fmt/format.h>

#include <algorithm>
#include <map>

#include "core/uri.h"
#include "project/baseline.h"
#include "fix/apply.h"
#include "project/files.h"
#include "rules/rule.h"

namespace lwc {

ReportedFinding locate(const Source& source, const Finding& f, const std::function<const Source*(const std::string&)>& other) {
  ReportedFinding r;
  r.rule = f.rule;
  r.severity = f.severity;
  r.message = f.message;
  r.hint = f.hint;
  r.start = source.position(f.span.begin);
  r.end = source.position(f.span.end);
  r.decision = f.decision;
  r.not_needed = f.not_needed;
  if (f.span.begin <= f.span.end && f.span.end <= source.text().size())
    r.text = normalised_text(std::string_view(source.text()).substr(f.span.begin, std::min<size_t>(f.span.end - f.span.begin, 4096)));
  if (!f.not_needed) r.withheld = f.withheld;
  r.facts = f.facts;
  // A long line is shown around the finding only: a finding's report never grows with its line.
  constexpr size_t kMaxLineShown = 240;
  std::string_view line = source.line_text(r.start.line);
  if (line.size() <= kMaxLineShown) {
    r.line_text = std::string(line);
  } else {
    size_t line_start = static_cast<size_t>(line.data() - source.text().data());
    size_t at = std::min<size_t>(f.span.begin - std::min<size_t>(f.span.begin, line_start), line.size());
    size_t from = utf8_char_start(line, at > kMaxLineShown / 3 ? at - kMaxLineShown / 3 : 0);
    size_t to = utf8_char_start(line, std::min(line.size(), from + kMaxLineShown));
    r.line_text = std::string(line.substr(from, to - from));
    r.line_column = source.position(static_cast<uint32_t>(line_start + from)).column;
    r.cut_before = from > 0;
    r.cut_after = to < line.size();
  }
  if (!f.fixes.empty()) {
    const Fix& fix = f.fixes.front();
    ReportedFix rf{fix.title, fix.applicability, fix.reason, fix.strategy, {}, fix.library, fix.notes};
    bool placed = true;
    for (const Edit& e : fix.edits) {
      const Source* in = e.path.empty() ? &source : other ? other(e.path) : nullptr;
      if (!in) placed = false;
      else rf.edits.push_back({in->position(e.span.begin), in->position(e.span.end), in_line_endings(*in, e.text), e.path});
    }
    if (placed) r.fix = std::move(rf);
  }
  return r;
}

void add_fingerprints(FileReport& report, const Source& source, bool with_line_hashes) {
  std::vector<std::pair<std::string, std::string>> keys;
  for (const ReportedFinding& f : report.findings) keys.emplace_back(f.rule, f.text);
  std::vector<Fingerprinted> prints = fingerprint_all(keys);
  std::vector<std::string> lines = with_line_hashes ? line_hashes(source.text()) : std::vector<std::string>{};
  for (size_t i = 0; i < report.findings.size(); ++i) {
    ReportedFinding& f = report.findings[i];
    f.fingerprint = prints[i].fingerprint;
    f.occurrence = prints[i].occurrence;
    if (f.start.line >= 1 && static_cast<size_t>(f.start.line) <= lines.size()) f.line_hash = lines[f.start.line - 1];
  }
}

namespace {

nlohmann::json position_json(Position p) { return {{"line", p.line}, {"column", p.column}}; }

}  // namespace

nlohmann::json finding_json(const ReportedFinding& f) {
  nlohmann::json j = {{"rule", f.rule},
                      {"severity", severity_name(f.severity)},
                      {"message", f.message},
                      {"hint", f.hint},
                      {"start", position_json(f.start)},
                      {"end", position_json(f.end)}};
  if (f.fix) {
    nlohmann::json edits = nlohmann::json::array();
    for (const ReportedEdit& e : f.fix->edits) {
      edits.push_back({{"start", position_json(e.start)}, {"end", position_json(e.end)}, {"text", e.text}});
      if (!e.path.empty()) edits.back()["path"] = e.path;
    }
    j["fix"] = {{"title", f.fix->title},
                {"applicability", applicability_name(f.fix->applicability)},
                {"reason", f.fix->reason},
                {"edits", edits}};
    if (!f.fix->strategy.empty()) j["fix"]["strategy"] = f.fix->strategy;
    if (!f.fix->library.empty()) j["fix"]["library"] = f.fix->library;
    if (!f.fix->notes.empty()) j["fix"]["notes"] = f.fix->notes;
  }
  if (!f.decision.empty()) j["decision"] = f.decision;
  if (f.not_needed) j["not-needed"] = true;
  if (!f.withheld.empty()) j["withheld"] = f.withheld;
  if (!f.facts.empty()) j["facts"] = f.facts;
  return j;
}

ReportedFinding finding_from_json(const nlohmann::json& j) {
  ReportedFinding f;
  auto position = [](const nlohmann::json& p) { return Position{p.at("line").get<int>(), p.at("column").get<int>()}; };
  f.rule = j.at("rule");
  if (!parse_severity(j.at("severity").get<std::string>(), f.severity)) throw std::runtime_error("bad severity " + j.at("severity").dump());
  f.message = j.at("message");
  f.hint = j.value("hint", "");
  f.start = position(j.at("start"));
  f.end = position(j.at("end"));
  if (j.contains("fix")) {
    const nlohmann::json& x = j.at("fix");
    ReportedFix fix;
    fix.title = x.at("title");
    fix.applicability = x.at("applicability") == "safe" ? Applicability::safe : Applicability::unsafe;
    fix.reason = x.at("reason");
    fix.strategy = x.value("strategy", "");
    for (const auto& e : x.at("edits")) fix.edits.push_back({position(e.at("start")), position(e.at("end")), e.at("text"), e.value("path", "")});
    fix.library = x.value("library", std::vector<std::string>{});
    fix.notes = x.value("notes", std::vector<std::string>{});
    f.fix = std::move(fix);
  }
  f.decision = j.value("decision", "");
  f.not_needed = j.value("not-needed", false);
  f.withheld = j.value("withheld", std::vector<std::string>{});
  f.facts = j.value("facts", std::map<std::string, std::string>{});
  return f;
}

namespace {

const char* severity_color(Severity s) {
  return s == Severity::error ? "\x1b[1;31m" : s == Severity::warning ? "\x1b[1;33m" : "\x1b[1;36m";
}

// The caret under a finding: one column per character (a byte that is not UTF-8 is one, shown as
// `\xNN`), tabs kept so the caret lines up.
std::string caret_line(const ReportedFinding& f) {
  std::string out;
  const std::string& line = f.line_text;
  int end_column = f.end.line == f.start.line ? f.end.column : 1 << 30;
  int width = 0, column = f.line_column;
  if (f.cut_before) out += ' ';  // under the ellipsis
  for (size_t i = 0; i < line.size(); ++column) {
    size_t len = utf8_sequence(line, i);
    if (column < f.start.column) out += line[i] == '\t' ? "\t" : len ? " " : "    ";
    else if (column < end_column) width += len ? 1 : 4;
    i += len ? len : 1;
  }
  out += '^';
  if (width > 1) out += std::string(width - 1, '~');
  return out;
}

void write_text_file(std::ostream& out, const FileReport& file, bool color, bool explain) {
  auto paint = [&](const char* code, const std::string& s) { return color ? code + s + "\x1b[0m" : s; };
  for (const auto& f : file.findings) {
    out << paint("\x1b[1m", fmt::format("{}:{}:{}:", escape_invalid_utf8(file.path), f.start.line, f.start.column)) << ' '
        << paint(severity_color(f.severity), std::string(severity_name(f.severity)) + ":") << ' ' << escape_invalid_utf8(f.message) << ' '
        << paint("\x1b[2m", "[" + f.rule + "]") << '\n';
    if (!f.line_text.empty()) {
      out << paint("\x1b[34m", fmt::format("{:>5} | ", f.start.line)) << (f.cut_before ? "\u2026" : "") << escape_invalid_utf8(f.line_text)
          << (f.cut_after ? "\u2026" : "") << '\n';
      out << paint("\x1b[34m", std::string(6, ' ') + "| ") << paint("\x1b[1;32m", caret_line(f)) << '\n';
    }
    if (!f.hint.empty()) out << std::string(6, ' ') << paint("\x1b[1;36m", "= help:") << ' ' << f.hint << '\n';
    if (f.fix) {
      out << std::string(6, ' ') << paint("\x1b[1;32m", fmt::format("= fix ({}):", applicability_name(f.fix->applicability))) << ' '
          << f.fix->title << " (" << f.fix->reason << ")\n";
      for (const std::string& note : f.fix->notes) out << std::string(8, ' ') << "- " << note << '\n';
    } else {
      for (const std::string& why : f.withheld) out << std::string(6, ' ') << paint("\x1b[1;33m", "= no fix:") << ' ' << why << '\n';
    }
    if (explain && !f.decision.empty()) out << std::string(6, ' ') << paint("\x1b[1;35m", "= scene:") << ' ' << f.decision << '\n';
  }
}

std::string sarif_level(Severity s) { return s == Severity::error ? "error" : s == Severity::warning ? "warning" : "note"; }

std::string sentence(std::string s) {
  if (!s.empty() && s.back() != '.') s += '.';
  return s;
}

// Relative paths resolve against SRCROOT (the working folder); absolute ones are file: URIs.
nlohmann::json artifact_location(const std::string& path) {
  if (!path.empty() && path[0] == '/') return {{"uri", "file://" + uri_encode(path)}};
  std::string rel = path.rfind("./", 0) == 0 ? path.substr(2) : path;
  return {{"uri", uri_encode(rel)}, {"uriBaseId", "SRCROOT"}};
}

nlohmann::json sarif_rules(const std::string& help_uri_base) {
  nlohmann::json rules = nlohmann::json::array();
  for (const RuleInfo& r : all_rules()) {
    std::string url = rule_doc_url(r.id, help_uri_base);
    std::string help = sentence(r.summary) + " " + sentence(r.rationale);
    nlohmann::json rule = {{"id", r.id},
                           {"name", r.name},
                           {"shortDescription", {{"text", sentence(r.summary)}}},
                           {"fullDescription", {{"text", sentence(r.rationale)}}},
                           {"help", {{"text", help}, {"markdown", url.empty() ? help : fmt::format("{} See [{}]({}).", help, r.id, url)}}},
                           {"defaultConfiguration", {{"level", sarif_level(r.severity)}}},
                           {"properties", {{"tags", {"large-world-coordinates", "precision"}}}}};
    if (!url.empty()) rule["helpUri"] = url;
    rules.push_back(std::move(rule));
  }
  return rules;
}

size_t rule_index(const std::string& id) {
  const auto& rules = all_rules();
  for (size_t i = 0; i < rules.size(); ++i)
    if (rules[i].id == id) return i;
  return 0;
}

nlohmann::json sarif_region(Position start, Position end) {
  return {{"startLine", start.line}, {"startColumn", start.column}, {"endLine", end.line}, {"endColumn", end.column}};
}

nlohmann::json sarif_result(const std::string& path, const ReportedFinding& f) {
  nlohmann::json region = sarif_region(f.start, f.end);
  if (!f.line_text.empty()) region["snippet"] = {{"text", f.line_text}};
  nlohmann::json result = {{"ruleId", f.rule},
                           {"ruleIndex", rule_index(f.rule)},
                           {"level", sarif_level(f.severity)},
                           {"message", {{"text", sentence(f.message) + (f.hint.empty() ? "" : " Fix: " + sentence(f.hint))}}},
                           {"locations", {{{"physicalLocation", {{"artifactLocation", artifact_location(path)}, {"region", region}}}}}}};
  if (!f.fingerprint.empty()) {
    result["partialFingerprints"] = {{"lwcport/v1", f.fingerprint}};
    if (!f.line_hash.empty()) result["partialFingerprints"]["primaryLocationLineHash"] = f.line_hash;
  }
  if (f.fix) {
    // One artifact change per file the fix edits: the finding's own first, then the others.
    std::vector<std::string> files = {""};
    for (const ReportedEdit& e : f.fix->edits)
      if (std::find(files.begin(), files.end(), e.path) == files.end()) files.push_back(e.path);
    nlohmann::json changes = nlohmann::json::array();
    for (const std::string& file : files) {
      nlohmann::json replacements = nlohmann::json::array();
      for (const ReportedEdit& e : f.fix->edits)
        if (e.path == file) replacements.push_back({{"deletedRegion", sarif_region(e.start, e.end)}, {"insertedContent", {{"text", e.text}}}});
      if (!replacements.empty()) changes.push_back({{"artifactLocation", artifact_location(file.empty() ? path : file)}, {"replacements", replacements}});
    }
    nlohmann::json fix = {
        {"description", {{"text", fmt::format("{} ({}: {}).", f.fix->title, applicability_name(f.fix->applicability), f.fix->reason)}}},
        {"artifactChanges", changes}};
    result["fixes"] = nlohmann::json::array({fix});
    result["properties"] = {{"fixApplicability", applicability_name(f.fix->applicability)}};
    // What must change outside the shader (new uniforms, host code): SARIF's fix has no place for it.
    if (!f.fix->notes.empty()) result["properties"]["fixNotes"] = f.fix->notes;
  }
  if (!f.decision.empty()) result["properties"]["sceneDecision"] = f.decision;
  if (f.not_needed) result["properties"]["notNeeded"] = true;
  if (!f.withheld.empty()) result["properties"]["withheldFixes"] = f.withheld;
  return result;
}

// The SARIF log with an empty results array, split where results go.
std::pair<std::string, std::string> sarif_frame(const ReportOptions& o) {
  std::string root = o.working_dir;
  if (root.empty() || root.back() != '/') root += '/';
  nlohmann::json doc = {
      {"$schema", "https://docs.oasis-open.org/sarif/sarif/v2.1.0/errata01/os/schemas/sarif-schema-2.1.0.json"},
      {"version", "2.1.0"},
      {"runs",
       {{{"tool",
          {{"driver",
            {{"name", "lwcport"},
             {"version", LWCPORT_VERSION},
             {"semanticVersion", LWCPORT_VERSION},
             {"informationUri", docs_url()},
             {"rules", sarif_rules(o.help_uri_base)}}}}},
         {"originalUriBaseIds", {{"SRCROOT", {{"uri", "file://" + uri_encode(root)}}}}},
         {"columnKind", "unicodeCodePoints"},
         {"results", nlohmann::json::array()}}}}};
  auto& driver = doc["runs"][0]["tool"]["driver"];
  if (driver["informationUri"] == "") driver.erase("informationUri");
  std::string text = json_text(doc, 1);
  size_t at = text.find("\"results\": []");
  at += std::string("\"results\": [").size();
  return {text.substr(0, at) + "\n", text.substr(at)};
}

// GitHub workflow commands: properties escape %, CR, LF, ':' and ','; messages %, CR, LF.
std::string gh_escape(std::string_view s, bool property) {
  std::string out;
  for (char c : s) {
    if (c == '%') out += "%25";
    else if (c == '\r') out += "%0D";
    else if (c == '\n') out += "%0A";
    else if (property && c == ':') out += "%3A";
    else if (property && c == ',') out += "%2C";
    else out += c;
  }
  return out;
}

void write_github_file(std::ostream& out, const FileReport& file) {
  for (const auto& f : file.findings) {
    const char* command = f.severity == Severity::error ? "error" : f.severity == Severity::warning ? "warning" : "notice";
    out << fmt::format("::{} file={},line={},col={},endLine={},endColumn={},title={}::{}\n", command,
                       gh_escape(escape_invalid_utf8(file.path), true), f.start.line, f.start.column, f.end.line, f.end.column,
                       gh_escape(f.rule, true),
                       gh_escape(escape_invalid_utf8(f.message + (f.hint.empty() ? "" : ". Fix: " + f.hint)), false));
  }
}

}  // namespace

std::string json_text(const nlohmann::json& value, int indent) {
  return value.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
}

ReportWriter::ReportWriter(std::ostream& out, ReportOptions options) : out_(out), options_(std::move(options)) { begin(); }

void ReportWriter::begin() {
  if (options_.statistics) return;
  if (options_.format == Format::json) {
    out_ << "{\n \"version\": 1,\n \"tool\": " << nlohmann::json({{"name", "lwcport"}, {"version", LWCPORT_VERSION}}).dump()
         << ",\n \"findings\": [";
  } else if (options_.format == Format::sarif) {
    out_ << sarif_frame(options_).first;
  }
}

void ReportWriter::file(const FileReport& report) {
  if (!report.has_code) return;
  ++files_;
  for (const auto& f : report.findings) {
    (f.severity == Severity::error ? errors_ : f.severity == Severity::warning ? warnings_ : notes_)++;
    if (!f.not_needed) worst_ = std::max(worst_, static_cast<int>(f.severity));
    if (options_.statistics) {
      RuleCount& c = per_rule_[f.rule];
      ++c.findings;
      if (f.fix) ++(f.fix->applicability == Applicability::safe ? c.safe : c.unsafe);
    }
  }
  if (options_.statistics) return;
  switch (options_.format) {
    case Format::text: write_text_file(out_, report, options_.color, options_.explain); break;
    case Format::github: write_github_file(out_, report); break;
    case Format::json:
    case Format::sarif:
      for (const auto& f : report.findings) {
        nlohmann::json j;
        if (options_.format == Format::json) {
          j = finding_json(f);
          j["path"] = report.path;
          if (!f.fingerprint.empty()) j["fingerprint"] = f.fingerprint;
        } else {
          j = sarif_result(report.path, f);
        }
        out_ << (first_ ? "\n  " : ",\n  ") << json_text(j);
        first_ = false;
      }
      break;
  }
}

void ReportWriter::finish() {
  size_t total = errors_ + warnings_ + notes_;
  if (options_.statistics) {
    write_statistics();
    return;
  }
  switch (options_.format) {
    case Format::text:
      if (total == 0) out_ << fmt::format("No findings in {} file(s).\n", files_);
      else
        out_ << fmt::format("Found {} finding(s) in {} file(s): {} error(s), {} warning(s), {} note(s).\n", total, files_,
                            errors_, warnings_, notes_);
      out_ << units_line();
      break;
    case Format::json:
      out_ << (first_ ? "]" : "\n ]") << ",\n \"files\": " << files_;
      if (options_.units) out_ << ",\n \"units\": " << units_json().dump();
      out_ << ",\n \"summary\": " << nlohmann::json({{"error", errors_}, {"warning", warnings_}, {"note", notes_}}).dump() << "\n}\n";
      break;
    case Format::sarif: out_ << (first_ ? "" : "\n") << sarif_frame(options_).second << '\n'; break;
    case Format::github: break;
  }
  out_.flush();
}

// `lwcport host`: the translation units, which the files (units and the headers with findings) do not count.
nlohmann::json ReportWriter::units_json() const {
  const UnitCounts& u = *options_.units;
  return {{"analysed", u.analysed}, {"failed", u.failed}, {"crashed", u.crashed}, {"skipped", u.skipped}};
}

std::string ReportWriter::units_line() const {
  if (!options_.units) return "";
  const UnitCounts& u = *options_.units;
  return fmt::format("Translation units: {} analysed, {} Clang could not compile, {} where the analysis crashed, {} skipped (not on disk).\n",
                     u.analysed, u.failed, u.crashed, u.skipped);
}

// --statistics: per rule, most findings first, how many and how many a fix covers (safe / unsafe).
void ReportWriter::write_statistics() {
  std::vector<std::pair<std::string, RuleCount>> rows(per_rule_.begin(), per_rule_.end());
  std::stable_sort(rows.begin(), rows.end(), [](const auto& a, const auto& b) { return a.second.findings > b.second.findings; });
  if (options_.format == Format::json) {
    nlohmann::json list = nlohmann::json::array();
    for (const auto& [rule, c] : rows) list.push_back({{"rule", rule}, {"findings", c.findings}, {"safe_fixes", c.safe}, {"unsafe_fixes", c.unsafe}});
    nlohmann::json all = {{"version", 1}, {"statistics", list}, {"files", files_}, {"summary", {{"error", errors_}, {"warning", warnings_}, {"note", notes_}}}};
    if (options_.units) all["units"] = units_json();
    out_ << json_text(all, 1) << '\n';
  } else {
    out_ << fmt::format("{:>8}  {:<26} {:>9} {:>9}\n", "FINDINGS", "RULE", "SAFE FIX", "UNSAFE");
    for (const auto& [rule, c] : rows) out_ << fmt::format("{:>8}  {:<26} {:>9} {:>9}\n", c.findings, rule, c.safe, c.unsafe);
    out_ << fmt::format("{} finding(s) in {} file(s): {} error(s), {} warning(s), {} note(s).\n", errors_ + warnings_ + notes_,
                        files_, errors_, warnings_, notes_);
    out_ << units_line();
  }
  out_.flush();
}

bool ReportWriter::failed(Severity threshold) const { return worst_ >= static_cast<int>(threshold); }

}  // namespace lwc
