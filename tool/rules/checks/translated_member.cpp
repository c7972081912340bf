// lwc-translated-member: an engine member or global that UE 5.0 replaced by its translated-world
// twin (a light's position, a directional light's shadow matrices, a light function's matrix, the
// sky's camera and planet centre), read under its UE4 name. The line stops compiling in UE5; the
// rewrite reads the twin.
#include <fmt/format.h>

#include "rules/checks/util.h"

namespace lwc::checks {
namespace {

class TranslatedMember : public Check {
 public:
  explicit TranslatedMember(const RuleInfo&) {}

  void run(const CheckContext& ctx) const override {
    if (!ctx.unreal) return;
    const SyntaxTree& t = ctx.tree;
    for (int id : nodes_of(t, {"field_expression", "identifier"})) {
      if (t.is(id, "identifier") && (t.is(t.at(id).parent, "field_expression") || is_definition_name(t, id))) continue;
      std::string twin = engine_translated_twin(ctx, id);
      if (twin.empty()) continue;
      bool ue4 = ctx.unreal->era == UnrealEra::ue4;
      Vars vars{{"name", std::string(t.text(id))},
                {"twin", twin},
                {"when", ue4 ? "when this code moves to UE5" : "in " + std::string(era_name(ctx.unreal->era))},
                {"marker", ctx.unreal->era == UnrealEra::ue5_0 ? "LWCHackToFloat" : "DFHackToFloat"}};
      Finding& f = ctx.report(t.span(id), vars);
      if (ue4) {
        f.withheld.push_back(fmt::format("`{}` exists from UE 5.0: set \"unreal\" in .lwcport.json to the engine this code moves to",
                                         twin));
        continue;
      }
      offer_fix(ctx, f, id, vars);
    }
  }

 private:
  static void offer_fix(const CheckContext& ctx, Finding& f, int id, Vars vars) {
    const SyntaxTree& t = ctx.tree;
    int use = id, parent = t.at(id).parent;
    while (t.is(parent, "parenthesized_expression") || is_field_of(t, parent, use, "xyz")) use = parent, parent = t.at(use).parent;
    const std::string& twin = vars["twin"];
    std::string pre_view = vars["marker"] + "(PrimaryView.PreViewTranslation)";
    // A store into a member that has a twin (`LightData.Position = DeferredLightUniforms.Position`):
    // the whole assignment moves, from either side's finding.
    if (t.is(parent, "assignment_expression") && t.text(t.child_by_field(parent, "operator")) == "=") {
      int left = t.child_by_field(parent, "left"), right = t.child_by_field(parent, "right");
      std::string left_twin = engine_translated_twin(ctx, left), right_twin = engine_translated_twin(ctx, right);
      if (!left_twin.empty() && !right_twin.empty()) {
        vars["stored"] = left_twin;
        ctx.fix(f, "store", vars, {{t.span(left), left_twin}, {t.span(right), right_twin}});
        return;
      }
      if (left == use) {
        f.withheld.push_back(fmt::format("`{}` stores `{}`, which has no translated twin: store it in translated world (plus the pre-view "
                                         "translation), or have the host hand it over translated", t.text(id), shortened(t.text(right))));
        return;
      }
    }
    // A float4 that packs a position with a scalar (Unreal names them `XAndY`: the sky's
    // `SkyPlanetCenterAndViewHeight`): its `.xyz` is the position, its `.w` the same in both spaces.
    bool packed = twin.find("And") != std::string::npos;
    if (packed && use == id && t.is(parent, "field_expression") && t.text(t.child_by_field(parent, "field")) == "w") {
      ctx.fix(f, "packed-scalar", vars, {{t.span(id), twin}});
      return;
    }
    bool position = twin.ends_with("Position") || ctx.world.kind(use) == Kind::absolute;
    if (packed && use == id) position = false;  // the whole float4: no float3 arithmetic rebuilds it
    // A difference with a translated point: both sides in translated world.
    if (position && t.is(parent, "binary_expression") && t.text(t.child_by_field(parent, "operator")) == "-") {
      int other = t.child_by_field(parent, "left") == use ? t.child_by_field(parent, "right") : t.child_by_field(parent, "left");
      Kind kind = ctx.world.kind(other);
      if (kind == Kind::unknown && t.is(other, "identifier")) kind = ctx.world.data().named_kind(t.text(other), Kind::absolute) == Kind::translated ? Kind::translated : kind;
      // Built from a view member UE5 hands over translated under its UE4 name: UE4 had both sides
      // absolute, UE5 has both translated.
      if (translated_in_target(ctx, other)) {
        ctx.fix(f, "twin-in-place", vars, {{t.span(id), twin}});
        return;
      }
      if (kind == Kind::translated) {
        ctx.fix(f, "twin", vars, {{t.span(id), twin}});
        return;
      }
      // Another absolute point with a translated twin (the sky's camera minus its planet centre):
      // both take their twins, and the camera's translation cancels in the difference.
      while (t.is(other, "parenthesized_expression")) other = t.named_child(other);
      if (std::string other_twin = kind == Kind::absolute ? translated_twin(ctx, other) : ""; !other_twin.empty()) {
        vars["other"] = other_twin;
        ctx.fix(f, "difference", vars, {{t.span(id), twin}, {t.span(other), other_twin}});
        return;
      }
    }
    // A position anywhere else: the absolute one UE4 read, rebuilt from the twin and marked.
    if (position) {
      std::string value = packed ? twin + ".xyz" : twin;
      ctx.fix(f, "absolute", vars, {{packed ? t.span(use) : t.span(id), fmt::format("({} - {})", value, pre_view)}});
      return;
    }
    // A matrix transforming an absolute point: the point moves to translated world, marked.
    int list = t.is(parent, "argument_list") ? parent : -1;
    int call = list >= 0 ? t.at(list).parent : -1;
    auto args = call >= 0 && mul_call(t, call) == call ? call_arguments(t, call) : std::vector<int>{};
    std::string point = args.size() == 2 && args[1] == use ? position_of_homogeneous(t, args[0]) : "";
    if (!point.empty()) {
      ctx.fix(f, "matrix", vars,
              {{t.span(args[0]), fmt::format("float4({} + {}, 1)", point, pre_view)}, {t.span(id), twin}});
      return;
    }
    f.withheld.push_back(fmt::format("`{}` is used as `{}` (line {}): the code around it must move to translated world by hand",
                                     t.text(id), shortened(t.text(parent)), line_of(t, parent)));
  }
};

}  // namespace

std::unique_ptr<Check> make_translated_member(const RuleInfo& rule) { return std::make_unique<TranslatedMember>(rule); }

}  // namespace lwc::checks
