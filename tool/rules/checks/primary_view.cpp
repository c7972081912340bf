// lwc-primary-view: `View.<member>` (or ResolvedView's) for a world-space member that UE5 moved to PrimaryView.
#include "rules/checks/library_rewrite.h"
#include "rules/checks/util.h"

namespace lwc::checks {
namespace {

class PrimaryView : public Check {
 public:
  explicit PrimaryView(const RuleInfo& rule)
      : objects_(string_list(rule.data, "objects")),
        members_(string_list(rule.data, "members")),
        positions_(string_list(rule.data, "position-members")),
        lwc_calls_(string_list(rule.data, "lwc-calls")) {}

  void run(const CheckContext& ctx) const override {
    const SyntaxTree& t = ctx.tree;
    for (int id : nodes_of(t, "field_expression")) {
      int base = t.child_by_field(id, "argument");
      int field = t.child_by_field(id, "field");
      if (base < 0 || field < 0 || !t.is(base, "identifier") || !matches_any(objects_, t.text(base))) continue;
      // A local or parameter that happens to be called View is not Unreal's view.
      int var = ctx.world.variable_at(base);
      if (var >= 0 && ctx.world.variables()[var].role != Variable::Role::global) continue;
      std::string member(t.text(field));
      if (!matches_any(members_, member)) continue;
      const auto& twins = ctx.world.data().twins.members;
      std::string twin = twins.count(member) ? std::string(t.text(base)) + "." + twins.at(member) : "";
      Vars vars{{"object", std::string(t.text(base))}, {"member", member}, {"twin", twin.empty() ? "" : " (or, better, its translated twin `" + twin + "`)"}};
      describe_era(ctx, id, vars);
      Finding& f = ctx.report(t.span(id), vars);
      offer_fix(ctx, f, id, member, vars);
    }
  }

 private:
  // In UE 5.4 PrimaryView's world members are DoubleFloat values: the rename alone is right only
  // where LWC code already takes them; a float difference becomes its DF*Demote form.
  void offer_fix(const CheckContext& ctx, Finding& f, int id, const std::string& member, Vars vars) const {
    const SyntaxTree& t = ctx.tree;
    int parent = t.at(id).parent;
    if (t.is(parent, "argument_list") && matches_any(lwc_calls_, call_name(t, t.at(parent).parent))) {
      ctx.fix(f, "primary-view", vars, {{t.span(t.child_by_field(id, "argument")), "PrimaryView"}});
      return;
    }
    // The member as an operand: through `.xyz` (a 3-vector's own value) and parentheses.
    int use = id, above = parent;
    while (t.is(above, "parenthesized_expression") || is_field_of(t, above, use, "xyz")) use = above, above = t.at(use).parent;
    int op = t.is(above, "binary_expression") ? t.child_by_field(above, "operator") : -1;
    if (op >= 0 && (t.text(op) == "-" || t.text(op) == "+") && matches_any(positions_, member)) {
      parent = above;
      int left = t.child_by_field(parent, "left"), right = t.child_by_field(parent, "right");
      // Either operand that is a view position member (this one, or another beside it) is written
      // as UE5 spells it, so both findings of `A - B` carry the same rewrite.
      auto operand = [&](int n) {
        std::string other = view_position(ctx, n);
        return !other.empty() ? "PrimaryView." + other : std::string(t.text(n));
      };
      vars["call"] = t.text(op) == "-" ? "DFSubtractDemote" : "DFAddDemote";
      // Measured before it is written: in a long chain of sums each operand is the chain so far.
      auto operand_size = [&](int n) { return t.text(n).size() + 12; };
      if (ctx.too_long(f, "demote", vars["call"].size() + operand_size(left) + operand_size(right) + 4)) return;
      ctx.fix(f, "demote", vars, {{t.span(parent), vars["call"] + "(" + operand(left) + ", " + operand(right) + ")"}});
      return;
    }
    // A point or direction transformed by a view matrix: in the era's library, or by its twin.
    UnrealEra era = ctx.unreal ? ctx.unreal->era : UnrealEra::ue5_4;
    LibraryRewrite r = library_rewrite(ctx, {id, "PrimaryView." + member, ctx.world.kind(id), "PrimaryView", member},
                                       era != UnrealEra::ue5_0);
    if (!r.fix.empty()) {
      for (const auto& [key, text] : r.vars) vars[key] = text;
      ctx.fix(f, r.fix, vars, r.edits);
      return;
    }
    // One coordinate of a position (a height, a clamp): the absolute value is what the code
    // wants, as Epic's own port keeps it, so the era's marker gives the float value UE4 had.
    if (read_as_coordinates(t, id) && matches_any(positions_, member)) {
      vars["marker"] = era == UnrealEra::ue5_0 ? "LWCHackToFloat" : "DFHackToFloat";
      vars["use"] = shortened(t.text(parent));
      ctx.fix(f, "hack-marker", vars, {{t.span(id), vars["marker"] + "(PrimaryView." + member + ")"}});
      return;
    }
    f.withheld.push_back("in UE 5.4 `PrimaryView." + member + "` is a DoubleFloat value and this use (`" +
                         shortened(t.text(parent)) + "`) needs a float: the surrounding computation must move " +
                         "to translated world or DoubleFloat first (lwc-float-world-position)");
  }

  // The position member of the view a node is (`View.M`, `View.M.xyz`, through parentheses) as
  // its name, or "".
  std::string view_position(const CheckContext& ctx, int n) const {
    const SyntaxTree& t = ctx.tree;
    while (t.is(n, "parenthesized_expression")) n = t.named_child(n);
    n = without_xyz(t, n);
    int base = t.is(n, "field_expression") ? t.child_by_field(n, "argument") : -1;
    if (base < 0 || !t.is(base, "identifier") || !matches_any(objects_, t.text(base))) return {};
    int var = ctx.world.variable_at(base);
    if (var >= 0 && ctx.world.variables()[var].role != Variable::Role::global) return {};
    std::string member(t.text(t.child_by_field(n, "field")));
    return matches_any(positions_, member) ? member : "";
  }

  // The member's large-world type in the era the code builds against, and what that means for it.
  static void describe_era(const CheckContext& ctx, int id, Vars& vars) {
    Kind kind = ctx.world.kind(id);
    std::string shape = kind == Kind::world_matrix ? "Matrix" : kind == Kind::from_world_matrix ? "InverseMatrix" : "Vector3";
    UnrealEra era = ctx.unreal ? ctx.unreal->era : UnrealEra::ue5_4;
    std::string object = vars["object"] + "." + vars["member"];
    if (era == UnrealEra::ue4) {
      vars["era-type"] = "a tile/offset `FLWC" + shape + "` (UE 5.0-5.3) or DoubleFloat `FDF" + shape + "` (UE 5.4+)";
      vars["consequence"] = ", so `" + object + "` stops compiling when this code moves to UE5";
    } else {
      vars["era-type"] = era == UnrealEra::ue5_0 ? "a tile/offset `FLWC" + shape + "`" : "a DoubleFloat `FDF" + shape + "`";
      vars["consequence"] = ", so `" + object + "` does not compile in " + std::string(era_name(era));
    }
  }

  std::vector<std::string> objects_, members_, positions_, lwc_calls_;
};

}  // namespace

std::unique_ptr<Check> make_primary_view(const RuleInfo& rule) { return std::make_unique<PrimaryView>(rule); }

}  // namespace lwc::checks
