#include "core/finding.h"

#include <algorithm>
#include <tuple>

namespace lwc {

std::string_view severity_name(Severity s) {
  switch (s) {
    case Severity::note: return "note";
    case Severity::warning: return "warning";
    case Severity::error: return "error";
  }
  return "warning";
}

std::string_view applicability_name(Applicability a) { return a == Applicability::safe ? "safe" : "unsafe"; }

bool parse_severity(std::string_view text, Severity& out) {
  for (Severity s : {Severity::note, Severity::warning, Severity::error}) {
    if (text == severity_name(s)) {
      out = s;
      return true;
    }
  }
  return false;
}

void sort_findings(std::vector<Finding>& findings) {
  std::stable_sort(findings.begin(), findings.end(), [](const Finding& a, const Finding& b) {
    return std::tie(a.span.begin, a.span.end, a.rule) < std::tie(b.span.begin, b.span.end, b.rule);
  });
}

std::string splice(std::string_view text, const std::vector<Edit>& edits) {
  std::string out;
  out.reserve(text.size());
  size_t at = 0;
  for (const Edit& e : edits) {
    out.append(text.substr(at, e.span.begin - at));
    out += e.text;
    at = e.span.end;
  }
  out.append(text.substr(at));
  return out;
}

}  // namespace lwc
