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
      ctx.report(t.span(call), {{"demote", std::string(outer)}, {"op", inner}, {"fused", fused_.at(inner).get<std::string>()}});
    }
  }

 private:
  std::vector<std::string> demotes_;
  nlohmann::json fused_;  // op -> its Demote variant
};

}  // namespace

std::unique_ptr<Check> make_demote_fusion(const RuleInfo& rule) { return std::make_unique<DemoteFusion>(rule); }

}  // namespace lwc::checks
