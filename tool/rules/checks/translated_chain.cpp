// The translated-world chain of lwc-float-world-position (translated_chain.h).
#include "rules/checks/translated_chain.h"

#include <algorithm>
#include <cctype>

#include <fmt/format.h>

#include "rules/checks/chain_shapes.h"

namespace lwc::checks {
namespace {

// The most callers a function split tries (split_function).
constexpr size_t kMaxSplitCallers = 32;

}  // namespace

namespace {
// A call (or its `.xyz`) of an engine function that returns a large-world position in the era the
// code moves to, which the file does not define: that value made translated in the era's library
// (`DFFastToTranslatedWorld`; the tile/offset sum in UE 5.0-5.3); else "".
std::string engine_position_to_translated(const CheckContext& ctx, int value) {
  const SyntaxTree& t = ctx.tree;
  if (!ctx.unreal || ctx.unreal->era == UnrealEra::ue4) return {};
  int call = without_xyz(t, value);
  if (!t.is(call, "call_expression")) return {};
  std::string name(call_name(t, call));
  const auto& types = ctx.world.data().engine_function_types;
  auto entry = types.find(name);
  bool ue5_0 = ctx.unreal->era == UnrealEra::ue5_0;
  if (entry == types.end() || defines_function(t, name) || ctx.world.kind(call) != Kind::absolute) return {};
  const std::string& type = entry->second[ue5_0 ? 1 : 2];
  if (!type.starts_with("FDFVector3") && !type.starts_with("FLWCVector3")) return {};
  std::string text(t.text(call));
  return ue5_0 ? fmt::format("LWCToFloat(LWCAdd({}, PrimaryView.PreViewTranslation))", text)
               : fmt::format("DFFastToTranslatedWorld({}, PrimaryView.PreViewTranslation)", text);
}
}  // namespace

std::string input_semantic(const SyntaxTree& t, const Variable& p) {
  if (p.declaration < 0) return {};
  std::string_view text = t.source->text();
  size_t at = t.at(p.declaration).end;
  while (at < text.size() && (text[at] == ' ' || text[at] == '\t')) ++at;
  if (at >= text.size() || text[at] != ':') return {};
  ++at;
  while (at < text.size() && (text[at] == ' ' || text[at] == '\t')) ++at;
  size_t end = at;
  while (end < text.size() && (std::isalnum(static_cast<unsigned char>(text[end])) || text[end] == '_')) ++end;
  std::string semantic(text.substr(at, end - at));
  return semantic.empty() || semantic.starts_with("SV_") || semantic.starts_with("sv_") ? std::string() : semantic;
}

bool unreal_code(const SyntaxTree& t) {
  const std::string& p = t.source->path();
  return p.ends_with(".usf") || p.ends_with(".ush");
}

std::string TranslatedChain::primitive_to_world(const SyntaxTree& t, int node) const {
  Member m = member_of(t, node);
  if (m.empty() || !matches_any(primitive_objects_, m.object)) return {};
  if (m.member == "LocalToWorld") return "PreViewTranslation";
  if (m.member == "PreviousLocalToWorld" || m.member == "PrevLocalToWorld") return "PrevPreViewTranslation";
  return {};
}

RewritePlan TranslatedChain::plan_translated(const CheckContext& ctx, int var, const DeclaredNames& names) const {
  RewritePlan plan;
  std::string why = ctx.world.variables()[var].init >= 0 ? move_local(ctx, names, var, true, plan, 0) : move_out_local(ctx, names, var, plan, 0);
  if (!why.empty()) return withheld(why);
  return plan;
}

std::string TranslatedChain::move_local(const CheckContext& ctx, const DeclaredNames& names, int var, bool with_value, RewritePlan& plan, int depth) const {
  const SyntaxTree& t = ctx.tree;
  const Variable& v = ctx.world.variables()[var];
  std::string new_name = translated_name(v.name);
  if (new_name == v.name || names.taken(new_name, v.function)) return fmt::format("the name `{}` is already taken", new_name);
  plan.moving_variables.push_back(var);
  if (with_value)
    if (std::string why = translate_value(ctx, names, v.init, plan, depth); !why.empty()) return why;
  plan.edits.push_back({t.span(v.decl), new_name});
  follow_translated(ctx, names, var, new_name, plan, depth);
  return plan.blocker;
}

std::string TranslatedChain::translate_value(const CheckContext& ctx, const DeclaredNames& names, int value, RewritePlan& plan, int depth) const {
  const SyntaxTree& t = ctx.tree;
  while (t.is(value, "parenthesized_expression")) value = t.named_child(value);
  // Built from a view member UE5 hands over translated: translated already in the target era.
  if (translated_in_target(ctx, value)) return {};
  // A camera position or engine function with a translated twin.
  if (std::string twin = translated_twin(ctx, value); !twin.empty() && ctx.world.kind(value) == Kind::absolute) {
    plan.edits.push_back({t.span(value), twin});
    return {};
  }
  if (std::string twin = ctx.world.kind(value) == Kind::absolute ? host_twin(ctx, names, value, plan) : ""; !twin.empty()) {
    plan.edits.push_back({t.span(value), twin});
    return {};
  }
  if (t.is(value, "binary_expression")) {
    std::string_view op = t.text(t.child_by_field(value, "operator"));
    int left = t.child_by_field(value, "left"), right = t.child_by_field(value, "right");
    // (A name that says translated counts: a parameter has no kind of its own until a caller's.)
    bool translated = ctx.world.kind(left) == Kind::translated ||
                      (t.is(left, "identifier") && ctx.world.data().named_kind(t.text(left), Kind::absolute) == Kind::translated);
    if (op == "-" && ctx.world.kind(right) == Kind::camera_offset && translated) {
      plan.edits.push_back({t.span(value), std::string(t.text(left))});
      return {};
    }
    // A point and a small offset (`P + Normal * Bias`, `P - Dir * T`): the point moves.
    // (Any offset, where the point is known to be one.)
    if ((op == "+" || op == "-") && (small_vector(ctx, right) || (is_position(ctx.world.kind(left)) && point_offset(ctx, right, op, value))))
      return translate_value(ctx, names, left, plan, depth);
    if (op == "+" && (small_vector(ctx, left) || (is_position(ctx.world.kind(right)) && point_offset(ctx, left, op, value))))
      return translate_value(ctx, names, right, plan, depth);
    // The camera plus a vector that is no position (`ScreenVector * SceneDepth + View.WorldCameraOrigin`,
    // a view ray scaled to a depth): the camera takes its translated twin, the vector stays.
    if (op == "+" || op == "-") {
      for (auto [camera, other] : {std::pair{left, right}, std::pair{right, left}}) {
        if (op == "-" && camera != left) continue;
        std::string twin = ctx.world.kind(camera) == Kind::absolute ? translated_twin(ctx, camera) : "";
        if (!twin.empty() && !is_position(ctx.world.kind(other))) {
          plan.edits.push_back({t.span(camera), twin});
          return {};
        }
      }
    }
    // A homogeneous point divided by its own w (`H.xyz / H.w`): H moves, its w stays.
    if (op == "/" && t.is(left, "field_expression") && is_field_of(t, left, t.child_by_field(left, "argument"), "xyz") &&
        t.is(right, "field_expression") && is_field_of(t, right, t.child_by_field(right, "argument"), "w") &&
        t.text(t.child_by_field(left, "argument")) == t.text(t.child_by_field(right, "argument")))
      return translate_value(ctx, names, t.child_by_field(left, "argument"), plan, depth);
  }
  if (int base = t.child_by_field(value, "argument"); t.is(base, "identifier") && is_field_of(t, value, base, "xyz"))
    return translate_value(ctx, names, base, plan, depth);
  // A point made homogeneous (`float4(P, 1)`, or its `.xyz` again): the point moves.
  if (int base = t.child_by_field(value, "argument"); is_field_of(t, value, base, "xyz") && !position_of_homogeneous(t, base).empty())
    value = base;
  if (std::string p = position_of_homogeneous(t, value); !p.empty() && call_arguments(t, value).size() == 2)
    return translate_value(ctx, names, call_arguments(t, value)[0], plan, depth);
  // A point between two points (`lerp(A, B, t)`): the same weights of the two translated points.
  if (t.is(value, "call_expression") && call_name(t, value) == "lerp")
    if (auto args = call_arguments(t, value); args.size() == 3) {
      for (int point : {args[0], args[1]})
        if (std::string why = translate_value(ctx, names, point, plan, depth); !why.empty()) return why;
      return {};
    }
  // A wrapper that only changes how the value is computed (`INVARIANT(P)`): its operand moves.
  if (t.is(value, "call_expression") && matches_any(wrappers_, call_name(t, value)))
    if (auto args = call_arguments(t, value); args.size() == 1) return translate_value(ctx, names, args[0], plan, depth);
  // An engine function UE5 returns as a large-world position, with no translated twin
  // (`TransformLocalPositionToWorld(Parameters, P)`): the library takes it to translated world.
  if (std::string moved = engine_position_to_translated(ctx, value); !moved.empty()) {
    plan.edits.push_back({t.span(value), moved});
    return {};
  }
  // Another local holding an absolute position, or a call of a function of this file returning
  // one: it moves too, and this value follows it as one of its uses.
  if (int var = t.is(value, "identifier") ? ctx.world.variable_at(value) : -1; var >= 0) {
    const Variable& v = ctx.world.variables()[var];
    if (std::find(plan.moving_variables.begin(), plan.moving_variables.end(), var) != plan.moving_variables.end()) return {};
    if (v.role == Variable::Role::local && depth < 4)
      return v.init >= 0 ? move_local(ctx, names, var, true, plan, depth + 1) : move_out_local(ctx, names, var, plan, depth + 1);
    // The caller's own parameter: its callers pass the translated value in turn.
    if (v.role == Variable::Role::parameter && depth < 4) return move_parameter(ctx, names, var, plan, depth + 1);
  }
  if (int fn = t.is(value, "call_expression") ? defined_function(t, call_name(t, value), call_arguments(t, value).size()) : -1;
      fn >= 0 && depth < 4) {
    // A function this plan moves already: the call takes its translated name here (a split
    // keeps the old one for the callers that stay absolute).
    if (std::find(plan.moving_functions.begin(), plan.moving_functions.end(), fn) != plan.moving_functions.end()) {
      Span callee = t.span(t.child_by_field(value, "function"));
      if (!covered(plan, callee)) plan.edits.push_back({callee, translated_name(std::string(t.text(function_name(t, fn))))});
      return {};
    }
    int name = function_name(t, fn);
    return translate_function(ctx, fn, translated_name(std::string(t.text(name))), names, plan, depth + 1);
  }
  int mul = mul_call(t, value);
  if (mul < 0) return fmt::format("its value (`{}`) has no translated form lwcport knows", shortened(t.text(value)));
  auto args = call_arguments(t, mul);
  int matrix = undemoted(t, args[1]);
  std::string translation = primitive_to_world(t, matrix);
  if (mul != value && !is_field_of(t, value, mul, "xyz")) return fmt::format("it takes part of a transformed point (`{}`)", shortened(t.text(value)));
  if (std::string m = translated_twin(ctx, matrix); !m.empty()) {
    plan.edits.push_back({t.span(args[1]), m});
  } else if (std::string h = host_twin(ctx, names, matrix, plan); !h.empty()) {
    plan.edits.push_back({t.span(args[1]), h});
  } else if (std::string p = position_of_homogeneous(t, args[0]); !p.empty() && !translation.empty()) {
    // The library call gives the 3-vector; a 4-vector value keeps its w of 1.
    std::string call = fmt::format("DFTransformLocalToTranslatedWorld({}, {}, PrimaryView.{})", p,
                                   ue5_spelling(ctx, matrix), translation);
    plan.edits.push_back({t.span(value), mul == value ? fmt::format("float4({}, 1)", call) : call});
  } else {
    return fmt::format("its matrix `{}` has no translated twin", shortened(t.text(args[1])));
  }
  return {};
}

std::string TranslatedChain::host_twin(const CheckContext& ctx, const DeclaredNames& names, int node, RewritePlan& plan, bool by_use) const {
  const SyntaxTree& t = ctx.tree;
  while (t.is(node, "parenthesized_expression")) node = t.named_child(node);
  int name = node;
  std::string suffix;
  if (int base = t.child_by_field(node, "argument"); t.is(base, "identifier") && is_field_of(t, node, base, "xyz")) {
    name = base;
    suffix = ".xyz";
  }
  int var = t.is(name, "identifier") && unreal_code(t) ? ctx.world.variable_at(name) : -1;
  if (var < 0) return {};
  const Variable& v = ctx.world.variables()[var];
  Kind kind = ctx.world.kind(name);
  bool matrix_type = v.type == "float4x4" || v.type == "float3x4";
  // A vector met in a difference may be an offset as well as a point: only a name that says point
  // (`VolumeCenter`, `TouchPosition`) makes it one.
  if (by_use && kind == Kind::unknown)
    kind = matrix_type ? Kind::from_world_matrix : (v.type == "float3" || !suffix.empty()) && named_as_point(v.name) ? Kind::absolute : Kind::unknown;
  bool from_world = kind == Kind::from_world_matrix, to_world = kind == Kind::world_matrix;
  if (v.role != Variable::Role::global || !v.uniform || v.private_global || (kind != Kind::absolute && !from_world && !to_world)) return {};
  for (std::string_view word : leading_words(t, v.declaration))
    if (word == "static" || word == "const" || word == "groupshared") return {};
  // One declarator per declaration, and no register or binding of its own: the new one is a copy
  // of it under the new name (a copied `register(c4)` would clash).
  std::string declaration(t.text(v.declaration));
  if (declaration.find_first_of(",:[") != std::string::npos) return {};
  std::string twin = translated_name(v.name);
  if (twin == v.name || names.taken(twin, -1)) return {};
  uint32_t at = t.at(v.declaration).end, line = t.at(v.declaration).begin;
  std::string_view text = t.source->text();
  while (line > 0 && (text[line - 1] == ' ' || text[line - 1] == '\t')) --line;
  std::string indent(text.substr(line, t.at(v.declaration).begin - line));
  if (line > 0 && text[line - 1] != '\n') indent.clear();  // something else on the line before it
  Edit added{{at, at}, "\n" + indent + declaration.replace(t.at(v.decl).begin - t.at(v.declaration).begin, v.name.size(), twin)};
  if (std::find(plan.edits.begin(), plan.edits.end(), added) == plan.edits.end()) {
    plan.edits.push_back(added);
    std::string what = from_world ? "taking translated-world points (its translation moved by the camera's position)"
                       : to_world ? "giving translated-world points (the pre-view translation added to its translation)"
                                  : "plus the pre-view translation";
    plan.notes.push_back(fmt::format("the pass must also set `{}`: `{}` {}, computed in double on the host", twin, v.name, what));
  }
  return twin + suffix;
}

std::string TranslatedChain::move_parameter(const CheckContext& ctx, const DeclaredNames& names, int var, RewritePlan& plan, int depth) const {
  const SyntaxTree& t = ctx.tree;
  const Variable& p = ctx.world.variables()[var];
  int fn = p.function;
  if (p.output) return fmt::format("`{}` is an `out` parameter", p.name);
  // A header's function may be called from other files: in Unreal code it moves all the same, with
  // this file's callers, and the fix names it (unsafe: the other files' callers must follow).
  bool header = !whole_program(t);
  std::string function(t.text(function_name(t, fn)));
  if (header && !unreal_code(t))
    return fmt::format("`{}` is a parameter of `{}`, which other files may call with an absolute position", p.name, function);
  std::string new_name = translated_name(p.name);
  if (new_name == p.name || names.taken(new_name, fn)) return fmt::format("the name `{}` is already taken", new_name);
  size_t index = 0, arity = function_arity(t, fn);
  while (index < arity && parameter_variable(ctx, fn, index) != var) ++index;
  std::vector<int> calls = calls_to(t, fn);
  if (index < arity && calls.empty() && !header)
    if (std::string semantic = input_semantic(t, p); !semantic.empty())
      return fmt::format("`{}` is a shader input (`{}`) that the host or the stage before writes: no shader rewrite recovers what was "
                         "rounded there; the producer must write it in translated world (relative to the camera, computed in double) "
                         "or as a high/low pair",
                         p.name, semantic);
  if (index == arity || (calls.empty() && !header)) return fmt::format("no call in this file passes `{}`", p.name);
  plan.moving_variables.push_back(var);
  plan.edits.push_back({t.span(p.decl), new_name});
  if (header && std::find(plan.helpers.begin(), plan.helpers.end(), function) == plan.helpers.end()) plan.helpers.push_back(function);
  follow_translated(ctx, names, var, new_name, plan, depth + 1);
  if (!plan.blocker.empty()) return plan.blocker;
  for (int call : calls) {
    int argument = call_arguments(t, call)[index];
    if (std::string why = translate_value(ctx, names, argument, plan, depth + 1); !why.empty())
      return fmt::format("the call on line {} passes `{}`: {}", line_of(t, call), shortened(t.text(argument)), why);
  }
  return plan.blocker;
}

std::string TranslatedChain::translate_function(const CheckContext& ctx, int fn, const std::string& new_name, const DeclaredNames& names,
                               RewritePlan& plan, int depth) const {
  const SyntaxTree& t = ctx.tree;
  int name = function_name(t, fn);
  if (name < 0) return "its definition has no plain name";
  std::string old_name(t.text(name));
  if (std::string why = movable(t, names, fn, new_name); !why.empty()) return why;
  std::vector<int> returns;
  collect_returns(t, t.child_by_field(fn, "body"), returns);
  if (returns.empty()) return "it has no return value to move";
  plan.moving_functions.push_back(fn);
  size_t body_edits = plan.edits.size();
  for (int r : returns) {
    int value = t.named_child(r);
    if (value < 0) return "it returns nothing somewhere";
    // A local it returns moves with it: its value, its name and its other uses.
    int local = t.is(value, "identifier") ? ctx.world.variable_at(value) : -1;
    if (local >= 0 && ctx.world.variables()[local].role == Variable::Role::local && ctx.world.variables()[local].init >= 0) {
      if (std::string why = move_local(ctx, names, local, true, plan, depth + 1); !why.empty()) return why;
      continue;
    }
    if (std::string why = translate_value(ctx, names, value, plan, depth); !why.empty()) return why;
  }
  RewritePlan whole = plan;
  rename_with_callers(ctx, names, fn, new_name, whole, depth);
  if (whole.blocker.empty()) {
    plan = std::move(whole);
    return {};
  }
  // A caller needs the absolute value (a height, a light it meets): Epic's split.
  if (split_function(ctx, fn, new_name, names, body_edits, plan, depth)) return {};
  return whole.blocker;
}

std::string TranslatedChain::movable(const SyntaxTree& t, const DeclaredNames& names, int fn, const std::string& new_name) {
  std::string old_name(t.text(function_name(t, fn)));
  // Another file may call a header's function with an absolute position in mind.
  if (!whole_program(t)) return fmt::format("`{}` is in a header other files may call", old_name);
  if (names.taken(new_name, -1) || t.has_identifier(new_name)) return fmt::format("the name `{}` is already taken", new_name);
  if (calls_to(t, fn).empty())
    return fmt::format("nothing in this file calls `{}` (an entry point's name is the engine's to call)", old_name);
  return {};
}

void TranslatedChain::rename_with_callers(const CheckContext& ctx, const DeclaredNames& names, int fn, const std::string& new_name, RewritePlan& plan, int depth) const {
  const SyntaxTree& t = ctx.tree;
  int name = function_name(t, fn);
  plan.edits.push_back({t.span(name), new_name});
  for (int call : calls_to(t, fn)) {
    if (!plan.blocker.empty()) return;
    if (covered(plan, t.span(t.child_by_field(call, "function")))) continue;  // renamed as another call's partner
    // What the plan already changed in the arguments (a transform passed on, renamed) goes into
    // the call's new text, which replaces the whole call (the fix then keeps that one edit).
    int args = t.child_by_field(call, "arguments");
    Span inside = t.span(args);
    std::vector<Edit> within;
    for (const Edit& e : plan.edits)
      if (e.path.empty() && inside.begin <= e.span.begin && e.span.end <= inside.end) within.push_back(e);
    follow_use(ctx, names, call, new_name + spliced(std::string(t.text(args)), inside.begin, within), plan, depth + 1);
  }
}

bool TranslatedChain::split_function(const CheckContext& ctx, int fn, const std::string& new_name, const DeclaredNames& names, size_t body_edits,
                    RewritePlan& plan, int depth) const {
  const SyntaxTree& t = ctx.tree;
  int body = t.child_by_field(fn, "body");
  int type = t.child_by_field(fn, "type");
  if (!ctx.unreal || body < 0 || type < 0 || t.text(type) != "float3") return false;
  // Each finding of the chain plans the split again, trying every caller: a bound keeps a file
  // with a function called from hundreds of places linear.
  std::vector<int> callers = calls_to(t, fn);
  if (callers.size() > kMaxSplitCallers) return false;
  Span whole = t.span(fn);
  // The return values' edits inside the function go to the copy; those outside it (a function
  // it calls, moved on the way) stay.
  RewritePlan split = plan;
  split.edits.resize(body_edits);
  std::vector<Edit> inside;
  for (size_t i = body_edits; i < plan.edits.size(); ++i) {
    const Edit& e = plan.edits[i];
    bool in = e.span.begin >= whole.begin && e.span.end <= whole.end;
    (in ? inside : split.edits).push_back(e);
  }
  // The copy: the function's text with its name and return values translated.
  inside.push_back({t.span(function_name(t, fn)), new_name});
  std::string copy = spliced(std::string(t.text(fn)), whole.begin, inside);
  // Written with "\n" like every rewrite: the writer gives it the file's own line endings.
  for (size_t crlf; (crlf = copy.find("\r\n")) != std::string::npos;) copy.erase(crlf, 1);
  std::string marker = ctx.unreal->era == UnrealEra::ue5_0 ? "LWCHackToFloat" : "DFHackToFloat";
  std::string args;
  for (size_t i = 0; i < function_arity(t, fn); ++i) {
    int param = parameter_variable(ctx, fn, i);
    if (param < 0) return false;  // an unnamed parameter: the original cannot pass it on
    args += (args.empty() ? "" : ", ") + ctx.world.variables()[static_cast<size_t>(param)].name;
  }
  split.edits.push_back({Span{whole.begin, whole.begin}, copy + "\n\n"});
  split.edits.push_back({t.span(body), fmt::format("{{\n\treturn {}({}) - {}(PrimaryView.PreViewTranslation);\n}}", new_name, args, marker)});
  Span kept = t.span(body);
  int moved = 0;
  for (int call : callers) {
    if (t.at(call).begin >= kept.begin && t.at(call).end <= kept.end) continue;
    if (covered(split, t.span(t.child_by_field(call, "function")))) continue;  // renamed as another call's partner
    PlanMark before = mark(split);
    follow_use(ctx, names, call, new_name + std::string(t.text(t.child_by_field(call, "arguments"))), split, depth + 1);
    // A caller's rewrite may not reach into the body the split replaces.
    bool clear = split.blocker.empty() && std::none_of(split.edits.begin() + static_cast<long>(before.edits), split.edits.end(),
                                                       [&](const Edit& e) { return e.span.end > kept.begin && e.span.begin < kept.end; });
    if (!clear) {
      roll_back(split, before);
      continue;
    }
    ++moved;
  }
  if (moved == 0) return false;
  plan = std::move(split);
  return true;
}

bool TranslatedChain::follow_partner_call(const CheckContext& ctx, const DeclaredNames& names, int partner, RewritePlan& plan, int depth) const {
  const SyntaxTree& t = ctx.tree;
  while (t.is(partner, "parenthesized_expression")) partner = t.named_child(partner);
  if (!t.is(partner, "call_expression")) return false;
  int fn = defined_function(t, call_name(t, partner), call_arguments(t, partner).size());
  if (fn < 0) return false;
  Span callee = t.span(t.child_by_field(partner, "function"));
  if (std::find(plan.moving_functions.begin(), plan.moving_functions.end(), fn) != plan.moving_functions.end()) {
    if (!covered(plan, callee)) plan.edits.push_back({callee, translated_name(std::string(t.text(function_name(t, fn))))});
    return true;
  }
  PlanMark before = mark(plan);
  // A sibling of the use, not a step deeper: each function moves once per plan, which bounds it.
  if (translate_value(ctx, names, partner, plan, depth).empty() && plan.blocker.empty() && covered(plan, callee)) return true;
  roll_back(plan, before);
  return false;
}

void TranslatedChain::follow_translated(const CheckContext& ctx, const DeclaredNames& names, int var, const std::string& new_name, RewritePlan& plan, int depth,
                                        int assigned) const {
  const SyntaxTree& t = ctx.tree;
  uint32_t translated_from = UINT32_MAX;
  size_t followed = plan.followed, bridged = plan.bridged;
  for (int use : ctx.world.uses(var)) {
    if (!plan.blocker.empty()) return;
    if (use == assigned) {
      plan.edits.push_back({t.span(use), new_name});
    } else if (t.at(use).begin >= translated_from) {
      plan.edits.push_back({t.span(use), new_name});
      ++plan.followed;
    } else if (int statement = rebase_statement(ctx, use); statement >= 0) {
      plan.edits.push_back({whole_lines(t, statement), ""});
      translated_from = t.at(statement).end;
      ++plan.followed;
    } else {
      follow_use(ctx, names, use, new_name, plan, depth);
    }
  }
  // Moved only to read the absolute value back at every use: it stays as it was, and the value
  // handed to it is read back instead.
  if (plan.blocker.empty() && plan.followed == followed && plan.bridged > bridged)
    plan.blocker = fmt::format("every use of `{}` needs the absolute position", ctx.world.variables()[static_cast<size_t>(var)].name);
}

void TranslatedChain::follow_use(const CheckContext& ctx, const DeclaredNames& names, int use, const std::string& text, RewritePlan& plan, int depth) const {
  const SyntaxTree& t = ctx.tree;
  auto renamed = [&] {
    plan.edits.push_back({t.span(use), text});
    ++plan.followed;
  };
  // Passed to a parameter that this plan moves (written through an `out` one, or read by a
  // helper that now takes a translated position): the helper takes it translated.
  if (int p = parameter_of(ctx, use); p >= 0 && moving(plan, p)) {
    renamed();
    return;
  }
  // Passed to a parameter of this file that nothing reads: any value will do.
  if (int p = parameter_of(ctx, use); p >= 0 && ctx.world.uses(p).empty()) {
    renamed();
    return;
  }
  // The homogeneous w of a point is the same in translated world (a translation leaves it be).
  if (is_field_of(t, t.at(use).parent, use, "w")) {
    renamed();
    return;
  }
  int expr = climb_point(ctx, use);
  int partner = subtraction_partner(t, expr);
  if (std::string m = partner >= 0 ? translated_twin(ctx, partner) : ""; !m.empty()) {
    renamed();
    plan.edits.push_back({t.span(partner), m});
    return;
  }
  if (std::string m = partner >= 0 ? host_twin(ctx, names, partner, plan, true) : ""; !m.empty()) {
    renamed();
    plan.edits.push_back({t.span(partner), m});
    return;
  }
  if (partner >= 0 && follow_partner(ctx, names, partner, plan, depth)) {
    renamed();
    return;
  }
  // The other point is a call of a function of this file returning an absolute position (a
  // neighbouring cell's): it takes the translated one too.
  if (partner >= 0 && depth < 4 && follow_partner_call(ctx, names, partner, plan, depth)) {
    renamed();
    return;
  }
  // A sum with the pre-view translation is the translated value itself: the term goes.
  if (int sum = pre_view_sum(ctx, expr); sum >= 0) {
    int inner = expr;
    while (t.at(inner).parent != sum) inner = t.at(inner).parent;
    bool left = t.child_by_field(sum, "left") == inner;
    renamed();
    plan.edits.push_back({left ? Span{t.at(inner).end, t.at(sum).end} : Span{t.at(sum).begin, t.at(inner).begin}, ""});
    return;
  }
  // The point moved by an offset in place (`P -= Bias * Dir`, `P.z += Height`): it stays a point
  // of the same space.
  if (shifted_in_place(ctx, use)) {
    renamed();
    return;
  }
  int wrapper = homogeneous_wrapper(t, expr);
  int outer = wrapper >= 0 ? t.at(t.at(wrapper).parent).parent : -1;
  if (outer >= 0 && mul_call(t, outer) == outer && call_arguments(t, outer)[0] == wrapper) {
    int matrix = call_arguments(t, outer)[1];
    std::string m = translated_twin(ctx, matrix);
    if (m.empty()) m = host_twin(ctx, names, matrix, plan, true);
    if (!m.empty()) {
      renamed();
      plan.edits.push_back({t.span(matrix), m});
      return;
    }
  }
  // An engine function that takes its position in translated world from UE5 (its lighting, the
  // global distance field): UE4 code handing it the translated point hands it what it always meant.
  // A function translated by its own declaration, or UE5 code, gets a different point than before:
  // the call's own finding (lwc-translated-parameter) offers that, as a change of behaviour.
  bool declared = false;
  if (int call = ctx.unreal && ctx.unreal->era != UnrealEra::ue4 ? translated_parameter_call(ctx, expr, nullptr, &declared) : -1; call >= 0) {
    if (!declared && ctx.world.code_era() == UnrealEra::ue4) {
      renamed();
      return;
    }
    plan.blocker = fmt::format("it is passed to `{}` (line {}), which takes a translated point already: passing one changes what the call "
                               "computes (lwc-translated-parameter offers it there)", call_name(t, call), line_of(t, call));
    return;
  }
  // A point between this one and another (`float3 O = lerp(P, Q, t);`): the other point moves too,
  // and the local holding the result follows.
  if (int list = t.at(expr).parent; depth < 4 && t.is(list, "argument_list") && call_name(t, t.at(list).parent) == "lerp") {
    int call = t.at(list).parent;
    auto args = call_arguments(t, call);
    if (args.size() == 3 && (args[0] == expr || args[1] == expr)) {
      PlanMark before = mark(plan);
      if (translate_value(ctx, names, args[0] == expr ? args[1] : args[0], plan, depth + 1).empty() && plan.blocker.empty() &&
          follow_into_local(ctx, names, call, plan, depth)) {
        renamed();
        return;
      }
      roll_back(plan, before);
    }
  }
  if (depth < 4 && follow_into_difference_group(ctx, names, expr, plan, depth)) {
    renamed();
    return;
  }
  if (depth < 4 && expr == use && follow_into_helper(ctx, names, use, plan, depth)) {
    renamed();
    return;
  }
  if (depth < 4 && follow_into_local(ctx, names, expr, plan, depth)) {
    renamed();
    return;
  }
  // A screen derivative of the point: the camera's translation is the same at every pixel, so
  // the derivative of the translated point is the one of the absolute point.
  if (int list = t.at(expr).parent; t.is(list, "argument_list") && call_arguments(t, t.at(list).parent).size() == 1 &&
                                    matches_any(translation_invariant_, call_name(t, t.at(list).parent))) {
    renamed();
    return;
  }
  if (depth < 4 && t.is(t.at(expr).parent, "return_statement")) {
    int fn = expr;
    while (fn >= 0 && !t.is(fn, "function_definition")) fn = t.at(fn).parent;
    // Returned from a function this plan already moves: it is renamed there.
    if (std::find(plan.moving_functions.begin(), plan.moving_functions.end(), fn) != plan.moving_functions.end()) {
      renamed();
      return;
    }
    int name = fn >= 0 ? function_name(t, fn) : -1;
    if (name >= 0) {
      PlanMark before = mark(plan);
      std::string why = translate_function_of_use(ctx, fn, translated_name(std::string(t.text(name))), names, plan, depth);
      if (why.empty()) {
        renamed();
        return;
      }
      roll_back(plan, before);
      if (bridge(ctx, use, text, plan)) return;
      if (plan.blocker.empty()) plan.blocker = why;
      return;
    }
  }
  if (bridge(ctx, use, text, plan)) return;
  if (plan.blocker.empty()) plan.blocker = escape(t, use);
}

bool TranslatedChain::bridge(const CheckContext& ctx, int use, const std::string& text, RewritePlan& plan) {
  const SyntaxTree& t = ctx.tree;
  if (!ctx.unreal || ctx.unreal->era == UnrealEra::ue4 || !plan.blocker.empty()) return false;
  // Only a read: a store into the point (`P = ..`, `P.z += ..`, `P++`, an `out` argument) must
  // store a translated value, which is the chain's work, not a bridge's.
  if (stores_into(ctx, use)) return false;
  // The library subtracts 3-vectors: a homogeneous point is read back through its xyz.
  std::string type;
  if (int var = ctx.world.variable_at(use); var >= 0) type = ctx.world.variables()[static_cast<size_t>(var)].type;
  else if (t.is(use, "call_expression")) type = ctx.world.function_return_type(std::string(call_name(t, use)));
  int replaced = use;
  std::string point = text;
  if (type == "float4" && is_field_of(t, t.at(use).parent, use, "xyz")) {
    replaced = t.at(use).parent;
    point += ".xyz";
  } else if (type != "float3") {
    return false;
  }
  std::string absolute = ctx.unreal->era == UnrealEra::ue5_0 ? fmt::format("LWCToFloat(LWCSubtract({}, PrimaryView.PreViewTranslation))", point)
                                                             : fmt::format("DFSubtractDemote({}, PrimaryView.PreViewTranslation)", point);
  plan.edits.push_back({t.span(replaced), absolute});
  ++plan.bridged;
  return true;
}

bool TranslatedChain::follow_into_local(const CheckContext& ctx, const DeclaredNames& names, int expr, RewritePlan& plan, int depth) const {
  const SyntaxTree& t = ctx.tree;
  // Packed with a scalar (`float4(P, Radius)`, a bounding sphere): the 4-vector's xyz is the
  // point, and its w stays what it was.
  if (int packed = packed_point(t, expr); packed >= 0) expr = packed;
  int declarator = t.at(expr).parent;
  if (!t.is(declarator, "init_declarator") || t.child_by_field(declarator, "value") != expr) return false;
  int id = t.child_by_field(declarator, "declarator");
  int local = id >= 0 ? ctx.world.variable_declared_at(id) : -1;
  if (local < 0) return false;
  const Variable& v = ctx.world.variables()[local];
  std::string new_name = translated_name(v.name);
  if (std::find(plan.moving_variables.begin(), plan.moving_variables.end(), local) != plan.moving_variables.end()) return true;
  if (new_name == v.name || names.taken(new_name, v.function)) return false;
  // A local that cannot move (every use of it needs the absolute value) is left as it was: the
  // use that feeds it reads the absolute value back instead.
  PlanMark before = mark(plan);
  if (move_local(ctx, names, local, false, plan, depth + 1).empty()) return true;
  roll_back(plan, before);
  return false;
}

bool TranslatedChain::follow_partner(const CheckContext& ctx, const DeclaredNames& names, int partner, RewritePlan& plan, int depth) const {
  const SyntaxTree& t = ctx.tree;
  while (t.is(partner, "parenthesized_expression")) partner = t.named_child(partner);
  if (is_field_of(t, partner, t.child_by_field(partner, "argument"), "xyz")) partner = t.child_by_field(partner, "argument");
  int var = t.is(partner, "identifier") ? ctx.world.variable_at(partner) : -1;
  if (var < 0) return false;
  if (std::find(plan.moving_variables.begin(), plan.moving_variables.end(), var) != plan.moving_variables.end()) return true;
  const Variable& v = ctx.world.variables()[var];
  if (depth >= 4) return false;
  // A parameter on the other side of a difference with a world point is a world point too (a
  // difference of points is meaningful only in one frame): it moves with its callers.
  bool parameter = v.role == Variable::Role::parameter && !v.output && (v.type == "float3" || v.type == "float4") &&
                   (v.kind == Kind::absolute || (v.kind == Kind::unknown && ctx.world.data().named_kind(v.name, Kind::absolute) == Kind::absolute));
  if (!parameter && (v.role != Variable::Role::local || v.kind != Kind::absolute)) return false;
  PlanMark before = mark(plan);
  std::string why = parameter ? move_parameter(ctx, names, var, plan, depth + 1)
                    : v.init >= 0 ? move_local(ctx, names, var, true, plan, depth + 1) : move_out_local(ctx, names, var, plan, depth + 1);
  if (why.empty()) return true;
  roll_back(plan, before);
  return false;
}

std::string TranslatedChain::translate_function_of_use(const CheckContext& ctx, int fn, const std::string& new_name, const DeclaredNames& names,
                                      RewritePlan& plan, int depth) const {
  const SyntaxTree& t = ctx.tree;
  int name = function_name(t, fn);
  std::string old_name(t.text(name));
  if (std::string why = movable(t, names, fn, new_name); !why.empty()) return fmt::format("it is returned by `{}`: {}", old_name, why);
  std::vector<int> returns;
  collect_returns(t, t.child_by_field(fn, "body"), returns);
  if (returns.size() != 1) return fmt::format("`{}` returns from more than one place", old_name);
  plan.moving_functions.push_back(fn);
  rename_with_callers(ctx, names, fn, new_name, plan, depth);
  return plan.blocker;
}

bool TranslatedChain::follow_into_difference_group(const CheckContext& ctx, const DeclaredNames& names, int use, RewritePlan& plan,
                                                   int depth) const {
  const SyntaxTree& t = ctx.tree;
  int list = t.at(use).parent;
  if (!t.is(list, "argument_list")) return false;
  int call = t.at(list).parent;
  std::string_view name = call_name(t, call);
  std::vector<int> args = call_arguments(t, call);
  size_t index = std::find(args.begin(), args.end(), use) - args.begin();
  if (name.empty() || index == args.size()) return false;
  std::vector<size_t> group;
  if (int fn = defined_function(t, name, args.size()); fn >= 0) {
    group = ctx.world.difference_group(fn);
  } else if (const FileSummary* inc = ctx.world.includes()) {
    auto it = inc->difference_groups.find(std::string(name) + "/" + std::to_string(args.size()));
    if (it != inc->difference_groups.end()) group = it->second;
  }
  if (std::find(group.begin(), group.end(), index) == group.end()) return false;
  PlanMark before = mark(plan);
  for (size_t other : group) {
    if (other == index || other >= args.size()) continue;
    PlanMark before_value = mark(plan);
    if (translate_value(ctx, names, args[other], plan, depth + 1).empty() && plan.blocker.empty()) continue;
    // A uniform of no known kind met there is a world point too: the host sets a translated one.
    roll_back(plan, before_value);
    if (std::string twin = host_twin(ctx, names, args[other], plan, true); !twin.empty()) {
      plan.edits.push_back({t.span(args[other]), twin});
      continue;
    }
    roll_back(plan, before);
    return false;
  }
  return true;
}

bool TranslatedChain::follow_into_helper(const CheckContext& ctx, const DeclaredNames& names, int use, RewritePlan& plan, int depth) const {
  const SyntaxTree& t = ctx.tree;
  int param = parameter_of(ctx, use);
  if (param < 0) return false;
  // A whole program: the helper takes the translated value from every caller.
  if (whole_program(t)) {
    PlanMark before = mark(plan);
    if (move_parameter(ctx, names, param, plan, depth + 1).empty()) return true;
    roll_back(plan, before);
    return false;
  }
  std::string_view callee = call_name(t, t.at(t.at(use).parent).parent);
  // One caller only: another call might pass an absolute position.
  if (calls_of(t, callee) != 1) return false;
  const auto& vars = ctx.world.variables();
  std::string param_name = translated_name(vars[param].name);
  plan.edits.push_back({t.span(vars[param].decl), param_name});
  follow_translated(ctx, names, param, param_name, plan, depth + 1);
  if (plan.blocker.empty() && unreal_code(t) && !t.source->path().ends_with(".usf"))
    plan.helpers.push_back(std::string(callee));
  return plan.blocker.empty();
}

int TranslatedChain::assigned_once(const CheckContext& ctx, int var, const std::vector<int>& uses) {
  const SyntaxTree& t = ctx.tree;
  int first = uses.front(), assignment = t.at(first).parent;
  if (!t.is(assignment, "assignment_expression") || t.child_by_field(assignment, "left") != first ||
      t.text(t.child_by_field(assignment, "operator")) != "=")
    return -1;
  int statement = t.at(assignment).parent;
  const Variable& v = ctx.world.variables()[var];
  if (!t.is(statement, "expression_statement") || v.declaration < 0 || t.at(statement).parent != t.at(v.declaration).parent) return -1;
  for (size_t i = 1; i < uses.size(); ++i)
    if (stores_into(ctx, uses[i])) return -1;
  return t.child_by_field(assignment, "right");
}

std::string TranslatedChain::move_out_local(const CheckContext& ctx, const DeclaredNames& names, int var, RewritePlan& plan, int depth) const {
  const SyntaxTree& t = ctx.tree;
  const auto& vars = ctx.world.variables();
  const Variable& v = vars[var];
  std::string new_name = translated_name(v.name);
  if (new_name == v.name || names.taken(new_name, v.function)) return fmt::format("the name `{}` is already taken", new_name);
  std::vector<int> uses = ctx.world.uses(var);
  // Declared, then given its value once by a plain assignment in the same block before any read
  // (`float3 P; P = mul(..);`, as generated material code writes): that value is its own.
  if (int value = uses.empty() ? -1 : assigned_once(ctx, var, uses); value >= 0) {
    plan.moving_variables.push_back(var);
    if (std::string why = translate_value(ctx, names, value, plan, depth); !why.empty()) return why;
    plan.edits.push_back({t.span(v.decl), new_name});
    follow_translated(ctx, names, var, new_name, plan, depth, uses.front());
    return plan.blocker;
  }
  int param = uses.empty() ? -1 : out_parameter_of(ctx, uses.front());
  if (param < 0)
    return fmt::format("`{}` gets its value from nothing lwcport can follow (it moves a local given its value once, in its own block "
                       "before any read, or by one call's `out` parameter)", v.name);
  for (size_t i = 1; i < uses.size(); ++i)
    if (out_parameter_of(ctx, uses[i]) >= 0) return fmt::format("`{}` is written by more than one call", v.name);
  std::string_view callee = call_name(t, t.at(t.at(uses.front()).parent).parent);
  if (calls_of(t, callee) != 1) return fmt::format("`{}` is called from more than one place", callee);
  const Variable& p = vars[param];
  std::string param_name = translated_name(p.name);
  if (param_name == p.name || names.taken(param_name, p.function)) return fmt::format("the name `{}` is already taken", param_name);
  plan.moving_variables.push_back(var);
  plan.moving_variables.push_back(param);
  plan.edits.push_back({t.span(v.decl), new_name});
  plan.edits.push_back({t.span(p.decl), param_name});
  for (int use : ctx.world.uses(param)) {
    int assignment = t.at(use).parent;
    bool plain = t.is(assignment, "assignment_expression") && t.child_by_field(assignment, "left") == use &&
                 t.text(t.child_by_field(assignment, "operator")) == "=" && t.is(t.at(assignment).parent, "expression_statement");
    if (!plain) return fmt::format("`{}` in `{}` is read or written in part, not only assigned", p.name, callee);
    plan.edits.push_back({t.span(use), param_name});
    if (std::string why = translate_value(ctx, names, t.child_by_field(assignment, "right"), plan, depth); !why.empty())
      return fmt::format("what `{}` writes to `{}`: {}", callee, p.name, why);
  }
  if (unreal_code(t) && !t.source->path().ends_with(".usf")) plan.helpers.push_back(std::string(callee));
  follow_translated(ctx, names, var, new_name, plan, depth);
  return plan.blocker;
}

}  // namespace lwc::checks
