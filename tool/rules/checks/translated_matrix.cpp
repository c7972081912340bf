// The translated-world chain of lwc-float-world-position for transforms (translated_chain.h):
// a transform moves to translated world whole, and its uses follow.
#include <algorithm>

#include <fmt/format.h>

#include "rules/checks/chain_shapes.h"
#include "rules/checks/translated_chain.h"

namespace lwc::checks {

namespace {
// An engine transform (through a demotion or marker: `DFHackToFloat(Primitive.LocalToWorld)`) made
// translated in the era's library, as text; else "" and `why` says why not.
std::string translated_engine_transform(const CheckContext& ctx, int expression, Kind& kind, std::string& why) {
  const SyntaxTree& t = ctx.tree;
  int value = undemoted(t, expression);
  Member m = member_of(t, value);
  const WorldData::EngineMember* e = engine_member_at(ctx, value);
  bool ue5_0 = ctx.unreal->era == UnrealEra::ue5_0;
  const std::string type = e ? e->types[ue5_0 ? 1 : 2] : "";
  if (!e || !is_matrix(e->kind) || !(type.starts_with("FDF") || type.starts_with("FLWC"))) {
    why = fmt::format("its value (`{}`) is not an engine transform lwcport can move to translated world", shortened(t.text(expression)));
    return {};
  }
  kind = e->kind;
  std::string matrix = ue5_spelling(ctx, value);
  std::string translation = std::string("PrimaryView.") + (m.member.starts_with("Prev") ? "PrevPreViewTranslation" : "PreViewTranslation");
  return !ue5_0 ? fmt::format("DFFastToTranslatedWorld({}, {})", matrix, translation)
         : e->kind == Kind::world_matrix ? fmt::format("LWCMultiplyTranslation({}, {})", matrix, translation)
                                         : fmt::format("LWCMultiplyTranslation(LWCNegate({}), {})", translation, matrix);
}
}  // namespace

std::string TranslatedChain::move_matrix(const CheckContext& ctx, const DeclaredNames& names, int var, RewritePlan& plan, int depth) const {
  const SyntaxTree& t = ctx.tree;
  const Variable& v = ctx.world.variables()[var];
  if (!ctx.unreal || ctx.unreal->era == UnrealEra::ue4) return "the translated transform is made with UE5's library: set \"unreal\" to the engine this code moves to";
  if (v.role != Variable::Role::local || v.init < 0) return "not a local with a value";
  if (moving(plan, var)) return {};
  std::string new_name = translated_name(v.name);
  if (new_name == v.name || names.taken(new_name, v.function)) return fmt::format("the name `{}` is already taken", new_name);
  Kind kind = Kind::unknown;
  std::string why, call = translated_engine_transform(ctx, v.init, kind, why);
  if (call.empty()) return why;
  plan.moving_variables.push_back(var);
  plan.edits.push_back({t.span(v.init), call});
  plan.edits.push_back({t.span(v.decl), new_name});
  for (int use : ctx.world.uses(var)) {
    if (!plan.blocker.empty()) break;
    follow_matrix_use(ctx, names, use, kind, new_name, plan, depth);
  }
  return plan.blocker;
}

std::string TranslatedChain::move_matrix_parameter(const CheckContext& ctx, const DeclaredNames& names, int var, RewritePlan& plan, int depth) const {
  const SyntaxTree& t = ctx.tree;
  const Variable& p = ctx.world.variables()[var];
  if (!ctx.unreal || ctx.unreal->era == UnrealEra::ue4) return "the translated transform is made with UE5's library: set \"unreal\" to the engine this code moves to";
  if (moving(plan, var)) return {};
  if (depth > 8) return "the calls it passes through nest too deep";
  if (p.output) return fmt::format("`{}` is an `out` parameter", p.name);
  if (p.kind != Kind::world_matrix && p.kind != Kind::from_world_matrix) return fmt::format("`{}` is not a transform to or from world", p.name);
  int fn = p.function;
  std::string function(t.text(function_name(t, fn)));
  // Another file may call a header's function with an absolute transform.
  if (!whole_program(t)) return fmt::format("`{}` is a parameter of `{}`, which other files may call with an absolute transform", p.name, function);
  std::string new_name = translated_name(p.name);
  if (new_name == p.name || names.taken(new_name, fn)) return fmt::format("the name `{}` is already taken", new_name);
  size_t index = 0, arity = function_arity(t, fn);
  while (index < arity && parameter_variable(ctx, fn, index) != var) ++index;
  std::vector<int> calls = calls_to(t, fn);
  if (index == arity || calls.empty()) return fmt::format("no call in this file passes `{}`", p.name);
  plan.moving_variables.push_back(var);
  plan.edits.push_back({t.span(p.decl), new_name});
  // Each call passes a translated transform: a local or parameter that moves with it (its use
  // there is renamed as it follows), or the engine's transform made translated in place. The
  // calls go first: a call the uses below rewrite whole then carries its renamed argument.
  for (int call : calls) {
    if (!plan.blocker.empty()) break;
    int argument = call_arguments(t, call)[index];
    while (t.is(argument, "parenthesized_expression")) argument = t.named_child(argument);
    int source = t.is(argument, "identifier") ? ctx.world.variable_at(argument) : -1;
    const Variable* s = source >= 0 ? &ctx.world.variables()[static_cast<size_t>(source)] : nullptr;
    std::string why;
    if (s && s->role == Variable::Role::local && s->kind == p.kind) {
      why = move_matrix(ctx, names, source, plan, depth + 1);
    } else if (s && s->role == Variable::Role::parameter && s->kind == p.kind) {
      why = move_matrix_parameter(ctx, names, source, plan, depth + 1);
    } else if (!s) {
      Kind kind = Kind::unknown;
      std::string made = translated_engine_transform(ctx, argument, kind, why);
      if (!made.empty() && kind != p.kind) why = fmt::format("`{}` is not the same kind of transform", shortened(t.text(argument)));
      else if (!made.empty()) plan.edits.push_back({t.span(argument), made});
    } else {
      why = fmt::format("`{}` is not a transform lwcport can move with it", s->name);
    }
    if (!why.empty() && plan.blocker.empty()) plan.blocker = fmt::format("the call on line {} passes `{}`: {}", line_of(t, call), shortened(t.text(argument)), why);
  }
  for (int use : ctx.world.uses(var)) {
    if (!plan.blocker.empty()) break;
    follow_matrix_use(ctx, names, use, p.kind, new_name, plan, depth + 1);
  }
  return plan.blocker;
}

void TranslatedChain::follow_matrix_use(const CheckContext& ctx, const DeclaredNames& names, int use, Kind kind, const std::string& new_name,
                                        RewritePlan& plan, int depth) const {
  const SyntaxTree& t = ctx.tree;
  auto renamed = [&] { plan.edits.push_back({t.span(use), new_name}); };
  int parent = t.at(use).parent;
  // A row: the rotation rows are the same in translated world; a local-to-world transform's
  // translation row is the object's origin, now translated, and follows as a point.
  if (t.is(parent, "subscript_expression") && t.child_by_field(parent, "argument") == use) {
    int index = t.subscript_index(parent);
    std::string_view row = index >= 0 ? t.text(index) : "";
    if (row == "0" || row == "1" || row == "2") {
      renamed();
      return;
    }
    if (row == "3" && kind == Kind::world_matrix) {
      follow_use(ctx, names, parent, new_name + "[3]", plan, depth + 1);
      return;
    }
  }
  // The 3x3 part (rotation and scale) is the same in translated world.
  if (int cast = t.is(parent, "cast_expression") ? t.child_by_field(parent, "type") : -1; cast >= 0 && t.text(cast).ends_with("3x3")) {
    renamed();
    return;
  }
  // A transform of a point: a local-to-world one gives the translated point, which follows; a
  // world-to-local one takes the point translated. A direction (w = 0) is the same in both.
  int call = t.is(parent, "argument_list") ? t.at(parent).parent : -1;
  std::vector<int> args = call >= 0 && mul_call(t, call) == call ? call_arguments(t, call) : std::vector<int>{};
  if (args.size() == 2 && args[1] == use) {
    if (!direction_of_homogeneous(t, args[0]).empty()) {
      renamed();
      return;
    }
    std::vector<int> point = position_of_homogeneous(t, args[0]).empty() ? std::vector<int>{} : call_arguments(t, args[0]);
    if (kind == Kind::world_matrix && !point.empty()) {
      follow_use(ctx, names, call, spliced(std::string(t.text(call)), t.at(call).begin, {{t.span(use), new_name}}), plan, depth + 1);
      return;
    }
    if (kind == Kind::from_world_matrix && !point.empty()) {
      renamed();
      if (std::string why = translate_value(ctx, names, point[0], plan, depth + 1); !why.empty() && plan.blocker.empty())
        plan.blocker = fmt::format("the point `{}` it transforms (line {}): {}", shortened(t.text(point[0])), line_of(t, call), why);
      return;
    }
  }
  // Handed whole to a function of this file: its transform parameter moves with it.
  if (call >= 0 && mul_call(t, call) != call) {
    int param = parameter_of(ctx, use);
    if (param >= 0 && is_matrix(ctx.world.variables()[static_cast<size_t>(param)].kind)) {
      renamed();
      std::string why = ctx.world.variables()[static_cast<size_t>(param)].kind == kind ? move_matrix_parameter(ctx, names, param, plan, depth + 1)
                                                                                        : "it takes another kind of transform";
      if (!why.empty() && plan.blocker.empty())
        plan.blocker = fmt::format("it is passed to `{}` (line {}): {}", call_name(t, call), line_of(t, call), why);
      return;
    }
  }
  if (plan.blocker.empty()) plan.blocker = escape(t, use);
}

}  // namespace lwc::checks
