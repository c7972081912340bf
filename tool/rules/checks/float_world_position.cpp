// lwc-float-world-position: a float variable, field, parameter or return holding absolute world data.
// For a local initialised by a world transform it offers the rewrites: translated world (the
// variable becomes camera-relative and every use follows) and, in Unreal code, DoubleFloat.
#include <algorithm>
#include <optional>

#include <fmt/format.h>

#include "rules/checks/chain_shapes.h"
#include "rules/checks/high_low.h"
#include "rules/checks/translated_chain.h"
#include "rules/checks/util.h"

namespace lwc::checks {
namespace {

class FloatWorldPosition : public Check {
 public:
  explicit FloatWorldPosition(const RuleInfo& rule)
      : descriptions_(rule.data.at("kinds")),
        chain_(string_list(rule.data, "primitive-objects"), string_list(rule.data, "wrappers"),
               string_list(rule.data, "translation-invariant")),
        camera_{string_list(rule.data, "camera-words")} {}

  void run(const CheckContext& ctx) const override {
    std::optional<DeclaredNames> names;  // for the rewrites' new names, made at the first one
    for (const AbsoluteHolder& h : ctx.world.absolute_holders()) {
      if (h.what == AbsoluteHolder::What::parameter && never_read(ctx, h)) continue;
      std::string what = h.what == AbsoluteHolder::What::variable    ? "variable"
                         : h.what == AbsoluteHolder::What::field     ? "field"
                         : h.what == AbsoluteHolder::What::parameter ? "parameter"
                                                                     : "return value of";
      std::string kind(kind_name(h.kind));
      Finding& f = ctx.report(ctx.tree.span(h.site), {{"what", what},
                                                      {"name", h.name},
                                                      {"type", h.type.empty() ? "float" : h.type},
                                                      {"holds", descriptions_.value(kind, kind)}});
      if (!names) names.emplace(ctx.world);
      // A transform kept in a local, and a parameter of a whole program: the chain moves whole.
      if (is_matrix(h.kind) && h.what == AbsoluteHolder::What::variable && unreal_code(ctx.tree))
        offer_move(ctx, f, h, "translated-matrix", [&](int var, RewritePlan& plan) { return chain_.move_matrix(ctx, *names, var, plan, 0); });
      if (is_matrix(h.kind) && h.what == AbsoluteHolder::What::parameter && unreal_code(ctx.tree))
        offer_move(ctx, f, h, "translated-matrix", [&](int var, RewritePlan& plan) { return chain_.move_matrix_parameter(ctx, *names, var, plan, 0); });
      if (h.kind == Kind::absolute) {
        if (h.what == AbsoluteHolder::What::variable) offer_rewrites(ctx, f, h, *names);
        if (h.what == AbsoluteHolder::What::return_value) offer_function_rewrite(ctx, f, h, *names);
        if (h.what == AbsoluteHolder::What::parameter)
          offer_move(ctx, f, h, "translated-parameter", [&](int var, RewritePlan& plan) { return chain_.move_parameter(ctx, *names, var, plan, 0); });
      }
      // Every finding without a rewrite says why.
      if (f.fixes.empty() && f.withheld.empty()) f.withheld.push_back(no_rewrite_reason(ctx, h));
    }
  }

 private:
  // Why a holder no planner tried has no rewrite.
  static std::string no_rewrite_reason(const CheckContext& ctx, const AbsoluteHolder& h) {
    int var = ctx.world.variable_declared_at(h.site);
    const Variable* v = var >= 0 ? &ctx.world.variables()[var] : nullptr;
    if (h.kind == Kind::camera_offset)
      return fmt::format("translated world: `{}` holds the pre-view translation itself, which has no translated twin: the code it is "
                         "handed to must take it as a large-world value (`FDFVector3`) and add it in the DoubleFloat library", h.name);
    if (h.what == AbsoluteHolder::What::field)
      return fmt::format("translated world: `{}` is a struct field; lwcport moves locals, parameters and returns, not fields: a port moves "
                         "every store into it and every read of it together", h.name);
    if (v && v->role == Variable::Role::global)
      return fmt::format("translated world: `{}` is a global, which every function of the file may read; lwcport moves locals, "
                         "parameters and returns, not globals", h.name);
    if (is_matrix(h.kind) && !unreal_code(ctx.tree))
      return "translated world: lwcport moves world matrices to translated world in Unreal code only (its view and primitive data)";
    return fmt::format("translated world: lwcport has no rewrite for a {} of this kind", h.what == AbsoluteHolder::What::parameter ? "parameter" : "value");
  }

  // A parameter the function never reads: what its callers pass is rounded at the call (reported
  // there, where it is a variable or a member), not here.
  static bool never_read(const CheckContext& ctx, const AbsoluteHolder& h) {
    int var = ctx.world.variable_declared_at(h.site);
    return var >= 0 && ctx.world.uses(var).empty();
  }

  void offer_rewrites(const CheckContext& ctx, Finding& f, const AbsoluteHolder& h, const DeclaredNames& names) const {
    const SyntaxTree& t = ctx.tree;
    int var = ctx.world.variable_declared_at(h.site);
    if (var < 0) return;
    const Variable& v = ctx.world.variables()[var];
    bool local = v.role == Variable::Role::local && v.init >= 0;
    // A local with no value of its own may be written by a helper's `out` parameter.
    bool written = v.role == Variable::Role::local && v.init < 0;
    RewritePlan translated = local || written ? chain_.plan_translated(ctx, var, names) : withheld("not a local with a value");
    review_plan(translated);
    if (translated.blocker.empty()) {
      Fix* fix = ctx.fix(f, translated_kind(translated, "translated"), chain_vars(v.name, translated), translated.edits);
      if (fix) fix->notes = translated.notes;
    }
    // Without Unreal's view and primitive data, plain code gets the High/Low design instead.
    if (!unreal_code(t)) {
      if (!translated.blocker.empty()) offer_plain_rewrite(ctx, f, var);
      return;
    }
    if (!translated.blocker.empty()) f.withheld.push_back("translated world: " + translated.blocker);
    if (!local) return;
    RewritePlan df = plan_double_float(ctx, var);
    if (df.blocker.empty())
      ctx.fix(f, "df", {{"name", v.name}}, df.edits);
    else
      f.withheld.push_back("DoubleFloat: " + df.blocker);
  }

  // Code without Unreal's library: a local from a world-matrix uniform gets the High/Low design,
  // a stage input the translated position its previous stage now writes.
  void offer_plain_rewrite(const CheckContext& ctx, Finding& f, int var) const {
    const Variable& v = ctx.world.variables()[var];
    auto words = leading_words(ctx.tree, v.declaration);
    bool input = v.role == Variable::Role::global && !v.uniform &&
                 (std::find(words.begin(), words.end(), "in") != words.end() || std::find(words.begin(), words.end(), "varying") != words.end());
    if (!input && (v.role != Variable::Role::local || v.init < 0)) return;
    RewritePlan plan = input ? plan_translated_input(ctx, var, camera_) : plan_high_low(ctx, var, camera_);
    if (!plan.blocker.empty()) {
      f.withheld.push_back("translated world: " + plan.blocker);
    } else {
      std::string interface;
      for (const std::string& rename : plan.interface) interface += (interface.empty() ? "" : ", ") + rename;
      Fix* fix = ctx.fix(f, input ? "translated-input" : "high-low",
                         {{"name", v.name},
                          {"new-name", translated_name(v.name)},
                          {"interface", interface},
                          {"interface-change", interface.empty() ? "" : "; the stage interface changes too (" + interface + "): the next stage must follow"}},
                         plan.edits);
      if (fix) {
        fix->library = plan.library;
        fix->notes = plan.notes;
      }
    }
    f.withheld.push_back("DoubleFloat: this code has no DoubleFloat matrices to start from (the translated rewrite keeps its translations as High/Low pairs instead)");
  }

  // A place whose whole chain moves to translated world by `move` (a parameter with every caller,
  // a transform kept in a local with its uses): the fix of kind `fix`, or why not.
  template <typename Move>
  void offer_move(const CheckContext& ctx, Finding& f, const AbsoluteHolder& h, const char* fix, Move move) const {
    int var = ctx.world.variable_declared_at(h.site);
    if (var < 0) return;
    RewritePlan plan;
    std::string why = move(var, plan);
    if (why.empty()) review_plan(plan), why = plan.blocker;
    if (!why.empty()) {
      f.withheld.push_back("translated world: " + why);
      return;
    }
    const Variable& v = ctx.world.variables()[var];
    Fix* made = ctx.fix(f, translated_kind(plan, fix), chain_vars(v.name, plan), plan.edits);
    if (made) made->notes = plan.notes;
  }

  // The fix a translated plan makes: unsafe where it changes what a header's functions take (their
  // callers in other files must follow) or what the host must set (the notes say what).
  static const char* translated_kind(const RewritePlan& plan, const char* kind) {
    return !plan.helpers.empty() ? "translated-helpers" : !plan.notes.empty() ? "translated-host" : kind;
  }

  // A chain whose every use needs the absolute point back gains nothing from moving.
  static void review_plan(RewritePlan& plan) {
    if (plan.blocker.empty() && plan.bridged > 0 && plan.followed == 0)
      plan.blocker = "every use of it needs the absolute position (nothing downstream takes a translated one)";
  }

  // The words of a translated fix: the names, the header functions it changes, the bridges.
  static Vars chain_vars(const std::string& name, const RewritePlan& plan) {
    std::string bridges;
    if (plan.bridged > 0)
      bridges = fmt::format("; {} use{} that need{} the absolute position read{} it back from the translated one, rounded once as before "
                            "(`DFSubtractDemote`, `LWCSubtract` in UE 5.0-5.3)",
                            plan.bridged, plan.bridged == 1 ? "" : "s", plan.bridged == 1 ? "s" : "", plan.bridged == 1 ? "s" : "");
    return {{"name", name}, {"new-name", translated_name(name)}, {"helpers", helper_list(plan)}, {"bridges", bridges}};
  }

  static std::string helper_list(const RewritePlan& plan) {
    std::string helpers;
    for (const std::string& name : plan.helpers) helpers += (helpers.empty() ? "`" : ", `") + name + "`";
    return helpers;
  }

  // A function returning an absolute position built from translated values: it returns the
  // translated one instead, under a name that says so, and every caller in this file follows.
  void offer_function_rewrite(const CheckContext& ctx, Finding& f, const AbsoluteHolder& h, const DeclaredNames& names) const {
    const SyntaxTree& t = ctx.tree;
    int fn = h.site;
    while (fn >= 0 && !t.is(fn, "function_definition")) fn = t.at(fn).parent;
    if (fn < 0) return;
    RewritePlan plan;
    std::string new_name = translated_name(h.name);
    std::string why = chain_.translate_function(ctx, fn, new_name, names, plan, 0);
    if (why.empty()) review_plan(plan), why = plan.blocker;
    if (!why.empty()) {
      f.withheld.push_back("translated world: " + why);
      return;
    }
    Fix* fix = ctx.fix(f, translated_kind(plan, "translated"), chain_vars(h.name, plan), plan.edits);
    if (fix) fix->notes = plan.notes;
  }

  // FDFVector3 X = DFMultiply(P, M); differences become DF*Demote; anything else withholds.
  RewritePlan plan_double_float(const CheckContext& ctx, int var) const {
    const SyntaxTree& t = ctx.tree;
    const Variable& v = ctx.world.variables()[var];
    RewritePlan plan;
    if (v.type != "float3") return withheld(fmt::format("its type `{}` is not a float3 position", v.type));
    int mul = mul_call(t, v.init);
    std::string p = mul >= 0 ? position_of_homogeneous(t, call_arguments(t, mul)[0]) : "";
    if (p.empty()) return withheld(fmt::format("its value (`{}`) is not a transform of a position lwcport can redo in DoubleFloat", shortened(t.text(v.init))));
    int matrix = call_arguments(t, mul)[1];
    Member m = member_of(t, matrix);
    if (m.empty()) return withheld(fmt::format("its matrix `{}` is not a view or primitive member", shortened(t.text(matrix))));
    std::string df_matrix = (m.object == "View" ? std::string("PrimaryView") : std::string(t.text(t.child_by_field(matrix, "argument")))) + "." + m.member;
    int type = t.child_by_field(v.declaration, "type");
    if (type < 0) return withheld("its declaration has no type lwcport can rewrite");
    plan.edits.push_back({t.span(type), "FDFVector3"});
    plan.edits.push_back({t.span(v.init), fmt::format("DFMultiply({}, {})", p, df_matrix)});
    for (int use : ctx.world.uses(var)) {
      int partner = subtraction_partner(t, use);
      if (partner < 0) return withheld(escape(t, use));
      int parent = t.at(partner).parent;
      bool use_first = t.child_by_field(parent, "left") != partner;
      Member pm = member_of(t, partner);
      std::string other(t.text(partner));
      if (!pm.empty() && pm.object == "View" && ctx.world.data().twins.members.count(pm.member)) other = "PrimaryView." + pm.member;
      std::string call = use_first ? fmt::format("DFSubtractDemote({}, {})", v.name, other)
                                   : fmt::format("DFSubtractDemote({}, {})", other, v.name);
      plan.edits.push_back({t.span(parent), call});
    }
    return plan;
  }

  nlohmann::json descriptions_;  // kind -> words for the message
  TranslatedChain chain_;
  CameraNames camera_;  // plain code: which absolute uniforms are the camera
};

}  // namespace

std::unique_ptr<Check> make_float_world_position(const RuleInfo& rule) {
  return std::make_unique<FloatWorldPosition>(rule);
}

}  // namespace lwc::checks
