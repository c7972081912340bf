// lwc-demote-fusion: DFDemote(DFAdd(..)) where the fused DFAddDemote(..) exists.
#include <algorithm>

#include "rules/checks/util.h"

namespace lwc::checks {
namespace {

class DemoteFusion : public Check {
 public:
  explicit DemoteFusion(const RuleInfo& rule)
      : demotes_(string_list(rule.data, "demote")), fused_(rule.data.at("fused")) {}

  void run(const CheckContext& ctx) const override {
    const SyntaxTree& t = ctx.tree;
    for (int call : nodes_of(t, "call_expression")) {
      std::string_view outer = call_name(t, call);
      if (!matches_any(demotes_, outer)) continue;
      auto args = call_arguments(t, call);
      if (args.size() != 1 || !t.is(args[0], "call_expression")) continue;
      std::string inner(call_name(t, args[0]));
      if (!fused_.contains(inner)) continue;
      // DFMultiplyDemote has no overload taking a local-to-world matrix: a transform stays as written.
      auto inner_args_list = call_arguments(t, args[0]);
      if (std::any_of(inner_args_list.begin(), inner_args_list.end(), [&](int a) { return matrix_operand(ctx, a); })) continue;
      std::string fused = fused_.at(inner).get<std::string>();
      Vars vars{{"demote", std::string(outer)}, {"op", inner}, {"fused", fused}};
      Finding& f = ctx.report(t.span(call), vars);
      // The inner call's argument list is kept as written, comments and all.
      int inner_args = t.child_by_field(args[0], "arguments");
      if (inner_args >= 0) ctx.fix(f, "fuse", vars, {{t.span(call), fused + std::string(t.text(inner_args))}});
    }
  }

 private:
  // A matrix by its kind, or by an engine member's type (`GetPrimitiveData(Id).LocalToWorld`).
  static bool matrix_operand(const CheckContext& ctx, int arg) {
    if (is_matrix(ctx.world.kind(arg))) return true;
    Member m = member_of(ctx.tree, arg);
    if (m.empty()) return false;
    for (const auto& [owner, members] : ctx.world.data().engine_structs)
      if (auto it = members.find(m.member); it != members.end() && is_matrix(it->second.kind)) return true;
    return false;
  }

  std::vector<std::string> demotes_;
  nlohmann::json fused_;  // op -> its Demote variant
};

}  // namespace

std::unique_ptr<Check> make_demote_fusion(const RuleInfo& rule) { return std::make_unique<DemoteFusion>(rule); }

}  // namespace lwc::checks
