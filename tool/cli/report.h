#pragma once
#include <map>
#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/finding.h"
#include "core/unit_counts.h"
#include "core/source.h"

namespace lwc {

// JSON text of a value; bytes in its strings that are not UTF-8 become U+FFFD (a source or a path
// may hold any bytes: output must never abort on them).
std::string json_text(const nlohmann::json& value, int indent = -1);

struct ReportedEdit {
  Position start, end;
  std::string text;  // with the file's line endings
  std::string path = "";  // another file than the finding's, "" for its own
};

struct ReportedFix {
  std::string title;
  Applicability applicability;
  std::string reason;
  std::string strategy;
  std::vector<ReportedEdit> edits;
  std::vector<std::string> library, notes;
};

// A finding with its positions resolved, so the source can be dropped before output.
struct ReportedFinding {
  std::string rule;
  Severity severity;
  std::string message;
  std::string hint;
  Position start, end;
  // The start line, for carets and snippets; a long line only around the finding (kMaxLineShown
  // bytes), from column line_column, cut before and/or after.
  std::string line_text;
  int line_column = 1;
  bool cut_before = false, cut_after = false;
  std::optional<ReportedFix> fix;
  std::string decision;
  bool not_needed = false;
  std::vector<std::string> withheld;  // rewrites not offered, each with why
  std::map<std::string, std::string> facts;  // what the check recognised (Finding::facts)
  std::string text;         // the span's text, blanks collapsed (project/baseline.h)
  std::string fingerprint;  // its identity across edits (add_fingerprints)
  int occurrence = 0;       // which finding of its rule and text in the file it is
  std::string line_hash;    // GitHub's primaryLocationLineHash of its line, for SARIF
};

struct FileReport {
  std::string path;
  std::vector<ReportedFinding> findings;
  bool has_code = true;  // false: a script with no GLSL in it, not counted as a linted file
  int added_suppressions = 0;  // lint --add-suppressions: lines given a suppression comment
  std::string era{};  // what its code is written for (rules/analyze.h: file_era)
};

// `other`: the file an edit of another file (Edit::path) is in, to place it; none for shader code.
ReportedFinding locate(const Source& source, const Finding& finding,
                       const std::function<const Source*(const std::string&)>& other = nullptr);
// Gives each finding of a file its fingerprint (rule, text, occurrence) and, when asked, the
// line hash GitHub code scanning computes for its start line.
void add_fingerprints(FileReport& report, const Source& source, bool line_hashes);
// The JSON form of one finding (docs/json-output.md), shared by --format json and the goldens.
nlohmann::json finding_json(const ReportedFinding& f);
// The finding a finding_json() object describes (the report reads `lwcport host`'s findings so).
ReportedFinding finding_from_json(const nlohmann::json& j);

enum class Format { text, json, sarif, github };

struct ReportOptions {
  Format format = Format::text;
  bool color = false;
  bool explain = false;     // text: print each scene decision with its numbers
  bool statistics = false;  // text or json: per-rule counts instead of each finding
  std::string working_dir;  // absolute, for SARIF's base URI
  std::string help_uri_base;  // where the rule pages are ("" for the installed pages): SARIF's helpUri
  std::optional<UnitCounts> units;  // `lwcport host`: its translation units, counted in the summary
};

// Writes a report file by file, in the order given, so no run holds every finding at once.
class ReportWriter {
 public:
  ReportWriter(std::ostream& out, ReportOptions options);
  void file(const FileReport& report);
  void finish();
  bool failed(Severity threshold) const;  // a finding at or above the threshold was written

 private:
  void begin();
  void write_statistics();
  nlohmann::json units_json() const;
  std::string units_line() const;
  struct RuleCount {
    size_t findings = 0, safe = 0, unsafe = 0;
  };
  std::map<std::string, RuleCount> per_rule_;
  std::ostream& out_;
  ReportOptions options_;
  size_t files_ = 0, errors_ = 0, warnings_ = 0, notes_ = 0;
  int worst_ = -1;  // the most severe finding that counts towards failing (not-needed ones do not)
  bool first_ = true;
};

}  // namespace lwc
