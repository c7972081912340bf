#include "report/migration.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <tuple>

#include "rules/rule.h"

namespace lwc {

namespace {

constexpr double kReviewSafe = 1, kReviewUnsafe = 5;

}  // namespace

const char* const kEraNote =
    "What each file's code is written for, read from the code: `UE 5.4+` uses DoubleFloat names, `UE 5.0-5.3` tile/offset names, "
    "`UE4` is Unreal code with neither (code written for UE4, or code that never needed a large-world type); `HLSL` and `GLSL` "
    "are files outside Unreal; `C++ host` is the host code `--host` names (lwcport host).";
const char* const kHostEra = "C++ host";
const char* const kHostSideNote =
    "Values the shaders read from the host (uniforms, buffers, what a particle simulation or the engine writes) that the port needs "
    "handed over differently: no shader rewrite recovers precision lost before the shader sees the value, so these change on the host.";

namespace {

// How a finding gets fixed: "safe" or "unsafe" (lwcport's fix), "by hand", or "not needed".
std::string fix_kind(const ReportedFinding& f) {
  if (f.not_needed) return "not needed";
  if (f.fix) return std::string(applicability_name(f.fix->applicability));
  return "by hand";
}

std::string directory_of(const std::string& path) {
  std::string dir = std::filesystem::path(path).parent_path().generic_string();
  return dir.empty() ? "." : dir;
}

struct Tally {
  size_t findings = 0, error = 0, warning = 0, note = 0, safe = 0, unsafe = 0, by_hand = 0, not_needed = 0;
  double minutes = 0;
  void add(const ReportedFinding& f) {
    ++findings;
    ++(f.severity == Severity::error ? error : f.severity == Severity::warning ? warning : note);
    std::string kind = fix_kind(f);
    ++(kind == "safe" ? safe : kind == "unsafe" ? unsafe : kind == "by hand" ? by_hand : not_needed);
    minutes += effort_minutes(f);
  }
  void into(nlohmann::ordered_json& j) const {
    j["findings"] = findings;
    j["error"] = error;
    j["warning"] = warning;
    j["note"] = note;
    j["safe"] = safe;
    j["unsafe"] = unsafe;
    j["by_hand"] = by_hand;
    j["not_needed"] = not_needed;
    j["minutes"] = std::round(minutes * 10) / 10;
  }
};

}  // namespace

double effort_minutes(const ReportedFinding& f) {
  std::string kind = fix_kind(f);
  if (kind == "not needed") return 0;
  if (kind == "safe") return kReviewSafe;
  if (kind == "unsafe") return kReviewUnsafe;
  const RuleInfo* rule = find_rule(f.rule);
  return rule ? rule->effort_minutes : 0;
}

MarkerSite marker_site(const std::string& path, const ReportedFinding& f) {
  MarkerSite m{path, f.start.line, f.start.column, f.text, "", ""};
  // The argument: the balanced parentheses after the marker on its line.
  const std::string& line = f.line_text;
  // The marker's byte in the shown line: its column counts code points from line_column.
  size_t at = 0;
  for (int column = f.line_column; at < line.size() && column < f.start.column; ++column) {
    ++at;  // one character: its lead byte, then its continuation bytes
    while (at < line.size() && (static_cast<unsigned char>(line[at]) & 0xC0) == 0x80) ++at;
  }
  if (line.compare(at, f.text.size(), f.text) != 0) at = line.find(f.text);
  size_t open = at == std::string::npos ? std::string::npos : line.find('(', at + f.text.size());
  if (open != std::string::npos) {
    int depth = 0;
    for (size_t i = open; i < line.size(); ++i) {
      depth += line[i] == '(' ? 1 : line[i] == ')' ? -1 : 0;
      if (depth == 0) {
        m.demotes = line.substr(open + 1, i - open - 1);
        break;
      }
    }
  }
  if (f.fix) m.removal = f.fix->applicability == Applicability::safe ? "safe fix" : "unsafe fix: " + f.fix->reason;
  else m.removal = "by hand" + (f.withheld.empty() ? std::string() : ": " + f.withheld.front());
  return m;
}

SceneCost scene_cost(const std::string& name, const std::vector<FileEntry>& files) {
  SceneCost c{name};
  for (const FileEntry& file : files)
    for (const ReportedFinding& f : file.findings) {
      std::string kind = fix_kind(f);
      if (kind == "not needed") {
        ++c.not_needed;
        continue;
      }
      ++c.needed;
      ++(kind == "safe" ? c.safe : kind == "unsafe" ? c.unsafe : c.by_hand);
      if (f.fix && f.fix->strategy == "translated") ++c.translated;
      if (f.fix && f.fix->strategy == "df") ++c.df;
      c.minutes += effort_minutes(f);
    }
  return c;
}

std::string host_work(const ReportedFinding& f) {
  if (f.rule == "lwc-uniform-world-float") return f.hint;
  std::string notes;
  if (f.fix)
    for (const std::string& n : f.fix->notes) notes += (notes.empty() ? "" : "; ") + n;
  if (!notes.empty()) return notes;
  for (const std::string& why : f.withheld)
    if (why.find("host") != std::string::npos) return why;
  return {};
}

nlohmann::ordered_json report_json(const MigrationReport& r) {
  using json = nlohmann::ordered_json;
  Tally all;
  std::map<std::string, Tally> by_rule, by_dir;
  std::map<std::string, size_t> eras, files_in_dir;
  std::map<std::string, std::set<std::string>> rules_in_dir;
  json files = json::array(), findings = json::array(), host_side = json::array();
  // (file, what the host must do, the value unless the words are a fix's notes): a fix's notes name
  // what they ask for, and the findings sharing one fix list them once; each uniform is its own row.
  std::set<std::tuple<std::string, std::string, std::string>> host_listed;
  for (const FileEntry& file : r.files) {
    ++eras[file.era];
    ++files_in_dir[directory_of(file.path)];
    Tally t;
    std::map<std::string, size_t> rules;
    for (const ReportedFinding& f : file.findings) {
      all.add(f);
      t.add(f);
      by_rule[f.rule].add(f);
      by_dir[directory_of(file.path)].add(f);
      rules_in_dir[directory_of(file.path)].insert(f.rule);
      ++rules[f.rule];
      json one = {{"path", file.path}, {"line", f.start.line}, {"column", f.start.column}, {"rule", f.rule},
                  {"severity", severity_name(f.severity)}, {"message", f.message}, {"fix", fix_kind(f)},
                  {"minutes", effort_minutes(f)}};
      findings.push_back(std::move(one));
      std::string needs = file.era == kHostEra ? "" : host_work(f);
      bool shared = f.rule != "lwc-uniform-world-float" && f.fix && !f.fix->notes.empty();  // each uniform is listed
      std::string where = shared ? "" : f.text + ":" + std::to_string(f.start.line);
      if (!needs.empty() && host_listed.emplace(file.path, needs, where).second)
        host_side.push_back({{"path", file.path}, {"line", f.start.line}, {"column", f.start.column}, {"rule", f.rule}, {"value", f.text},
                             {"needs", needs}});
    }
    json entry = {{"path", file.path}, {"era", file.era}};
    t.into(entry);
    entry["by_rule"] = rules;
    files.push_back(std::move(entry));
  }
  json rule_rows = json::array();
  for (const auto& [rule, t] : by_rule) {
    json row = {{"rule", rule}};
    t.into(row);
    rule_rows.push_back(std::move(row));
  }
  json dirs = json::array();
  for (const auto& [dir, count] : files_in_dir) {
    json row = {{"path", dir}, {"files", count}};
    (by_dir.count(dir) ? by_dir.at(dir) : Tally{}).into(row);
    row["rules"] = rules_in_dir[dir];
    dirs.push_back(std::move(row));
  }
  json summary = {{"files", r.files.size()}};
  all.into(summary);
  summary["eras"] = eras;
  summary["by_rule"] = rule_rows;
  std::string basis = "lwcport's estimate, not a measurement: a site fixed by hand costs its rule's minutes (`effort` in the rule's file";
  for (const RuleInfo& rule : all_rules())
    if (by_rule.count(rule.id) && by_rule.at(rule.id).by_hand)
      basis += fmt::format("; {} {:g} min: {}", rule.id, rule.effort_minutes, rule.effort_by_hand);
  basis += fmt::format("); a safe fix {:g} min of review, an unsafe one {:g} min of review and testing; a site the scene does not need, none",
                       kReviewSafe, kReviewUnsafe);
  json markers = json::array();
  for (const MarkerSite& m : r.markers)
    markers.push_back({{"path", m.path}, {"line", m.line}, {"column", m.column}, {"marker", m.marker}, {"demotes", m.demotes}, {"removal", m.removal}});
  json scenes = json::array();
  for (const SceneCost& c : r.scenes)
    scenes.push_back({{"name", c.name}, {"needed", c.needed}, {"not_needed", c.not_needed}, {"safe", c.safe}, {"unsafe", c.unsafe},
                      {"by_hand", c.by_hand}, {"translated", c.translated}, {"df", c.df}, {"minutes", std::round(c.minutes * 10) / 10}});
  json history = json::array();
  for (const HistoryPoint& h : r.history)
    history.push_back({{"commit", h.commit}, {"date", h.date}, {"subject", h.subject}, {"findings", h.total}, {"markers", h.markers}, {"by_rule", h.by_rule}});
  json host = nullptr;
  if (r.host) {
    json pairs = json::array();
    for (const HostPair& p : r.host_pairs)
      pairs.push_back({{"where", p.where}, {"rule", p.rule}, {"parameter", p.parameter}, {"port", p.port}, {"shader_files", p.shader_files}});
    size_t host_files = 0, host_findings = 0;
    for (const FileEntry& f : r.files)
      if (f.era == kHostEra) ++host_files, host_findings += f.findings.size();
    host = {{"files", host_files}, {"findings", host_findings}, {"pairs", pairs}};
  }
  return {{"version", 1},
          {"tool", {{"name", "lwcport"}, {"version", LWCPORT_VERSION}}},
          {"scene", r.scene},
          {"summary", summary},
          {"effort", {{"minutes", std::round(all.minutes * 10) / 10}, {"hours", std::round(all.minutes / 6) / 10}, {"basis", basis}}},
          {"markers", markers},
          {"host_side", host_side},
          {"directories", dirs},
          {"files", files},
          {"findings", findings},
          {"scenes", scenes},
          {"history", history},
          {"verification", r.verification},
          {"host", host}};
}

namespace {

// A Markdown table cell: one line, pipes escaped.
std::string cell(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '|') out += "\\|";
    else if (c == '\n' || c == '\r') out += ' ';
    else out += c;
  }
  return out;
}

std::string table(const std::vector<std::string>& head, const std::vector<std::vector<std::string>>& rows) {
  auto line = [](const std::vector<std::string>& cells) {
    std::string out = "|";
    for (const auto& c : cells) {
      out += ' ';
      out += cell(c);
      out += " |";
    }
    return out + "\n";
  };
  std::string out = line(head) + "|";
  for (size_t i = 0; i < head.size(); ++i) out += "---|";
  out += "\n";
  for (const auto& row : rows) out += line(row);
  return out + "\n";
}

std::string num(const nlohmann::ordered_json& v) { return v.is_number_float() ? fmt::format("{:g}", v.get<double>()) : v.dump(); }

}  // namespace

std::string report_markdown(const nlohmann::ordered_json& j) {
  std::string scene = j["scene"];
  const auto& s = j["summary"];
  std::string out = "# lwcport migration report\n\n";
  out += fmt::format("{} file(s), {} finding(s): {} error(s), {} warning(s), {} note(s). lwcport fixes {} safely and {} with an "
                     "unsafe fix; {} need a hand port; {} are not needed at scene `{}`. Estimated effort: **{} h** ({}).\n\n",
                     num(s["files"]), num(s["findings"]), num(s["error"]), num(s["warning"]), num(s["note"]), num(s["safe"]),
                     num(s["unsafe"]), num(s["by_hand"]), num(s["not_needed"]), scene, num(j["effort"]["hours"]),
                     j["effort"]["basis"].get<std::string>());
  std::vector<std::vector<std::string>> rows;
  for (const auto& row : s["by_rule"])
    rows.push_back({"`" + row["rule"].get<std::string>() + "`", num(row["findings"]), num(row["error"]), num(row["warning"]), num(row["note"]),
                    num(row["safe"]), num(row["unsafe"]), num(row["by_hand"]), num(row["minutes"])});
  out += "## Findings by rule\n\n" + table({"rule", "findings", "error", "warning", "note", "safe fix", "unsafe fix", "by hand", "minutes"}, rows);
  rows.clear();
  for (const auto& [era, count] : s["eras"].items()) rows.push_back({era, num(count)});
  out += "## Files by era\n\n" + std::string(kEraNote) + "\n\n" + table({"era", "files"}, rows);
  rows.clear();
  for (const auto& m : j["markers"])
    rows.push_back({m["path"].get<std::string>() + ":" + num(m["line"]), "`" + m["marker"].get<std::string>() + "`",
                    "`" + m["demotes"].get<std::string>() + "`", m["removal"]});
  out += fmt::format("## Marker ledger ({})\n\n", j["markers"].size());
  out += rows.empty() ? "No `LWCHackToFloat`, `DF*_Hack` or `LWC_HACK_TO_ZERO` left.\n\n" : table({"where", "marker", "demotes", "removal"}, rows);
  rows.clear();
  for (const auto& h : j["host_side"])
    rows.push_back({h["path"].get<std::string>() + ":" + num(h["line"]), "`" + h["rule"].get<std::string>() + "`",
                    "`" + h["value"].get<std::string>() + "`", h["needs"]});
  out += fmt::format("## Host-side work ({})\n\n", j["host_side"].size());
  out += rows.empty() ? std::string("No value the shaders read needs the host to hand it over differently.\n\n")
                      : std::string(kHostSideNote) + "\n\n" + table({"where", "rule", "value", "what the host must do"}, rows);
  std::vector<nlohmann::ordered_json> files(j["files"].begin(), j["files"].end());
  std::stable_sort(files.begin(), files.end(), [](const auto& a, const auto& b) { return a["minutes"].template get<double>() > b["minutes"].template get<double>(); });
  rows.clear();
  for (size_t i = 0; i < files.size() && i < 10 && files[i]["findings"].get<size_t>() > 0; ++i)
    rows.push_back({"`" + files[i]["path"].get<std::string>() + "`", files[i]["era"], num(files[i]["findings"]), num(files[i]["by_hand"]), num(files[i]["minutes"])});
  out += "## Top offenders\n\n" + (rows.empty() ? std::string("None.\n\n") : table({"file", "era", "findings", "by hand", "minutes"}, rows));
  rows.clear();
  for (const auto& d : j["directories"])
    if (d["findings"].get<size_t>() > 0)
      rows.push_back({"`" + d["path"].get<std::string>() + "`", num(d["files"]), num(d["findings"]), num(d["safe"]), num(d["unsafe"]), num(d["by_hand"]), num(d["minutes"])});
  out += "## Directories\n\n" + table({"directory", "files", "findings", "safe fix", "unsafe fix", "by hand", "minutes"}, rows);
  rows.clear();
  for (const auto& c : j["scenes"])
    rows.push_back({"`" + c["name"].get<std::string>() + "`", num(c["needed"]), num(c["not_needed"]), num(c["safe"]), num(c["unsafe"]),
                    num(c["by_hand"]), num(c["translated"]), num(c["df"]), num(c["minutes"])});
  if (!rows.empty())
    out += "## What each scene needs\n\n" +
           table({"scene", "needed", "not needed", "safe fix", "unsafe fix", "by hand", "translated", "DoubleFloat", "minutes"}, rows);
  rows.clear();
  for (const auto& f : j["findings"])
    if (f["fix"] == "not needed")
      rows.push_back({f["path"].get<std::string>() + ":" + num(f["line"]), "`" + f["rule"].get<std::string>() + "`", f["message"]});
  if (!rows.empty())
    out += fmt::format("## Not needed at scene `{}` ({})\n\nThe scene's numbers show float32 is precise enough at these sites: "
                       "they are reported as notes and cost nothing.\n\n", scene, rows.size()) +
           table({"where", "rule", "finding"}, rows);
  if (j["host"].is_object()) {
    const auto& h = j["host"];
    rows.clear();
    for (const auto& p : h["pairs"]) {
      std::string files;
      for (const auto& f : p["shader_files"]) files += (files.empty() ? "`" : ", `") + f.get<std::string>() + "`";
      rows.push_back({p["where"], "`" + p["parameter"].get<std::string>() + "`", port_text(p["port"]), files.empty() ? "none found" : files});
    }
    out += fmt::format("## Host code\n\n`lwcport host`: {} finding(s) in {} C++ file(s) (era `{}` above). A translated-world or high/low port changes "
                       "both sides at once: each host change below and the shaders that read what it uploads.\n\n",
                       num(h["findings"]), num(h["files"]), kHostEra);
    out += rows.empty() ? "No host change feeds a shader parameter.\n\n"
                        : table({"host change", "shader parameter", "the shaders must read it as", "shader files that read it"}, rows);
  }
  rows.clear();
  for (const auto& h : j["history"])
    rows.push_back({"`" + h["commit"].get<std::string>().substr(0, 10) + "`", h["date"], num(h["findings"]), num(h["markers"]), h["subject"]});
  if (!rows.empty()) out += "## Burn-down\n\n" + table({"commit", "date", "findings", "markers", "subject"}, rows);
  if (j["verification"].is_array()) {
    rows.clear();
    for (const auto& fn : j["verification"]) {
      std::string variants;
      for (const auto& v : fn["variants"]) variants += (variants.empty() ? "" : "; ") + v.value("variant", std::string()) + ": " + v.value("status", std::string());
      rows.push_back({"`" + fn.value("function", std::string()) + "`", fn.value("file", std::string()), variants, fn.value("pick", std::string())});
    }
    out += "## Verification\n\n" + table({"function", "file", "variants", "pick"}, rows);
  }
  return out;
}

std::string port_text(const std::string& port) {
  if (port == "translated-matrix") return "a translated-world matrix";
  if (port == "translated-position") return "a translated-world position";
  if (port == "high-low-matrix") return "a matrix relative to its own origin, and the origin (FDFMatrix)";
  if (port == "high-low-position") return "a high/low pair (DoubleFloat)";
  return port;
}

}  // namespace lwc
