// lwc-translated-parameter: an absolute world position passed to an engine function whose position
// parameter UE5 takes in translated world (rules/world-space.json engine "translated-parameters").
// The call compiles in every era; from the era the function changed, it reads a point displaced by
// the camera's position. The rewrite passes the translated point.
#include <fmt/format.h>

#include "rules/checks/util.h"

namespace lwc::checks {
namespace {

class TranslatedParameter : public Check {
 public:
  explicit TranslatedParameter(const RuleInfo&) {}

  void run(const CheckContext& ctx) const override {
    if (!ctx.unreal) return;
    const SyntaxTree& t = ctx.tree;
    UnrealEra target = ctx.unreal->era;
    bool ue4_code = ctx.world.code_era() == UnrealEra::ue4;
    for (int call : nodes_of(t, "call_expression")) {
      for (int argument : call_arguments(t, call)) {
        UnrealEra from{};
        bool declared = false;
        if (translated_parameter_call(ctx, argument, &from, &declared) != call) continue;
        // UE4 code passes what UE4's engine function takes: an absolute position, whatever it is
        // called. A function whose own declaration says translated is judged by what is known.
        Kind kind = ctx.world.kind(argument);
        if (kind != Kind::absolute && !(ue4_code && !declared && kind == Kind::unknown && !named_otherwise(ctx, argument))) continue;
        // Built from a view member UE5 hands over translated (`View.TranslucencyLightingVolumeMin`):
        // in the target era the point is translated already, as the function then takes it.
        if (ue4_code && translated_in_target(ctx, argument)) continue;
        std::string argument_text = shortened(t.text(argument));
        Vars vars{{"callee", std::string(call_name(t, call))},
                  {"argument", argument_text},
                  {"what", kind == Kind::absolute ? fmt::format("`{}` is an absolute world position", argument_text)
                                                  : fmt::format("`{}` is the absolute world position UE4's function takes", argument_text)},
                  {"from", declared ? std::string("its declaration") : from == UnrealEra::ue5_0 ? "UE 5.0" : "UE 5.4"},
                  {"era", std::string(era_name(target))},
                  {"when", declared ? "as it is" : target == UnrealEra::ue4 ? "when this code moves to UE5" : "in " + std::string(era_name(target))}};
        Finding& f = ctx.report(t.span(argument), vars);
        if (target == UnrealEra::ue4) {
          f.withheld.push_back("the translated point is spelt with UE5's API: set \"unreal\" in .lwcport.json to the engine this code moves to");
          continue;
        }
        // Passing the translated point changes what a function declared so computes: unsafe.
        offer_fix(ctx, f, argument, ue4_code && !declared, vars);
      }
    }
  }

 private:
  // A value whose name says it is translated or local (`TranslatedWorldPosition`): code that
  // names its space is not taken for UE4 code passing the absolute point.
  static bool named_otherwise(const CheckContext& ctx, int argument) {
    const SyntaxTree& t = ctx.tree;
    int name = t.is(argument, "field_expression") ? t.child_by_field(argument, "field") : argument;
    if (name < 0 || !(t.is(name, "identifier") || t.is(name, "field_identifier"))) return false;
    return ctx.world.data().named_kind(t.text(name), Kind::absolute) != Kind::absolute;
  }

  // The translated point: the value's translated twin where it has one (a marker or demotion
  // around it goes too), else the absolute value plus the pre-view translation in the era's library.
  static void offer_fix(const CheckContext& ctx, Finding& f, int argument, bool ue4_code, Vars vars) {
    const SyntaxTree& t = ctx.tree;
    int value = undemoted(t, argument);
    std::string suffix = ue4_code ? "" : "-current";
    if (std::string twin = translated_twin(ctx, value); !twin.empty()) {
      vars["twin"] = twin;
      ctx.fix(f, "twin" + suffix, vars, {{t.span(argument), twin}});
      return;
    }
    std::string absolute = ue5_spelling(ctx, value);
    vars["translated"] = ctx.unreal->era == UnrealEra::ue5_0
                             ? fmt::format("LWCToFloat(LWCAdd({}, PrimaryView.PreViewTranslation))", absolute)
                             : fmt::format("DFFastToTranslatedWorld({}, PrimaryView.PreViewTranslation)", absolute);
    if (ctx.too_long(f, "translate" + suffix, vars["translated"].size())) return;
    ctx.fix(f, "translate" + suffix, vars, {{t.span(argument), vars["translated"]}});
  }
};

}  // namespace

std::unique_ptr<Check> make_translated_parameter(const RuleInfo& rule) { return std::make_unique<TranslatedParameter>(rule); }

}  // namespace lwc::checks
