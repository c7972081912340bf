#pragma once
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "core/finding.h"
#include "core/source.h"
#include "rules/analyze.h"

namespace lwc {

// The fixes to apply, in finding order: the first fix of each finding that is allowed (safe, or
// unsafe too when asked) and whose edits overlap no edit already chosen. Overlapping ones wait
// for the next round, after the file is analysed again.
std::vector<const Fix*> choose_fixes(const std::vector<Finding>& findings, bool unsafe);

// Edit text ("\n" line breaks) as the file writes it: CRLF files get "\r\n".
std::string in_line_endings(const Source& source, std::string_view text);

// The source with the edits applied; "\n" in edit text becomes the file's line ending.
// Throws std::invalid_argument if edits overlap or fall outside the text.
std::string apply_edits(const Source& source, std::vector<Edit> edits);

struct FixOutcome {
  std::string text;              // the fixed text (equal to the input when nothing applied)
  int applied = 0;               // fixes applied over all rounds
  std::vector<Finding> remaining;  // findings of the fixed text
  std::set<std::string> library;   // shader-library functions the applied fixes call
  bool converged = true;         // false when the round limit stopped it (a fix keeps re-firing)
  // Findings of the original text the fixed text no longer has, matched by rule and the text
  // they point at: one fix may settle several (a chain moved whole), a later round's fix finish
  // what an earlier one started, and a marker a fix writes is a new finding, not an old one left.
  int resolved = 0;
};

// Analyses, applies the chosen fixes and analyses again until no fix applies (at most
// `max_rounds`). Pure, like analyze(): the caller writes the result.
FixOutcome fix_source(const Source& source, const AnalyzeOptions& options, bool unsafe, int max_rounds = 10);

}  // namespace lwc
