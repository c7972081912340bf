// lwc-primary-view: `View.<member>` for a world-space member that UE5 moved to PrimaryView.
#include "rules/checks/util.h"

namespace lwc::checks {
namespace {

class PrimaryView : public Check {
 public:
  explicit PrimaryView(const RuleInfo& rule)
      : members_(string_list(rule.data, "members")), twins_(rule.data.value("translated-twins", nlohmann::json::object())) {}

  void run(const CheckContext& ctx) const override {
    const SyntaxTree& t = ctx.tree;
    for (int id : nodes_of(t, "field_expression")) {
      int base = t.child_by_field(id, "argument");
      int field = t.child_by_field(id, "field");
      if (base < 0 || field < 0 || !t.is(base, "identifier") || t.text(base) != "View") continue;
      // A local or parameter that happens to be called View is not Unreal's view.
      int var = ctx.world.variable_at(base);
      if (var >= 0 && ctx.world.variables()[var].role != Variable::Role::global) continue;
      std::string member(t.text(field));
      if (!matches_any(members_, member)) continue;
      std::string twin = twins_.value(member, "");
      Vars vars{{"member", member}, {"twin", twin.empty() ? "" : " (or, better, its translated twin `" + twin + "`)"}};
      Finding& f = ctx.report(t.span(id), vars);
      ctx.fix(f, "primary-view", vars, {{t.span(base), "PrimaryView"}});
    }
  }

 private:
  std::vector<std::string> members_;
  nlohmann::json twins_;
};

}  // namespace

std::unique_ptr<Check> make_primary_view(const RuleInfo& rule) { return std::make_unique<PrimaryView>(rule); }

}  // namespace lwc::checks
