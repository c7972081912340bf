// lwc-fast-twosum-order: DFFastTwoSum(a, b) is exact only when |a| >= |b|; flag calls where the
// second operand is the large one (or may be) and the first is not known to be larger.
#include "rules/checks/util.h"

namespace lwc::checks {
namespace {

enum class Magnitude { small, large, unknown };

class FastTwoSumOrder : public Check {
 public:
  explicit FastTwoSumOrder(const RuleInfo& rule)
      : functions_(string_list(rule.data, "functions")),
        large_(string_list(rule.data, "large-names")),
        small_(string_list(rule.data, "small-names")) {}

  void run(const CheckContext& ctx) const override {
    const SyntaxTree& t = ctx.tree;
    for (int call : nodes_of(t, "call_expression")) {
      if (!matches_any(functions_, call_name(t, call))) continue;
      auto args = call_arguments(t, call);
      if (args.size() != 2) continue;
      Magnitude a = magnitude(ctx, args[0]), b = magnitude(ctx, args[1]);
      if (b != Magnitude::large || a == Magnitude::large) continue;
      Vars vars{{"a", std::string(t.text(args[0]))},
                {"b", std::string(t.text(args[1]))},
                {"why", a == Magnitude::small ? "is a small (relative or local) value" : "is not known to be the larger"}};
      Finding& f = ctx.report(t.span(call), vars);
      // A known-small first operand: the swapped order is guaranteed. Otherwise only TwoSum is.
      if (a == Magnitude::small)
        ctx.fix(f, "swap", vars, {{t.span(args[0]), vars["b"]}, {t.span(args[1]), vars["a"]}});
      else
        ctx.fix(f, "two-sum", vars, {{t.span(t.child_by_field(call, "function")), "DFTwoSum"}});
    }
  }

 private:
  Magnitude magnitude(const CheckContext& ctx, int node) const {
    Kind k = ctx.world.kind(node);
    if (holds_absolute(k)) return Magnitude::large;
    if (k == Kind::direction || k == Kind::local || k == Kind::translated) return Magnitude::small;
    auto path = ctx.world.path(node);
    if (!path) return Magnitude::unknown;
    std::string_view last = path->back().name;
    // "RelativeOrigin" is an offset: a small-value word outweighs a large-value one.
    if (matches_any(small_, last)) return Magnitude::small;
    if (matches_any(large_, last)) return Magnitude::large;
    return Magnitude::unknown;
  }

  std::vector<std::string> functions_, large_, small_;
};

}  // namespace

std::unique_ptr<Check> make_fast_twosum_order(const RuleInfo& rule) { return std::make_unique<FastTwoSumOrder>(rule); }

}  // namespace lwc::checks
