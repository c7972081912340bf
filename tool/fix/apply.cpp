#include "fix/apply.h"

#include <algorithm>
#include <map>
#include <stdexcept>

namespace lwc {

namespace {

// Two edits conflict when their spans intersect, or when both insert at the same offset (their
// order would be arbitrary).
bool conflict(const Edit& a, const Edit& b) {
  if (a.path != b.path) return false;
  if (a.span.begin == a.span.end && b.span.begin == b.span.end) return a.span.begin == b.span.begin;
  return a.span.begin < b.span.end && b.span.begin < a.span.end;
}

bool allowed(const Fix& fix, bool unsafe) { return fix.applicability == Applicability::safe || unsafe; }

}  // namespace

std::vector<const Fix*> choose_fixes(const std::vector<Finding>& findings, bool unsafe) {
  std::vector<const Fix*> chosen;
  std::vector<const Edit*> taken;
  // A fix that moves a whole chain goes before the one-line fixes it may overlap: they would make
  // it clash, and the next round's analysis of their text may no longer find the chain.
  std::vector<const Finding*> order;
  for (const Finding& f : findings) order.push_back(&f);
  std::stable_sort(order.begin(), order.end(), [](const Finding* a, const Finding* b) {
    auto size = [](const Finding* f) { return f->fixes.empty() ? size_t{0} : f->fixes.front().edits.size(); };
    return size(a) > size(b);
  });
  for (const Finding* finding : order) {
    const Finding& f = *finding;
    if (f.fixes.empty() || !allowed(f.fixes.front(), unsafe)) continue;
    const Fix& fix = f.fixes.front();
    bool clash = false;
    for (const Edit& e : fix.edits)
      for (const Edit* t : taken) clash = clash || conflict(e, *t);
    if (clash) continue;
    // Two findings may propose the very same fix (one declaration, two findings): apply it once.
    if (std::any_of(chosen.begin(), chosen.end(), [&](const Fix* c) { return c->edits == fix.edits; })) continue;
    chosen.push_back(&fix);
    for (const Edit& e : fix.edits) taken.push_back(&e);
  }
  return chosen;
}

std::string in_line_endings(const Source& source, std::string_view text) {
  std::string out;
  for (char c : text) {
    if (c == '\n' && source.uses_crlf()) out += '\r';
    out += c;
  }
  return out;
}

std::string apply_edits(const Source& source, std::vector<Edit> edits) {
  const std::string& text = source.text();
  std::sort(edits.begin(), edits.end(), [](const Edit& a, const Edit& b) {
    return a.span.begin != b.span.begin ? a.span.begin < b.span.begin : a.span.end < b.span.end;
  });
  uint32_t at = 0;
  for (Edit& e : edits) {
    if (e.span.begin < at || e.span.end < e.span.begin || e.span.end > text.size())
      throw std::invalid_argument("overlapping or out-of-range edit at byte " + std::to_string(e.span.begin));
    e.text = in_line_endings(source, e.text);
    at = e.span.end;
  }
  return splice(text, edits);
}

FixOutcome fix_source(const Source& source, const AnalyzeOptions& options, bool unsafe, int max_rounds) {
  FixOutcome outcome;
  std::vector<Finding> original;
  Source current(source.path(), source.text());
  for (int round = 0;; ++round) {
    std::vector<Finding> findings = analyze(current, options);
    if (round == 0) original = findings;
    std::vector<const Fix*> chosen = choose_fixes(findings, unsafe);
    if (chosen.empty()) {
      outcome.remaining = std::move(findings);
      break;
    }
    if (round == max_rounds) {
      outcome.converged = false;
      outcome.remaining = std::move(findings);
      break;
    }
    std::vector<Edit> edits;
    for (const Fix* fix : chosen) {
      edits.insert(edits.end(), fix->edits.begin(), fix->edits.end());
      outcome.library.insert(fix->library.begin(), fix->library.end());
    }
    outcome.applied += static_cast<int>(chosen.size());
    current = Source(source.path(), apply_edits(current, std::move(edits)));
  }
  outcome.text = current.text();
  std::map<std::pair<std::string, std::string>, int> left;
  for (const Finding& f : outcome.remaining) ++left[{f.rule, std::string(current.slice(f.span))}];
  for (const Finding& f : original)
    if (int& n = left[{f.rule, std::string(source.slice(f.span))}]; n > 0) --n;
    else ++outcome.resolved;
  return outcome;
}

}  // namespace lwc
