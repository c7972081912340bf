#pragma once
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "core/source.h"

namespace lwc {

enum class Severity { note, warning, error };
std::string_view severity_name(Severity s);
// Parses "note", "warning" or "error"; false for anything else.
bool parse_severity(std::string_view text, Severity& out);

// Replace the bytes of a span (empty for an insertion) with new text. Line breaks in the text are
// written as "\n"; applying an edit converts them to the file's line ending.
struct Edit {
  Span span;
  std::string text;
  // Another file than the finding's (a host fix that also declares a member in a header); "" for
  // the finding's own file, which is every shader fix.
  std::string path = "";
  bool operator==(const Edit&) const = default;
};
// The text with the edits (sorted by begin, not overlapping) applied as written.
std::string splice(std::string_view text, const std::vector<Edit>& edits);

// Safe fixes keep the program's meaning except for the precision gained, and are applied by
// `lwcport fix`; unsafe ones may change behaviour (the reason says how) and need --unsafe-fixes.
enum class Applicability { safe, unsafe };
std::string_view applicability_name(Applicability a);

struct Fix {
  std::string title;      // what the edits do, e.g. "use `PrimaryView.WorldCameraOrigin`"
  Applicability applicability = Applicability::safe;
  std::string reason;     // why it is safe, or what may change
  std::string strategy;   // "translated", "df", or "" where the rule has one rewrite
  std::vector<Edit> edits;  // non-overlapping
  std::vector<std::string> library;  // shader-library functions the new code calls
  std::vector<std::string> notes;    // changes outside the shader (new uniforms, host code)
};

// One diagnosis at a span of one file.
struct Finding {
  std::string rule;       // stable id, e.g. "lwc-primary-view"
  Severity severity = Severity::warning;
  Span span;
  std::string message;    // what is wrong and why it matters at large coordinates
  std::string hint;       // what to do about it
  std::vector<Fix> fixes;  // candidate rewrites; after planning, at most one
  std::vector<std::string> withheld;  // rewrites considered and not offered, each "strategy: why"
  std::string decision;    // the scene planner's choice and its numbers, where the rule is scene-dependent
  bool not_needed = false;  // the scene does not need this fixed: never fails a run
  // What the check recognised, for the other faces: lwc-missing-precise's "error-free" is the
  // transformation's operation ("sum", "fast-sum", "product", "split"), which verify judges by.
  std::map<std::string, std::string> facts;
  // Where the world-space value it is about came from, nearest first: each place and what
  // happens there (world/provenance.h).
  std::vector<std::pair<Span, std::string>> related;
};

// Sorted by span, then rule id: the order every output uses.
void sort_findings(std::vector<Finding>& findings);

}  // namespace lwc
