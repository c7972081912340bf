// lwc-missing-precise: error-free transformations (TwoSum, Fast2Sum, the Dekker split,
// TwoProduct) whose temporaries are not `precise`. They are recognised by their structure: an
// error term that is exactly zero in real arithmetic once its temporaries are expanded (`b - (s -
// a)` with `s = a + b`), which is what an optimiser that reassociates floats folds away (lavapipe
// does, and the low word becomes 0). A high/low difference of two pairs is reported too, as a
// warning: it is not error-free, but reassociating it loses the low words.
#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>

#include <fmt/format.h>

#include "rules/checks/util.h"

namespace lwc::checks {
namespace {

// A value as a polynomial over the atoms it reads: monomial (atoms joined by '*', "" for the
// constant) -> coefficient. Exact for the sums, differences and products EFTs are made of.
using Poly = std::map<std::string, double>;

constexpr size_t kMaxTerms = 32;
constexpr int kMaxExpansions = 16;

bool is_zero(const Poly& p) {
  return std::all_of(p.begin(), p.end(), [](const auto& t) { return t.second == 0; });
}

// Adds `scale * p`; true when a term that reads an input cancels (`(a + b) - a`): an error term
// cancels inputs, while a blend whose weight is a constant 0 (`c * (1 - 1) + 0`) cancels numbers only.
bool add_to(Poly& into, const Poly& p, double scale) {
  bool cancelled = false;
  for (const auto& [m, c] : p) {
    double& slot = into[m];
    slot += scale * c;
    if (slot == 0) {
      cancelled |= !m.empty();
      into.erase(m);
    }
  }
  return cancelled;
}

std::string times(const std::string& a, const std::string& b) {
  if (a.empty()) return b;
  if (b.empty()) return a;
  std::vector<std::string> atoms;
  for (const std::string* s : {&a, &b}) {
    size_t i = 0;
    while (i <= s->size()) {
      size_t j = s->find('*', i);
      if (j == std::string::npos) j = s->size();
      atoms.push_back(s->substr(i, j - i));
      i = j + 1;
    }
  }
  std::sort(atoms.begin(), atoms.end());
  std::string out;
  for (const std::string& x : atoms) out += (out.empty() ? "" : "*") + x;
  return out;
}

std::optional<Poly> multiply(const Poly& a, const Poly& b) {
  if (a.size() * b.size() > kMaxTerms) return std::nullopt;
  Poly out;
  for (const auto& [ma, ca] : a)
    for (const auto& [mb, cb] : b) add_to(out, Poly{{times(ma, mb), ca * cb}}, 1);
  return out;
}

std::optional<double> number(std::string_view text) {
  std::string s(text);
  while (!s.empty() && (s.back() == 'f' || s.back() == 'F' || s.back() == 'h' || s.back() == 'H' || s.back() == 'l' ||
                        s.back() == 'L'))
    s.pop_back();
  char* end = nullptr;
  double v = std::strtod(s.c_str(), &end);
  if (s.empty() || *end) return std::nullopt;
  return v;
}

class MissingPrecise : public Check {
 public:
  explicit MissingPrecise(const RuleInfo& rule)
      : wrappers_(string_list(rule.data, "precise-wrappers")),
        precise_ops_(rule.data.at("precise-operations").get<std::map<std::string, std::string, std::less<>>>()),
        split_constants_(string_list(rule.data, "split-constants")),
        high_(string_list(rule.data, "high-names")),
        low_(string_list(rule.data, "low-names")),
        fma_(string_list(rule.data, "fma")) {}

  void run(const CheckContext& ctx) const override {
    const SyntaxTree& t = ctx.tree;
    Definitions defs = collect_definitions(ctx);
    std::vector<uint8_t> flags = subtree_flags(ctx, defs);
    std::string no_precise = glsl_version_without_precise(t);
    std::set<int> reported_results;
    std::vector<Span> reported;
    // The sums, differences and calls, in source order (what is reported first covers what it holds).
    for (int id : nodes_of(t, {"binary_expression", "call_expression"})) {
      bool candidate = (t.is(id, "binary_expression") && (op(t, id) == "+" || op(t, id) == "-")) ||
                       (t.is(id, "call_expression") && (matches_any(fma_, call_name(t, id)) || precise_call(t, id)));
      if (!candidate) continue;
      if (std::any_of(reported.begin(), reported.end(), [&](Span s) { return s.begin <= t.at(id).begin && t.at(id).end <= s.end; }))
        continue;
      Transformation eft = recognise(ctx, defs, flags, id);
      if (eft.name.empty() || wrapped(t, id)) continue;
      reported.push_back(t.span(id));
      int result = result_variable(ctx, id);
      if (result >= 0 && !reported_results.insert(result).second) continue;
      std::vector<int> vars = eft.temporaries;
      if (result >= 0 && std::find(vars.begin(), vars.end(), result) == vars.end()) vars.push_back(result);
      std::vector<std::string> missing;
      std::vector<Edit> edits;  // `precise ` before each declaration that lacks it
      for (int var : vars) {
        const Variable& v = ctx.world.variables()[var];
        if (v.role != Variable::Role::local || v.precise || precise_definition(ctx, defs, var)) continue;
        missing.push_back("`" + v.name + "`");
        if (v.declaration < 0) continue;
        Edit e{{t.at(v.declaration).begin, t.at(v.declaration).begin}, "precise "};
        if (std::find(edits.begin(), edits.end(), e) == edits.end()) edits.push_back(e);
      }
      std::string where;
      if (result < 0 && t.ancestor(id, "return_statement") >= 0 && !precise_call(t, id))
        where = "it is computed in a return expression, with no precise temporary";
      if (missing.empty() && where.empty()) continue;
      std::string names;
      for (size_t i = 0; i < missing.size(); ++i) names += (i ? ", " : "") + missing[i];
      Finding& f = ctx.report(t.span(id), {{"eft", eft.name}, {"names", names.empty() ? where : "not precise: " + names}});
      if (!eft.error_free) f.severity = Severity::warning;
      else f.facts["error-free"] = eft.operation;
      if (!no_precise.empty()) {
        f.withheld.push_back(fmt::format(
            "GLSL {} has no `precise` (it arrived in GLSL 4.00 and ES 3.20; WebGL has none, nor SPIR-V NoContraction through "
            "it): keep the transformation on the host (upload high/low pairs split in double precision), or raise the `#version`",
            no_precise));
        continue;
      }
      // A transformation inside a return expression has no temporary to qualify: no fix.
      if (where.empty()) ctx.fix(f, "precise", {{"names", names}}, std::move(edits));
    }
  }

 private:
  // Per local variable, its plain assignments (`x = ...`, initialiser first) and every other
  // write (`x += ...`, `x++`): a value is expanded only through an assignment no write follows.
  struct Definitions {
    std::map<int, std::vector<std::pair<int, int>>> assigned;  // var -> (node, value), in order
    std::map<int, std::vector<int>> mutated;                   // var -> nodes
  };

  static std::string_view op(const SyntaxTree& t, int n) {
    int o = t.child_by_field(n, "operator");
    return o >= 0 ? t.text(o) : std::string_view();
  }
  static int strip(const SyntaxTree& t, int n) {
    while (n >= 0 && t.is(n, "parenthesized_expression")) n = t.named_child(n);
    return n;
  }

  static Definitions collect_definitions(const CheckContext& ctx) {
    const SyntaxTree& t = ctx.tree;
    Definitions d;
    for (size_t var = 0; var < ctx.world.variables().size(); ++var) {
      const Variable& v = ctx.world.variables()[var];
      if (v.init >= 0) d.assigned[static_cast<int>(var)].emplace_back(v.decl, v.init);
    }
    for (int a : nodes_of(t, {"assignment_expression", "update_expression"})) {
      bool assign = t.is(a, "assignment_expression");
      int target = strip(t, t.child_by_field(a, assign ? "left" : "argument"));
      int var = target >= 0 && t.is(target, "identifier") ? ctx.world.variable_at(target) : -1;
      if (var < 0) continue;
      if (assign && op(t, a) == "=") d.assigned[var].emplace_back(a, t.child_by_field(a, "right"));
      else d.mutated[var].push_back(a);
    }
    for (auto& [var, list] : d.assigned) std::sort(list.begin(), list.end());
    return d;
  }

  // The value a variable holds at node `at`: its latest plain assignment before `at` in the same
  // function, when nothing else writes it in between; else -1.
  static int value_at(const CheckContext& ctx, const Definitions& d, int var, int at) {
    const SyntaxTree& t = ctx.tree;
    auto it = d.assigned.find(var);
    if (it == d.assigned.end()) return -1;
    int fn = t.ancestor(at, "function_definition");
    int node = -1, value = -1;
    for (auto [n, v] : it->second) {
      if (n >= at) break;
      if (t.ancestor(n, "function_definition") != fn) continue;
      node = n;
      value = v;
    }
    if (value < 0) return -1;
    if (auto m = d.mutated.find(var); m != d.mutated.end())
      for (int w : m->second)
        if (w > node && w < at) return -1;
    return value;
  }

  bool precise_call(const SyntaxTree& t, int call) const {
    if (!t.is(call, "call_expression")) return false;
    std::string_view name = call_name(t, call);
    return matches_any(wrappers_, name) || precise_ops_.contains(name);
  }

  // A variable whose value is computed by a precise helper (`S = INVARIANT_ADD(a, b)`).
  bool precise_definition(const CheckContext& ctx, const Definitions& d, int var) const {
    auto it = d.assigned.find(var);
    if (it == d.assigned.end() || it->second.empty()) return false;
    return std::all_of(it->second.begin(), it->second.end(), [&](auto nv) { return precise_call(ctx.tree, strip(ctx.tree, nv.second)); });
  }

  struct Evaluation {
    std::vector<int> expanded;  // variables whose values were substituted
    bool fma = false, split = false, product = false;
    bool rounded = false;  // a substituted value combined two inputs
    bool reused = false;   // a temporary was substituted twice: TwoSum recovers both inputs from one
    bool integer = false;  // a substituted variable is not a float: integers do not round
    bool cancelled = false;  // a term reading an input cancelled (add_to)
    int budget = kMaxExpansions;
  };

  // The polynomial an expression computes; `expand` substitutes variables by their values.
  std::optional<Poly> evaluate(const CheckContext& ctx, const Definitions& d, int n, bool expand, Evaluation& e) const {
    const SyntaxTree& t = ctx.tree;
    n = strip(t, n);
    if (n < 0) return std::nullopt;
    std::string_view type = t.at(n).type;
    if (type == "number_literal") {
      auto v = number(t.text(n));
      if (!v) return std::nullopt;
      return Poly{{"", *v}};
    }
    if (type == "identifier") {
      int var = ctx.world.variable_at(n);
      if (expand && var >= 0 && e.budget > 0) {
        int value = value_at(ctx, d, var, n);
        if (value >= 0) {
          --e.budget;
          if (std::find(e.expanded.begin(), e.expanded.end(), var) == e.expanded.end()) e.expanded.push_back(var);
          else e.reused = true;
          if (integer_type(ctx.world.variables()[var].type)) e.integer = true;
          auto v = evaluate(ctx, d, value, expand, e);
          // A value combining two inputs was rounded when it was stored: what an EFT recovers.
          if (v && std::count_if(v->begin(), v->end(), [](const auto& term) { return !term.first.empty(); }) >= 2) e.rounded = true;
          return v;
        }
      }
      return Poly{{std::string(t.text(n)), 1}};
    }
    if (type == "field_expression") return Poly{{std::string(t.text(n)), 1}};
    if (type == "unary_expression") {
      std::string_view o = op(t, n);
      if (o != "-" && o != "+") return std::nullopt;
      auto v = evaluate(ctx, d, t.child_by_field(n, "argument"), expand, e);
      if (!v) return std::nullopt;
      Poly out;
      e.cancelled |= add_to(out, *v, o == "-" ? -1 : 1);
      return out;
    }
    if (type == "cast_expression") return evaluate(ctx, d, t.child_by_field(n, "value"), expand, e);
    if (type == "binary_expression") {
      std::string_view o = op(t, n);
      if (o != "+" && o != "-" && o != "*") return std::nullopt;
      int left = t.child_by_field(n, "left"), right = t.child_by_field(n, "right");
      auto a = evaluate(ctx, d, left, expand, e);
      auto b = a ? evaluate(ctx, d, right, expand, e) : std::nullopt;
      if (!b) return std::nullopt;
      if (o == "*") return product(t, left, right, *a, *b, e);
      Poly out = *a;
      e.cancelled |= add_to(out, *b, o == "-" ? -1 : 1);
      return out;
    }
    if (type == "call_expression") {
      std::string name(call_name(t, n));
      auto args = call_arguments(t, n);
      std::string_view as = matches_any(fma_, name) ? "fma" : precise_op(name);
      if (as.empty() && matches_any(wrappers_, name)) as = "same";
      if (as.empty() && d_cast(name) && args.size() == 1) as = "same";
      if (as == "same" && args.size() == 1) return evaluate(ctx, d, args[0], expand, e);
      if ((as == "add" || as == "subtract" || as == "multiply") && args.size() == 2) {
        auto a = evaluate(ctx, d, args[0], expand, e);
        auto b = a ? evaluate(ctx, d, args[1], expand, e) : std::nullopt;
        if (!b) return std::nullopt;
        if (as == "multiply") return product(t, args[0], args[1], *a, *b, e);
        Poly out = *a;
        e.cancelled |= add_to(out, *b, as == "subtract" ? -1 : 1);
        return out;
      }
      if (as == "fma" && args.size() == 3) {
        e.fma = true;
        auto a = evaluate(ctx, d, args[0], expand, e);
        auto b = a ? evaluate(ctx, d, args[1], expand, e) : std::nullopt;
        auto c = b ? evaluate(ctx, d, args[2], expand, e) : std::nullopt;
        if (!c) return std::nullopt;
        auto ab = multiply(*a, *b);
        if (!ab) return std::nullopt;
        e.cancelled |= add_to(*ab, *c, 1);
        return ab;
      }
    }
    return std::nullopt;
  }

  std::optional<Poly> product(const SyntaxTree& t, int left, int right, const Poly& a, const Poly& b, Evaluation& e) const {
    auto constant = [](const Poly& p) { return p.size() == 1 && p.begin()->first.empty(); };
    if (constant(a) || constant(b)) {
      if (matches_any(split_constants_, t.text(strip(t, left))) || matches_any(split_constants_, t.text(strip(t, right)))) e.split = true;
    } else {
      e.product = true;
    }
    return multiply(a, b);
  }

  static bool integer_type(std::string_view type) {
    for (std::string_view prefix : {"int", "uint", "bool", "min16int", "min16uint", "ivec", "uvec", "bvec", "dword"})
      if (type.rfind(prefix, 0) == 0) return true;
    return false;
  }

  static bool d_cast(std::string_view name) {
    return name == "float" || name == "half" || name == "double" || name == "float2" || name == "float3" ||
           name == "float4" || name == "vec2" || name == "vec3" || name == "vec4";
  }

  struct Transformation {
    std::string name;        // empty: not one
    bool error_free = true;  // false for a high/low difference
    std::vector<int> temporaries;
    std::string operation;   // what an error-free one computes exactly: "sum", "fast-sum", "product", "split"
  };

  // What a precise helper computes ("add", "subtract", ...; "" when `name` is not one).
  std::string_view precise_op(std::string_view name) const {
    auto it = precise_ops_.find(name);
    return it == precise_ops_.end() ? std::string_view() : std::string_view(it->second);
  }

  // Cheap necessary conditions for an error term, per node over its subtree, worked out once per
  // file: a subtraction (`-` or a precise subtract helper), and a local whose value can be
  // substituted (else expanding changes nothing and the term cannot cancel).
  enum : uint8_t { kSubtracts = 1, kSubstitutable = 2 };
  std::vector<uint8_t> subtree_flags(const CheckContext& ctx, const Definitions& d) const {
    const SyntaxTree& t = ctx.tree;
    std::vector<uint8_t> flags(t.nodes.size(), 0);
    std::vector<bool> assigned(ctx.world.variables().size(), false);  // d.assigned's keys, asked of every identifier
    for (const auto& [var, list] : d.assigned) assigned[var] = true;
    for (int n = static_cast<int>(t.nodes.size()) - 1; n >= 0; --n) {  // children come after their parent
      if (!t.at(n).named && t.text(n) == "-") flags[n] |= kSubtracts;
      if (t.is(n, "call_expression") && precise_op(call_name(t, n)) == "subtract") flags[n] |= kSubtracts;
      if (t.is(n, "identifier")) {
        int var = ctx.world.variable_at(n);
        if (var >= 0 && assigned[var]) flags[n] |= kSubstitutable;
      }
      if (int parent = t.at(n).parent; parent >= 0) flags[parent] |= flags[n];
    }
    return flags;
  }

  // An error term: zero as written only once its temporaries are expanded. Or a high/low
  // difference of two pairs.
  Transformation recognise(const CheckContext& ctx, const Definitions& d, const std::vector<uint8_t>& flags, int id) const {
    const SyntaxTree& t = ctx.tree;
    Evaluation as_written;
    bool may_cancel = flags[id] == (kSubtracts | kSubstitutable);
    auto written = may_cancel ? evaluate(ctx, d, id, false, as_written) : std::nullopt;
    if (written && !is_zero(*written)) {
      Evaluation e;
      auto expanded = evaluate(ctx, d, id, true, e);
      bool rounds = e.rounded || e.split || e.product || e.fma;
      if (expanded && is_zero(*expanded) && e.cancelled && !e.expanded.empty() && rounds && !e.integer) {
        std::string name = e.fma || e.product ? "TwoProduct" : e.split ? "Dekker split" : e.reused ? "TwoSum" : "Fast2Sum";
        std::string operation = e.fma || e.product ? "product" : e.split ? "split" : e.reused ? "sum" : "fast-sum";
        return {name + " error term", true, e.expanded, operation};
      }
    }
    if (t.is(id, "binary_expression") && op(t, id) == "+") {
      // (xHigh - yHigh) + (xLow - yLow): a camera-relative subtract of two high/low pairs.
      int left = strip(t, t.child_by_field(id, "left")), right = strip(t, t.child_by_field(id, "right"));
      auto definition = [&](int n, std::vector<int>& temps) {
        if (n >= 0 && t.is(n, "identifier")) {
          int var = ctx.world.variable_at(n);
          int value = var >= 0 ? value_at(ctx, d, var, n) : -1;
          if (value >= 0) {
            temps.push_back(var);
            return strip(t, value);
          }
        }
        return n;
      };
      std::vector<int> temps;
      int a = definition(left, temps), b = definition(right, temps);
      if (difference_of(t, a, high_) && difference_of(t, b, low_)) return {"high/low difference", false, temps, ""};
    }
    return {};
  }

  // `xHigh - yHigh` (by the word names end with).
  static bool difference_of(const SyntaxTree& t, int n, const std::vector<std::string>& globs) {
    if (n < 0 || !t.is(n, "binary_expression") || op(t, n) != "-") return false;
    auto last = [&](const char* field) {
      int c = strip(t, t.child_by_field(n, field));
      std::string_view s = c >= 0 ? t.text(c) : std::string_view();
      size_t dot = s.rfind('.');
      return dot == std::string_view::npos ? s : s.substr(dot + 1);
    };
    return matches_any(globs, last("left")) && matches_any(globs, last("right"));
  }

  bool wrapped(const SyntaxTree& t, int id) const {
    for (int a = t.at(id).parent; a >= 0; a = t.at(a).parent) {
      if (precise_call(t, a)) return true;
      std::string_view type = t.at(a).type;
      if (type == "expression_statement" || type == "declaration" || type == "return_statement") return false;
    }
    return false;
  }

  // The variable the transformation's value is stored in: a declaration's or an assignment's.
  static int result_variable(const CheckContext& ctx, int id) {
    const SyntaxTree& t = ctx.tree;
    for (int a = t.at(id).parent; a >= 0; a = t.at(a).parent) {
      std::string_view type = t.at(a).type;
      if (type == "init_declarator") {
        return ctx.world.variable_declared_at(t.child_by_field(a, "declarator"));
      }
      if (type == "assignment_expression") {
        int left = strip(t, t.child_by_field(a, "left"));
        while (left >= 0 && t.is(left, "field_expression")) left = t.child_by_field(left, "argument");
        return left >= 0 ? ctx.world.variable_at(left) : -1;
      }
      if (type == "expression_statement" || type == "return_statement" || type == "compound_statement") return -1;
    }
    return -1;
  }

  std::vector<std::string> wrappers_;
  std::map<std::string, std::string, std::less<>> precise_ops_;  // helper name -> "add" | "subtract" | "multiply" | "fma"
  std::vector<std::string> split_constants_, high_, low_, fma_;
};

}  // namespace

std::unique_ptr<Check> make_missing_precise(const RuleInfo& rule) { return std::make_unique<MissingPrecise>(rule); }

}  // namespace lwc::checks
