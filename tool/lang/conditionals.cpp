#include "lang/conditionals.h"

#include <algorithm>

namespace lwc {

namespace {

struct Group {
  std::vector<size_t> directives;  // token indices: #if..., #elif/#else..., #endif
  bool closed = false;
  bool has_else = false;
  std::vector<bool> zero;          // per arm: its condition is a literal 0
  size_t nesting = 0;              // groups open around it
};

// Groups nested deeper than this are read as the grammar sees them: resolving one costs a walk of
// its arms, and real code nests a handful deep, so the bound keeps the work linear in the file.
constexpr size_t kMaxResolvedNesting = 32;

std::string_view word(std::string_view text, const Token& t) { return text.substr(t.begin, t.end - t.begin); }

// `0` as the whole condition, comments aside.
bool literal_zero(std::string_view rest) {
  size_t c = std::min(rest.find("//"), rest.find("/*"));
  rest = rest.substr(0, c);
  size_t b = rest.find_first_not_of(" \t\r\n\\"), e = rest.find_last_not_of(" \t\r\n\\");
  return b != std::string_view::npos && rest.substr(b, e - b + 1) == "0";
}

}  // namespace

ConditionalPlan plan_conditionals(std::string_view text, const std::vector<Token>& tokens, int variant) {
  ConditionalPlan plan;
  const size_t n = tokens.size();
  plan.dropped.assign(n, false);

  std::vector<Group> groups;
  std::vector<size_t> open;
  bool any = false;
  for (size_t i = 0; i < n; ++i) {
    if (tokens[i].kind != Tok::directive) continue;
    Directive d = read_directive(word(text, tokens[i]));
    if (d.keyword == "if" || d.keyword == "ifdef" || d.keyword == "ifndef") {
      groups.push_back({{i}, false, false, {d.keyword == "if" && literal_zero(d.rest)}, open.size()});
      open.push_back(groups.size() - 1);
      any = true;
    } else if ((d.keyword == "elif" || d.keyword == "else") && !open.empty()) {
      Group& g = groups[open.back()];
      g.directives.push_back(i);
      g.zero.push_back(d.keyword == "elif" && literal_zero(d.rest));
      if (d.keyword == "else") g.has_else = true;
    } else if (d.keyword == "endif" && !open.empty()) {
      Group& g = groups[open.back()];
      g.directives.push_back(i);
      g.closed = true;
      open.pop_back();
    }
  }
  if (!any) return plan;

  // Per token: bracket depth before it (parentheses and square brackets), whether it lies in an
  // initialiser's braces, and the nearest code token before and after each directive.
  std::vector<int> depth(n, 0);
  std::vector<bool> in_init(n, false);
  std::vector<bool> brace_init;  // the open braces, innermost last: an initialiser's?
  int d = 0;
  std::string_view prev_word;
  for (size_t i = 0; i < n; ++i) {
    depth[i] = d;
    in_init[i] = !brace_init.empty() && brace_init.back();
    if (tokens[i].kind == Tok::directive) continue;
    std::string_view w = word(text, tokens[i]);
    if (w == "(" || w == "[") ++d;
    else if ((w == ")" || w == "]") && d > 0) --d;
    else if (w == "{") {
      bool init = prev_word == "=" || prev_word == "," || prev_word == "(" || prev_word == "return" ||
                  (prev_word == "{" && !brace_init.empty() && brace_init.back());
      brace_init.push_back(init || (!brace_init.empty() && brace_init.back()));
    } else if (w == "}" && !brace_init.empty()) {
      brace_init.pop_back();
    }
    prev_word = w;
  }
  // The nearest code token before and after each token (directives skipped), worked out once.
  std::vector<size_t> before_code(n, n), after_code(n, n);
  for (size_t i = 0, last = n; i < n; ++i) {
    before_code[i] = last;
    if (tokens[i].kind != Tok::directive) last = i;
  }
  for (size_t i = n, next = n; i-- > 0;) {
    after_code[i] = next;
    if (tokens[i].kind != Tok::directive) next = i;
  }
  auto code_before = [&](size_t i) { return before_code[i] < n ? word(text, tokens[before_code[i]]) : std::string_view(); };
  auto code_after = [&](size_t i) { return after_code[i] < n ? word(text, tokens[after_code[i]]) : std::string_view(); };
  // The grammar reads a directive between whole statements or declarations only.
  auto readable_at = [&](size_t i) {
    std::string_view before = code_before(i);
    bool boundary = before.empty() || before == ";" || before == "{" || before == "}";
    return boundary && depth[i] == 0 && !in_init[i] && code_after(i) != "else";
  };
  // Per token: the deepest group in whose second or later arm it lies (-1: none). An arm is
  // weighed with one arm of each group nested in it, the first, as one variant would see it:
  // two arms that each open a function body are one brace, not two.
  std::vector<int> later_arm(n, -1);
  for (const Group& g : groups) {
    if (!g.closed || g.nesting > kMaxResolvedNesting) continue;
    for (size_t i = g.directives[1] + 1; i < g.directives.back(); ++i)
      later_arm[i] = std::max(later_arm[i], static_cast<int>(g.nesting));
  }
  auto balanced = [&](size_t from, size_t to, size_t nesting) {
    int paren = 0, bracket = 0, brace = 0;
    for (size_t i = from + 1; i < to; ++i) {
      if (tokens[i].kind != Tok::punct || later_arm[i] > static_cast<int>(nesting)) continue;
      std::string_view w = word(text, tokens[i]);
      paren += w == "(" ? 1 : w == ")" ? -1 : 0;
      bracket += w == "[" ? 1 : w == "]" ? -1 : 0;
      brace += w == "{" ? 1 : w == "}" ? -1 : 0;
      if (paren < 0 || bracket < 0 || brace < 0) return false;
    }
    return paren == 0 && bracket == 0 && brace == 0;
  };

  for (const Group& g : groups) {
    if (!g.closed || g.nesting >= kMaxResolvedNesting) continue;
    bool resolve = std::find(g.zero.begin(), g.zero.end(), true) != g.zero.end();
    for (size_t k = 0; k < g.directives.size() && !resolve; ++k) resolve = !readable_at(g.directives[k]);
    for (size_t k = 0; k + 1 < g.directives.size() && !resolve; ++k) resolve = !balanced(g.directives[k], g.directives[k + 1], g.nesting);
    if (!resolve) continue;
    size_t arms = g.directives.size() - 1;
    std::vector<size_t> choices;
    for (size_t k = 0; k < arms; ++k)
      if (!g.zero[k]) choices.push_back(k);
    if (!g.has_else) choices.push_back(arms);  // the empty arm of an absent #else
    if (choices.empty()) choices.push_back(arms);
    plan.variants = std::max(plan.variants, std::min<int>(kMaxVariants, static_cast<int>(choices.size())));
    size_t keep = choices[std::min<size_t>(static_cast<size_t>(variant), choices.size() - 1)];
    for (size_t k = 0; k < g.directives.size(); ++k) plan.dropped[g.directives[k]] = true;
    for (size_t k = 0; k < arms; ++k)
      if (k != keep)
        for (size_t i = g.directives[k] + 1; i < g.directives[k + 1]; ++i) plan.dropped[i] = true;
    // With one arm live in every variant, only the dead arms and the directives differ from
    // the code as compiled: a rewrite inside the live arm fits every variant.
    if (choices.size() == 1 && keep < arms) {
      plan.regions.push_back({tokens[g.directives.front()].begin, tokens[g.directives[keep]].end});
      plan.regions.push_back({tokens[g.directives[keep + 1]].begin, tokens[g.directives.back()].end});
    } else {
      plan.regions.push_back({tokens[g.directives.front()].begin, tokens[g.directives.back()].end});
      if (keep < arms) plan.kept_arms.push_back({tokens[g.directives[keep]].end, tokens[g.directives[keep + 1]].begin});
    }
  }
  return plan;
}

}  // namespace lwc
