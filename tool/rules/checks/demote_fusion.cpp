// lwc-demote-fusion: DFDemote(DFAdd(..)) where the fused DFAddDemote(..) exists.
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
      std::string fused = fused_.at(inner).get<std::string>();
      Vars vars{{"demote", std::string(outer)}, {"op", inner}, {"fused", fused}};
      Finding& f = ctx.report(t.span(call), vars);
      // The inner call's argument list is kept as written, comments and all.
      int inner_args = t.child_by_field(args[0], "arguments");
      if (inner_args >= 0) ctx.fix(f, "fuse", vars, {{t.span(call), fused + std::string(t.text(inner_args))}});
    }
  }

 private:
  std::vector<std::string> demotes_;
  nlohmann::json fused_;  // op -> its Demote variant
};

}  // namespace

std::unique_ptr<Check> make_demote_fusion(const RuleInfo& rule) { return std::make_unique<DemoteFusion>(rule); }

}  // namespace lwc::checks
