#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "core/source.h"

namespace lwc {

enum class Severity { note, warning, error };
std::string_view severity_name(Severity s);
// Parses "note", "warning" or "error"; false for anything else.
bool parse_severity(std::string_view text, Severity& out);

// One diagnosis at a span of one file.
struct Finding {
  std::string rule;       // stable id, e.g. "lwc-primary-view"
  Severity severity = Severity::warning;
  Span span;
  std::string message;    // what is wrong and why it matters at large coordinates
  std::string hint;       // what to do about it
};

// Sorted by span, then rule id: the order every output uses.
void sort_findings(std::vector<Finding>& findings);

}  // namespace lwc
