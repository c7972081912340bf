// lwc-missing-precise: error-free transformations (TwoSum, Fast2Sum, Dekker split, TwoProduct,
// high/low differences) whose temporaries are not `precise`: drivers that reassociate floats
// (lavapipe does) fold them away and the low word becomes 0.
#include <algorithm>
#include <map>
#include <set>

#include "rules/checks/util.h"

namespace lwc::checks {
namespace {

class MissingPrecise : public Check {
 public:
  explicit MissingPrecise(const RuleInfo& rule)
      : wrappers_(string_list(rule.data, "precise-wrappers")),
        split_constants_(string_list(rule.data, "split-constants")),
        high_(string_list(rule.data, "high-names")),
        low_(string_list(rule.data, "low-names")),
        fma_(string_list(rule.data, "fma")) {}

  void run(const CheckContext& ctx) const override {
    const SyntaxTree& t = ctx.tree;
    Assignments assignments = collect_assignments(ctx);
    std::set<int> reported_results;
    for (int id = 0; id < static_cast<int>(t.nodes.size()); ++id) {
      std::string eft;
      std::vector<int> operands;  // identifiers whose definitions are part of the transformation
      if (t.is(id, "binary_expression")) {
        eft = binary_eft(ctx, assignments, id, operands);
      } else if (t.is(id, "call_expression") && matches_any(fma_, call_name(t, id))) {
        eft = fma_eft(ctx, assignments, id, operands);
      }
      if (eft.empty() || wrapped(t, id)) continue;
      int result = result_variable(ctx, id);
      if (result >= 0 && !reported_results.insert(result).second) continue;
      std::vector<std::string> missing;
      std::vector<Edit> edits;  // `precise ` before each declaration that lacks it
      std::set<int> seen;
      if (result >= 0) operands.push_back(-1 - result);
      auto need_precise = [&](int var) {
        const Variable& v = ctx.world.variables()[var];
        if (v.role != Variable::Role::local || v.precise) return;
        missing.push_back("`" + v.name + "`");
        if (v.declaration < 0) return;
        Edit e{{t.at(v.declaration).begin, t.at(v.declaration).begin}, "precise "};
        if (std::find(edits.begin(), edits.end(), e) == edits.end()) edits.push_back(e);
      };
      for (int o : operands) {
        int var = o < 0 ? -1 - o : ctx.world.variable_at(o);
        if (var >= 0 && seen.insert(var).second) need_precise(var);
      }
      // After a sum's or a split's middle step, the locals computed from its temporaries finish it
      // (TwoSum's error term, the split's low half): they need `precise` as much, or the last step
      // can still be folded. A high/low difference or a product ends at its result.
      if (eft != "high/low difference" && eft != "TwoProduct")
        for (int var : consumers_of(ctx, assignments, seen, t.ancestor(id, "function_definition")))
          if (seen.insert(var).second) need_precise(var);
      std::string where;
      if (result < 0 && t.ancestor(id, "return_statement") >= 0) where = "it is computed in a return expression, with no precise temporary";
      if (missing.empty() && where.empty()) continue;
      std::string names;
      for (size_t i = 0; i < missing.size(); ++i) names += (i ? ", " : "") + missing[i];
      Finding& f = ctx.report(t.span(id), {{"eft", eft}, {"names", names.empty() ? where : "not precise: " + names}});
      // A transformation inside a return expression has no temporary to qualify: no fix.
      if (where.empty()) ctx.fix(f, "precise", {{"names", names}}, std::move(edits));
    }
  }

 private:
  static int strip(const SyntaxTree& t, int n) {
    while (n >= 0 && t.is(n, "parenthesized_expression")) n = t.named_child(n);
    return n;
  }
  static std::string_view op(const SyntaxTree& t, int n) {
    int o = t.child_by_field(n, "operator");
    return o >= 0 ? t.text(o) : std::string_view();
  }
  // Per variable, its plain assignments (`x = ...`) as (assignment node, right side), in order.
  using Assignments = std::map<int, std::vector<std::pair<int, int>>>;
  static Assignments collect_assignments(const CheckContext& ctx) {
    const SyntaxTree& t = ctx.tree;
    Assignments out;
    for (int a = 0; a < static_cast<int>(t.nodes.size()); ++a) {
      if (!t.is(a, "assignment_expression") || op(t, a) != "=") continue;
      int left = t.child_by_field(a, "left");
      int var = left >= 0 ? ctx.world.variable_at(left) : -1;
      if (var >= 0) out[var].emplace_back(a, t.child_by_field(a, "right"));
    }
    return out;
  }
  // The expression a name was last given before `at` in the same function: its initialiser or
  // the latest earlier assignment.
  static int value_of(const CheckContext& ctx, const Assignments& assignments, int n, int at) {
    const SyntaxTree& t = ctx.tree;
    n = strip(t, n);
    if (n < 0 || !t.is(n, "identifier")) return n;
    int var = ctx.world.variable_at(n);
    if (var < 0) return n;
    int value = ctx.world.variables()[var].init;
    int fn = t.ancestor(at, "function_definition");
    if (auto it = assignments.find(var); it != assignments.end()) {
      for (auto [a, right] : it->second) {
        if (a >= at) break;
        if (a > fn) value = right;
      }
    }
    return strip(t, value);
  }
  static bool is_op(const SyntaxTree& t, int n, std::string_view o) {
    return n >= 0 && t.is(n, "binary_expression") && op(t, n) == o;
  }
  static std::string_view side(const SyntaxTree& t, int n, const char* field) {
    int c = strip(t, t.child_by_field(n, field));
    return c >= 0 ? t.text(c) : std::string_view();
  }

  std::string binary_eft(const CheckContext& ctx, const Assignments& assignments, int id, std::vector<int>& operands) const {
    const SyntaxTree& t = ctx.tree;
    int left = strip(t, t.child_by_field(id, "left"));
    int right = strip(t, t.child_by_field(id, "right"));
    if (left < 0 || right < 0) return {};
    if (op(t, id) == "-") {
      // x - (x - y): TwoSum's recovery step, or Dekker's split when x = C * y.
      if (is_op(t, right, "-") && side(t, right, "left") == t.text(left)) {
        operands = {left};
        int def = value_of(ctx, assignments, left, id);
        if (is_op(t, def, "*") && (matches_any(split_constants_, side(t, def, "left")) ||
                                   matches_any(split_constants_, side(t, def, "right"))))
          return "Dekker split";
        return "TwoSum";
      }
      // s - a where s = a + b: the rounding error of a sum (Fast2Sum / TwoSum).
      int def = value_of(ctx, assignments, left, id);
      if (is_op(t, def, "+") && (side(t, def, "left") == t.text(right) || side(t, def, "right") == t.text(right))) {
        operands = {left};
        return "Fast2Sum/TwoSum error term";
      }
      return {};
    }
    if (op(t, id) == "+") {
      // (xHigh - yHigh) + (xLow - yLow): a camera-relative subtract of two high/low pairs.
      int a = value_of(ctx, assignments, left, id), b = value_of(ctx, assignments, right, id);
      if (is_op(t, a, "-") && is_op(t, b, "-") && named(t, a, high_) && named(t, b, low_)) {
        operands = {left, right};
        return "high/low difference";
      }
    }
    return {};
  }

  // Both operands of a difference carry a high (or low) word name.
  static bool named(const SyntaxTree& t, int diff, const std::vector<std::string>& globs) {
    auto last = [&](const char* field) {
      std::string_view s = side(t, diff, field);
      size_t dot = s.rfind('.');
      return dot == std::string_view::npos ? s : s.substr(dot + 1);
    };
    return matches_any(globs, last("left")) && matches_any(globs, last("right"));
  }

  std::string fma_eft(const CheckContext& ctx, const Assignments& assignments, int call, std::vector<int>& operands) const {
    const SyntaxTree& t = ctx.tree;
    auto args = call_arguments(t, call);
    if (args.size() != 3) return {};
    int c = strip(t, args[2]);
    if (c < 0 || !t.is(c, "unary_expression")) return {};
    int p = strip(t, t.child_by_field(c, "argument"));
    int def = value_of(ctx, assignments, p, call);
    if (!is_op(t, def, "*")) return {};
    std::string_view x = t.text(strip(t, args[0])), y = t.text(strip(t, args[1]));
    bool same = (side(t, def, "left") == x && side(t, def, "right") == y) ||
                (side(t, def, "left") == y && side(t, def, "right") == x);
    if (!same) return {};
    if (t.is(p, "identifier")) operands = {p};
    return "TwoProduct";
  }

  // Local variables of a function whose initialiser or an assignment reads one of `vars`.
  static std::vector<int> consumers_of(const CheckContext& ctx, const Assignments& assignments, const std::set<int>& vars, int fn) {
    const SyntaxTree& t = ctx.tree;
    auto reads = [&](int expr) {
      if (expr < 0) return false;
      uint32_t end = t.at(expr).end;
      for (int n = expr; n < static_cast<int>(t.nodes.size()) && t.at(n).begin < end; ++n)
        if (t.is(n, "identifier") && vars.count(ctx.world.variable_at(n))) return true;
      return false;
    };
    std::vector<int> out;
    const auto& all = ctx.world.variables();
    for (int var = 0; var < static_cast<int>(all.size()); ++var) {
      const Variable& v = all[var];
      if (v.role != Variable::Role::local || v.function != fn || vars.count(var)) continue;
      bool consumer = reads(v.init);
      if (auto it = assignments.find(var); !consumer && it != assignments.end())
        for (auto [a, right] : it->second) consumer = consumer || reads(right);
      if (consumer) out.push_back(var);
    }
    return out;
  }

  bool wrapped(const SyntaxTree& t, int id) const {
    for (int a = t.at(id).parent; a >= 0; a = t.at(a).parent) {
      if (t.is(a, "call_expression") && matches_any(wrappers_, call_name(t, a))) return true;
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
        int d = t.child_by_field(a, "declarator");
        for (const Variable& v : ctx.world.variables())
          if (v.decl == d) return static_cast<int>(&v - ctx.world.variables().data());
        return -1;
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

  std::vector<std::string> wrappers_, split_constants_, high_, low_, fma_;
};

}  // namespace

std::unique_ptr<Check> make_missing_precise(const RuleInfo& rule) { return std::make_unique<MissingPrecise>(rule); }

}  // namespace lwc::checks
