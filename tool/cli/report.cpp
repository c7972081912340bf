#include "cli/report.h"

#include <fmt/format.h>

#include <map>

#include "rules/rule.h"

namespace lwc {

ReportedFinding locate(const Source& source, const Finding& f) {
  ReportedFinding r{f.rule, f.severity, f.message, f.hint, source.position(f.span.begin), source.position(f.span.end), {}};
  r.line_text = std::string(source.line_text(r.start.line));
  return r;
}

nlohmann::json finding_json(const ReportedFinding& f) {
  return {{"rule", f.rule},
          {"severity", severity_name(f.severity)},
          {"message", f.message},
          {"hint", f.hint},
          {"start", {{"line", f.start.line}, {"column", f.start.column}}},
          {"end", {{"line", f.end.line}, {"column", f.end.column}}}};
}

namespace {

struct Counts {
  size_t error = 0, warning = 0, note = 0;
  size_t total() const { return error + warning + note; }
};

Counts count(const std::vector<FileReport>& files) {
  Counts c;
  for (const auto& file : files)
    for (const auto& f : file.findings)
      (f.severity == Severity::error ? c.error : f.severity == Severity::warning ? c.warning : c.note)++;
  return c;
}

const char* severity_color(Severity s) {
  return s == Severity::error ? "\x1b[1;31m" : s == Severity::warning ? "\x1b[1;33m" : "\x1b[1;36m";
}

// Code points of a line up to a 1-based column, with tabs kept so the caret lines up.
std::string caret_line(const ReportedFinding& f) {
  std::string out;
  int column = 1;
  const std::string& line = f.line_text;
  int end_column = f.end.line == f.start.line ? f.end.column : 1 << 30;
  int width = 0;
  for (size_t i = 0; i < line.size(); ++i) {
    unsigned char c = static_cast<unsigned char>(line[i]);
    if ((c & 0xC0) == 0x80) continue;
    if (column < f.start.column) out += c == '\t' ? '\t' : ' ';
    else if (column < end_column) ++width;
    ++column;
  }
  out += '^';
  if (width > 1) out += std::string(width - 1, '~');
  return out;
}

void write_text(std::ostream& out, const std::vector<FileReport>& files, const ReportOptions& o) {
  auto paint = [&](const char* code, const std::string& s) { return o.color ? code + s + "\x1b[0m" : s; };
  for (const auto& file : files) {
    for (const auto& f : file.findings) {
      out << paint("\x1b[1m", fmt::format("{}:{}:{}:", file.path, f.start.line, f.start.column)) << ' '
          << paint(severity_color(f.severity), std::string(severity_name(f.severity)) + ":") << ' ' << f.message << ' '
          << paint("\x1b[2m", "[" + f.rule + "]") << '\n';
      if (!f.line_text.empty()) {
        std::string gutter = fmt::format("{:>5} | ", f.start.line);
        out << paint("\x1b[34m", gutter) << f.line_text << '\n';
        out << paint("\x1b[34m", std::string(6, ' ') + "| ") << paint("\x1b[1;32m", caret_line(f)) << '\n';
      }
      if (!f.hint.empty()) out << std::string(6, ' ') << paint("\x1b[1;36m", "= help:") << ' ' << f.hint << '\n';
    }
  }
  Counts c = count(files);
  if (c.total() == 0) {
    out << fmt::format("No findings in {} file(s).\n", files.size());
  } else {
    out << fmt::format("Found {} finding(s) in {} file(s): {} error(s), {} warning(s), {} note(s).\n", c.total(),
                       files.size(), c.error, c.warning, c.note);
  }
}

void write_json(std::ostream& out, const std::vector<FileReport>& files) {
  nlohmann::json findings = nlohmann::json::array();
  for (const auto& file : files)
    for (const auto& f : file.findings) {
      nlohmann::json j = finding_json(f);
      j["path"] = file.path;
      findings.push_back(std::move(j));
    }
  Counts c = count(files);
  nlohmann::json doc = {{"version", 1},
                        {"tool", {{"name", "lwcport"}, {"version", LWCPORT_VERSION}}},
                        {"files", files.size()},
                        {"summary", {{"error", c.error}, {"warning", c.warning}, {"note", c.note}}},
                        {"findings", std::move(findings)}};
  out << doc.dump(2) << '\n';
}

std::string sarif_level(Severity s) { return s == Severity::error ? "error" : s == Severity::warning ? "warning" : "note"; }

std::string sentence(std::string s) {
  if (!s.empty() && s.back() != '.') s += '.';
  return s;
}

// Percent-encodes what may not appear in a relative URI reference.
std::string uri_encode(std::string_view path) {
  std::string out;
  for (unsigned char c : path) {
    if (std::isalnum(c) || std::string_view("-._~/").find(static_cast<char>(c)) != std::string_view::npos) out += static_cast<char>(c);
    else out += fmt::format("%{:02X}", c);
  }
  return out;
}

// Relative paths resolve against SRCROOT (the working folder); absolute ones are file: URIs.
nlohmann::json artifact_location(const std::string& path) {
  if (!path.empty() && path[0] == '/') return {{"uri", "file://" + uri_encode(path)}};
  std::string rel = path.rfind("./", 0) == 0 ? path.substr(2) : path;
  return {{"uri", uri_encode(rel)}, {"uriBaseId", "SRCROOT"}};
}

void write_sarif(std::ostream& out, const std::vector<FileReport>& files, const ReportOptions& o) {
  const std::string docs = "https://github.com/lwcport/lwcport/blob/main/docs/rules/";
  nlohmann::json rules = nlohmann::json::array();
  std::map<std::string, size_t> index;
  for (const RuleInfo& r : all_rules()) {
    index[r.id] = rules.size();
    rules.push_back({{"id", r.id},
                     {"name", r.name},
                     {"shortDescription", {{"text", sentence(r.summary)}}},
                     {"fullDescription", {{"text", sentence(r.rationale)}}},
                     {"help", {{"text", sentence(r.hint)}, {"markdown", fmt::format("{} See [{}]({}{}.md).", sentence(r.rationale), r.id, docs, r.id)}}},
                     {"helpUri", docs + r.id + ".md"},
                     {"defaultConfiguration", {{"level", sarif_level(r.severity)}}},
                     {"properties", {{"tags", {"large-world-coordinates", "precision"}}}}});
  }
  nlohmann::json results = nlohmann::json::array();
  for (const auto& file : files) {
    for (const auto& f : file.findings) {
      nlohmann::json region = {{"startLine", f.start.line}, {"startColumn", f.start.column},
                               {"endLine", f.end.line}, {"endColumn", f.end.column}};
      if (!f.line_text.empty()) region["snippet"] = {{"text", f.line_text}};
      nlohmann::json result = {
          {"ruleId", f.rule},
          {"ruleIndex", index.count(f.rule) ? index[f.rule] : 0},
          {"level", sarif_level(f.severity)},
          {"message", {{"text", sentence(f.message) + (f.hint.empty() ? "" : " Fix: " + sentence(f.hint))}}},
          {"locations",
           {{{"physicalLocation",
              {{"artifactLocation", artifact_location(file.path)}, {"region", region}}}}}}};
      results.push_back(std::move(result));
    }
  }
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
             {"informationUri", "https://github.com/lwcport/lwcport"},
             {"rules", std::move(rules)}}}}},
         {"originalUriBaseIds", {{"SRCROOT", {{"uri", "file://" + uri_encode(root)}}}}},
         {"columnKind", "unicodeCodePoints"},
         {"results", std::move(results)}}}}};
  out << doc.dump(2) << '\n';
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

void write_github(std::ostream& out, const std::vector<FileReport>& files) {
  for (const auto& file : files)
    for (const auto& f : file.findings) {
      const char* command = f.severity == Severity::error ? "error" : f.severity == Severity::warning ? "warning" : "notice";
      out << fmt::format("::{} file={},line={},col={},endLine={},endColumn={},title={}::{}\n", command,
                         gh_escape(file.path, true), f.start.line, f.start.column, f.end.line, f.end.column,
                         gh_escape(f.rule, true), gh_escape(f.message + (f.hint.empty() ? "" : ". Fix: " + f.hint), false));
    }
}

}  // namespace

void write_report(std::ostream& out, const std::vector<FileReport>& files, const ReportOptions& options) {
  switch (options.format) {
    case Format::text: write_text(out, files, options); break;
    case Format::json: write_json(out, files); break;
    case Format::sarif: write_sarif(out, files, options); break;
    case Format::github: write_github(out, files); break;
  }
}

}  // namespace lwc
