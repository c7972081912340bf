// lwc-large-world-member: a member of an engine struct that UE5 holds as a large-world type
// (ResolvedView's camera origin and translations, a primitive's transforms and positions) used
// where a float is needed. In UE5 the line stops compiling; hacked back to float it loses the
// precision the type was made for. The rewrite does the float arithmetic in the era's library.
#include <fmt/format.h>

#include "rules/checks/library_rewrite.h"
#include "rules/checks/translation_row.h"
#include "rules/checks/util.h"

namespace lwc::checks {
namespace {

bool large_world_type(std::string_view type) { return type.starts_with("FDF") || type.starts_with("FLWC"); }

class LargeWorldMember : public Check {
 public:
  explicit LargeWorldMember(const RuleInfo& rule)
      : lwc_calls_(string_list(rule.data, "lwc-calls")),
        float_calls_(string_list(rule.data, "float-calls")) {}

  void run(const CheckContext& ctx) const override {
    if (!ctx.unreal) return;
    const SyntaxTree& t = ctx.tree;
    // UE4 code is read for the era it moves to: the DoubleFloat types of UE 5.4+.
    UnrealEra era = ctx.unreal->era == UnrealEra::ue5_0 ? UnrealEra::ue5_0 : UnrealEra::ue5_4;
    for (int id : nodes_of(t, "field_expression")) {
      Member m = member_of(t, id);
      if (m.empty()) continue;
      const WorldData::EngineMember* e = engine_member_at(ctx, id);
      if (!e) continue;
      const std::string& type = e->types[era == UnrealEra::ue5_0 ? 1 : 2];
      if (!large_world_type(type)) continue;
      bool vector3 = e->kind == Kind::absolute || e->kind == Kind::camera_offset;
      Use use = float_use(ctx, id, vector3);
      if (use.what.empty()) continue;
      if (use.node < 0) use.node = id;
      std::string object(t.text(t.child_by_field(id, "argument")));
      Vars vars{{"value", object + "." + m.member},
                {"type", type},
                {"era", std::string(era_name(era))},
                {"use", use.what},
                {"library", era == UnrealEra::ue5_0 ? "`LWCToFloat(LWCSubtract(..))`, `LWCToFloat3x3`, `LWCMultiply`"
                                                    : "`DFSubtractDemote`, `DFToFloat3x3`, `DFMultiply`"},
                {"when", ctx.unreal->era == UnrealEra::ue4 ? "when this code moves to UE5" : "in " + std::string(era_name(era))}};
      Finding& f = ctx.report(t.span(id), vars);
      // UE4's primitive uniform buffer: UE5 reads the same data through a call.
      bool respelled = ue5_spelling(ctx, id) != t.text(id);
      std::string spelled = respelled ? ctx.world.data().uniform_buffer[1] : object;
      offer_fix(ctx, f, id, use, {use.node, spelled + "." + m.member, e->kind, spelled, m.member}, era, vars);
    }
    // A material function UE5 returns as a large-world value (`GetWorldPosition(Parameters)`), when
    // the file does not define its own of that name.
    for (int call : nodes_of(t, "call_expression")) {
      std::string name(call_name(t, call));
      auto types = ctx.world.data().engine_function_types.find(name);
      if (types == ctx.world.data().engine_function_types.end() || defines_function(t, name)) continue;
      const std::string& type = types->second[era == UnrealEra::ue5_0 ? 1 : 2];
      if (!large_world_type(type)) continue;
      Use use = float_use(ctx, call, true);
      if (use.what.empty()) continue;
      if (use.node < 0) use.node = call;
      std::string text(t.text(call));
      Vars vars{{"value", text}, {"type", type}, {"era", std::string(era_name(era))}, {"use", use.what},
                {"library", era == UnrealEra::ue5_0 ? "`LWCToFloat(LWCSubtract(..))`, `LWCToFloat3x3`, `LWCMultiply`"
                                                    : "`DFSubtractDemote`, `DFToFloat3x3`, `DFMultiply`"},
                {"when", ctx.unreal->era == UnrealEra::ue4 ? "when this code moves to UE5" : "in " + std::string(era_name(era))}};
      Finding& f = ctx.report(t.span(call), vars);
      offer_fix(ctx, f, call, use, {use.node, text, Kind::absolute, "", ""}, era, vars);
    }
  }

 private:
  // What needs a float at a use, and the node that needs it.
  struct Use {
    std::string what;  // "" when the use takes the large-world value (or lwcport cannot tell)
    int parent = -1;
    int node = -1;     // the expression that stands for the member there (`M`, `(M)`, `M.xyz`)
    std::string callee = "";  // a function of the project whose float parameter takes it, else ""
  };

  Use float_use(const CheckContext& ctx, int node, bool vector3) const {
    const SyntaxTree& t = ctx.tree;
    int p = t.at(node).parent;
    while (t.is(p, "parenthesized_expression")) node = p, p = t.at(p).parent;
    // `.xyz` of a 3-vector is the vector itself: its use is the swizzle's.
    if (vector3 && is_field_of(t, p, node, "xyz")) {
      Use outer = float_use(ctx, p, false);
      if (outer.what.empty()) outer = {"swizzled (`.xyz`)", p};  // a large-world value has no swizzles
      outer.node = p;
      return outer;
    }
    if (p < 0) return {};
    std::string_view type = t.at(p).type;
    auto op_text = [&] {
      int op = t.child_by_field(p, "operator");
      return op >= 0 ? std::string(t.text(op)) : std::string();
    };
    if (type == "binary_expression") {
      std::string op = op_text();
      if (op == "+" || op == "-" || op == "*" || op == "/" || op == "<" || op == ">" || op == "<=" || op == ">=")
        return {fmt::format("in float arithmetic (`{}`)", op), p};
      return {};
    }
    if (type == "unary_expression") return op_text() == "-" ? Use{"negated as a float", p} : Use{};
    if (type == "assignment_expression") {
      std::string op = op_text();
      if (t.child_by_field(p, "right") != node) return {};
      if (op != "=") return {fmt::format("in float arithmetic (`{}`)", op), p};
      int left = t.child_by_field(p, "left");
      int var = t.is(left, "identifier") ? ctx.world.variable_at(left) : -1;
      if (var >= 0 && ctx.world.data().is_float_type(ctx.world.variables()[var].type))
        return {fmt::format("stored into `{}`, a `{}`", t.text(left), ctx.world.variables()[var].type), p};
      return {};
    }
    if (type == "cast_expression") {
      int cast_type = t.child_by_field(p, "type");
      if (cast_type >= 0 && ctx.world.data().is_float_type(t.text(cast_type))) return {fmt::format("cast to `{}`", t.text(cast_type)), p};
      return {};
    }
    if (type == "field_expression" && t.child_by_field(p, "argument") == node) {
      int field = t.child_by_field(p, "field");
      if (field >= 0 && is_swizzle(t.text(field))) return {fmt::format("swizzled (`.{}`)", t.text(field)), p};
      return {};
    }
    if (type == "subscript_expression" && t.child_by_field(p, "argument") == node) return {"indexed by row as a float matrix", p};
    if (type == "argument_list") {
      int call = t.at(p).parent;
      if (int cast = t.cast_written_as_call(call); cast >= 0) {
        if (ctx.world.data().is_float_type(t.text(cast))) return {fmt::format("cast to `{}`", t.text(cast)), call};
        return {};
      }
      std::string_view callee = call_name(t, call);
      if (callee.empty() || matches_any(lwc_calls_, callee)) return {};
      // An engine function that takes it in translated world: lwc-translated-parameter's finding.
      if (translated_parameter_call(ctx, node) == call) return {};
      if (matches_any(float_calls_, callee)) return {fmt::format("passed to `{}`", callee), p};
      auto args = call_arguments(t, call);
      size_t index = std::find(args.begin(), args.end(), node) - args.begin();
      std::string param = parameter_type(ctx, callee, index);
      if (param.empty() && !defines_function(t, callee))
        if (auto included = ctx.world.included_parameter_use(call, node)) param = included->type;
      if (!param.empty() && ctx.world.data().is_float_type(param))
        return {fmt::format("passed to `{}`, whose parameter is a `{}`", callee, param), p, -1, std::string(callee)};
      return {};
    }
    if (type == "init_declarator") {
      int declaration = t.at(p).parent;
      int decl_type = t.is(declaration, "declaration") ? t.child_by_field(declaration, "type") : -1;
      if (decl_type >= 0 && ctx.world.data().is_float_type(t.text(decl_type)))
        return {fmt::format("stored into a `{}`", t.text(decl_type)), p};
      return {};
    }
    if (type == "return_statement") {
      int fn = p;
      while (fn >= 0 && !t.is(fn, "function_definition")) fn = t.at(fn).parent;
      int ret = fn >= 0 ? t.child_by_field(fn, "type") : -1;
      if (ret >= 0 && ctx.world.data().is_float_type(t.text(ret))) return {fmt::format("returned as a `{}`", t.text(ret)), p};
    }
    return {};
  }

  // The declared type of a function's parameter when this file defines the function once, or ""
  // (an overload may take the large-world type: `RotateLocalToWorld(float3, FDFMatrix, float3)`).
  // A function of an included file: its type where every overload of that arity agrees.
  static std::string parameter_type(const CheckContext& ctx, std::string_view function, size_t index) {
    const SyntaxTree& t = ctx.tree;
    const std::vector<int>& defs = t.definitions_named(function);
    if (defs.size() != 1) return {};
    int var = parameter_variable(ctx, defs.front(), index);
    return var >= 0 ? ctx.world.variables()[static_cast<size_t>(var)].type : std::string();
  }


  // The arithmetic done in the era's large-world library (library_rewrite.h).
  // `id`: the member access or call that is the large-world value; `value`: it as the library takes it.
  void offer_fix(const CheckContext& ctx, Finding& f, int id, const Use& use, const LargeWorldValue& value, UnrealEra era, Vars vars) const {
    const SyntaxTree& t = ctx.tree;
    Kind kind = value.kind;
    vars["marker"] = era == UnrealEra::ue5_0 ? "LWCHackToFloat" : "DFHackToFloat";
    if (auto row = translation_row_at(ctx, id)) {
      offer_row_fix(ctx, f, id, *row, era, value.text, vars);
      return;
    }
    if (auto [sum, text] = translated_transform(ctx, id, era); sum >= 0) {
      vars["translated"] = shortened(text);
      ctx.fix(f, "translated-transform", vars, {{t.span(sum), text}});
      return;
    }
    if (auto [point, plane] = plane_point(ctx, use); point >= 0) {
      vars["point"] = shortened(t.text(point));
      vars["plane"] = plane;
      ctx.fix(f, "translated-plane", vars, {{t.span(use.parent), std::string(t.text(point))}});
      return;
    }
    // Beside another float32 absolute position the library gains nothing (library_rewrite.h): the
    // line compiles with the value UE4 read, marked for the ledger, until both move together.
    int other = kind == Kind::absolute || kind == Kind::camera_offset ? absolute_partner(ctx, use.node, kind) : -1;
    // An engine member the code reads as absolute and UE 5.0 hands over translated
    // (FMaterialVertexParameters.WorldPosition): the camera term takes its translated twin.
    if (std::string twin = other >= 0 && translated_from_ue5(ctx, other) ? translated_twin(ctx, id) : ""; !twin.empty()) {
      vars["partner"] = shortened(t.text(other));
      vars["twin"] = twin;
      ctx.fix(f, "twin-beside", vars, {{t.span(id), twin}});
      return;
    }
    if (other >= 0 && !large_world_value(ctx, other, era)) {
      vars["partner"] = shortened(t.text(other));
      ctx.fix(f, "marker-beside", vars, {{t.span(id), vars["marker"] + "(" + value.text + ")"}});
      return;
    }
    LibraryRewrite r = library_rewrite(ctx, value, era != UnrealEra::ue5_0);
    if (!r.fix.empty()) {
      for (const auto& [key, text] : r.vars) vars[key] = text;
      ctx.fix(f, r.fix, vars, r.edits);
      return;
    }
    // Handed to a float parameter of the project's own function: that function is not rewritten
    // here, so the era's marker passes it exactly the float32 value UE4 passed, and marks the place.
    if (!use.callee.empty()) {
      vars["callee"] = use.callee;
      ctx.fix(f, "marker-argument", vars, {{t.span(id), vars["marker"] + "(" + value.text + ")"}});
      return;
    }
    // One coordinate of a position (a height, a clamp): the absolute value is what the code
    // wants, as Epic's own port keeps it, so the era's marker demotes it, as UE4 did.
    if (read_as_coordinates(t, id) && (kind == Kind::absolute || kind == Kind::camera_offset)) {
      ctx.fix(f, "marker", vars, {{t.span(id), vars["marker"] + "(" + value.text + ")"}});
      return;
    }
    f.withheld.push_back(!r.blocker.empty() ? r.blocker
                                            : fmt::format("`{}` is an `{}` and is {} here: the computation around it must move to translated world "
                                                          "or to the large-world library first", t.text(id), vars["type"], vars["use"]));
  }

  // `mul(float4(P, 1), Primitive.LocalToWorld).xyz + ResolvedView.PreViewTranslation`, from either
  // member: UE4's translated point, made in float32 from an absolute one. UE5 makes it from the
  // large-world transform and translation in one call (`DFTransformLocalToTranslatedWorld`; in UE
  // 5.0-5.3 the tile/offset sum). The sum and its rewrite; else -1.
  std::pair<int, std::string> translated_transform(const CheckContext& ctx, int id, UnrealEra era) const {
    const SyntaxTree& t = ctx.tree;
    auto climb = [&](int n) {  // through parentheses and a 3-vector's `.xyz`
      for (int p = t.at(n).parent; t.is(p, "parenthesized_expression") || is_field_of(t, p, n, "xyz"); p = t.at(n).parent) n = p;
      return n;
    };
    int sum = -1;
    if (int list = t.at(id).parent; t.is(list, "argument_list") && mul_call(t, t.at(list).parent) == t.at(list).parent) {
      sum = t.at(climb(t.at(list).parent)).parent;  // the matrix of the transform
    } else {
      sum = t.at(climb(id)).parent;  // the translation
    }
    if (!t.is(sum, "binary_expression") || t.text(t.child_by_field(sum, "operator")) != "+") return {-1, ""};
    int transform = -1, translation = -1;
    for (int side : {t.child_by_field(sum, "left"), t.child_by_field(sum, "right")}) {
      int inner = side;
      while (t.is(inner, "parenthesized_expression")) inner = t.named_child(inner);
      if (int mul = mul_call(t, inner); mul >= 0) transform = mul;
      if (member_of(t, without_xyz(t, inner)).member == "PreViewTranslation") translation = without_xyz(t, inner);
    }
    if (transform < 0 || translation < 0) return {-1, ""};
    auto args = call_arguments(t, transform);
    std::string point = position_of_homogeneous(t, args[0]);
    int matrix = args[1];
    if (point.empty() || ctx.world.kind(matrix) != Kind::world_matrix || !large_world_matrix(ctx, matrix, era)) return {-1, ""};
    std::string m = ue5_spelling(ctx, matrix), v = ue5_spelling(ctx, translation);
    if (v.starts_with("View.")) v = "Primary" + v;
    return {sum, era == UnrealEra::ue5_0 ? fmt::format("LWCToFloat(LWCAdd(LWCMultiply({}, {}), {}))", point, m, v)
                                         : fmt::format("DFTransformLocalToTranslatedWorld({}, {}, {})", point, m, v)};
  }

  // `dot(View.GlobalClippingPlane, float4(P - View.PreViewTranslation, 1))`: a translated point
  // made absolute only to meet a plane that UE 5.0 hands over translated under the same name
  // (rules/world-space.json engine "view-members-translated-in-place"). The point and the plane,
  // where the use is that subtraction; else -1.
  std::pair<int, std::string> plane_point(const CheckContext& ctx, const Use& use) const {
    const SyntaxTree& t = ctx.tree;
    int difference = use.parent;
    if (!t.is(difference, "binary_expression") || t.text(t.child_by_field(difference, "operator")) != "-" ||
        t.child_by_field(difference, "right") != use.node)
      return {-1, ""};
    int homogeneous = t.at(difference).parent;
    if (!t.is(homogeneous, "argument_list") || position_of_homogeneous(t, t.at(homogeneous).parent).empty()) return {-1, ""};
    int list = t.at(t.at(homogeneous).parent).parent;
    if (!t.is(list, "argument_list") || call_name(t, t.at(list).parent) != "dot") return {-1, ""};
    for (int other : call_arguments(t, t.at(list).parent)) {
      Member m = member_of(t, other);
      if (const auto* e = view_member_translated_in_place(ctx, other); e && e->plane) return {t.child_by_field(difference, "left"), m.object + "." + m.member};
    }
    return {-1, ""};
  }

  // A translation row rebased one coordinate at a time (translation_row.h): UE5 builds the
  // translated transform in one call from the large-world one. A float matrix from elsewhere (the
  // host's) has no large-world value to start from: the marker keeps UE4's value, and the note says
  // what the host must hand over instead.
  void offer_row_fix(const CheckContext& ctx, Finding& f, int id, const TranslationRow& row, UnrealEra era, const std::string& value,
                     Vars vars) const {
    const SyntaxTree& t = ctx.tree;
    const Variable& local = ctx.world.variables()[static_cast<size_t>(row.local)];
    vars["local"] = local.name;
    vars["call"] = era == UnrealEra::ue5_0 ? "LWCMultiplyTranslation" : "DFFastToTranslatedWorld";
    vars["matrix"] = shortened(t.text(row.matrix));
    if (large_world_matrix(ctx, row.matrix, era)) {
      std::string translation = ue5_spelling(ctx, undemoted(t, row.translation));
      if (translation.starts_with("View.")) translation = "Primary" + translation;
      std::vector<Edit> edits{{t.span(local.init), fmt::format("{}({}, {})", vars["call"], ue5_spelling(ctx, row.matrix), translation)}};
      for (int s : row.statements) edits.push_back({whole_lines(t, s), ""});
      ctx.fix(f, "translated-row", vars, std::move(edits));
      return;
    }
    bool in_row = false;
    for (int s : row.statements) in_row |= t.at(s).begin <= t.at(id).begin && t.at(id).end <= t.at(s).end;
    if (!in_row) return;
    if (Fix* fix = ctx.fix(f, "marker-row", vars, {{t.span(id), vars["marker"] + "(" + value + ")"}}))
      fix->notes.push_back(fmt::format("`{}` holds the absolute transform in float32 (the host fills it): hand it over as a large-world matrix, "
                                       "then `{}` builds `{}` in one step, or already translated",
                                       vars["matrix"], vars["call"], local.name));
  }

  // A value the era holds as a large-world type: an engine member (through `.xyz` and
  // parentheses), or a variable so declared.
  bool large_world_value(const CheckContext& ctx, int node, UnrealEra era) const {
    const SyntaxTree& t = ctx.tree;
    while (t.is(node, "parenthesized_expression")) node = t.named_child(node);
    node = without_xyz(t, node);
    if (t.is(node, "identifier")) {
      int var = ctx.world.variable_at(node);
      return var >= 0 && large_world_type(ctx.world.variables()[static_cast<size_t>(var)].type);
    }
    if (t.is(node, "call_expression")) {
      auto types = ctx.world.data().engine_function_types.find(std::string(call_name(t, node)));
      return types != ctx.world.data().engine_function_types.end() && !defines_function(t, call_name(t, node)) &&
             large_world_type(types->second[era == UnrealEra::ue5_0 ? 1 : 2]);
    }
    const WorldData::EngineMember* e = engine_member_at(ctx, node);
    return e && large_world_type(e->types[era == UnrealEra::ue5_0 ? 1 : 2]);
  }

  // An engine member whose kind UE 5.0 changed to translated world (rules/world-space.json engine
  // "structs", a fifth entry), read by code written for UE4.
  static bool translated_from_ue5(const CheckContext& ctx, int node) {
    const SyntaxTree& t = ctx.tree;
    while (t.is(node, "parenthesized_expression")) node = t.named_child(node);
    node = without_xyz(t, node);
    const WorldData::EngineMember* e = engine_member_at(ctx, node);
    return e && e->ue5_kind == Kind::translated && ctx.world.code_era() == UnrealEra::ue4 && ctx.unreal && ctx.unreal->era != UnrealEra::ue4;
  }

  bool large_world_matrix(const CheckContext& ctx, int node, UnrealEra era) const {
    Kind kind = ctx.world.kind(node);
    return (is_matrix(kind) || kind == Kind::unknown) && large_world_value(ctx, node, era);
  }

  std::vector<std::string> lwc_calls_, float_calls_;
};

}  // namespace

std::unique_ptr<Check> make_large_world_member(const RuleInfo& rule) { return std::make_unique<LargeWorldMember>(rule); }

}  // namespace lwc::checks
