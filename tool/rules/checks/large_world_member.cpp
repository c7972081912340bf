// lwc-large-world-member: a member of an engine struct that UE5 holds as a large-world type
// (ResolvedView's camera origin and translations, a primitive's transforms and positions) used
// where a float is needed. In UE5 the line stops compiling; hacked back to float it loses the
// precision the type was made for. The rewrite does the float arithmetic in the era's library.
#include <fmt/format.h>

#include "rules/checks/util.h"

namespace lwc::checks {
namespace {

bool large_world_type(std::string_view type) { return type.starts_with("FDF") || type.starts_with("FLWC"); }

class LargeWorldMember : public Check {
 public:
  explicit LargeWorldMember(const RuleInfo& rule)
      : lwc_calls_(string_list(rule.data, "lwc-calls")),
        float_calls_(string_list(rule.data, "float-calls")),
        uniform_buffer_(rule.data.at("uniform-buffer").get<std::string>()),
        uniform_buffer_call_(rule.data.at("uniform-buffer-call").get<std::string>()) {
    for (const auto& [name, owner] : rule.data.at("objects").items()) objects_[name] = owner.get<std::string>();
  }

  void run(const CheckContext& ctx) const override {
    if (!ctx.unreal) return;
    const SyntaxTree& t = ctx.tree;
    // UE4 code is read for the era it moves to: the DoubleFloat types of UE 5.4+.
    UnrealEra era = ctx.unreal->era == UnrealEra::ue5_0 ? UnrealEra::ue5_0 : UnrealEra::ue5_4;
    for (int id : nodes_of(t, "field_expression")) {
      Member m = member_of(t, id);
      if (m.empty()) continue;
      std::string owner = owner_of(ctx, id);
      const WorldData::EngineMember* e = owner.empty() ? nullptr : ctx.world.data().engine_member(owner, m.member);
      if (!e) continue;
      const std::string& type = e->types[era == UnrealEra::ue5_0 ? 1 : 2];
      if (!large_world_type(type)) continue;
      bool vector3 = e->kind == Kind::absolute || e->kind == Kind::camera_offset;
      Use use = float_use(ctx, id, vector3);
      if (use.what.empty()) continue;
      if (use.node < 0) use.node = id;
      std::string object(t.text(t.child_by_field(id, "argument")));
      Vars vars{{"object", object},
                {"member", m.member},
                {"type", type},
                {"era", std::string(era_name(era))},
                {"use", use.what},
                {"when", ctx.unreal->era == UnrealEra::ue4 ? "when this code moves to UE5" : "in " + std::string(era_name(era))}};
      Finding& f = ctx.report(t.span(id), vars);
      offer_fix(ctx, f, id, use, e->kind, era, vars);
    }
  }

 private:
  // What needs a float at a use, and the node that needs it.
  struct Use {
    std::string what;  // "" when the use takes the large-world value (or lwcport cannot tell)
    int parent = -1;
    int node = -1;     // the expression that stands for the member there (`M`, `(M)`, `M.xyz`)
  };

  // The engine struct a member access reads: a variable's declared type, or an engine global or
  // call of the rule's table when the file does not declare the name.
  std::string owner_of(const CheckContext& ctx, int field) const {
    const SyntaxTree& t = ctx.tree;
    int base = t.child_by_field(field, "argument");
    if (t.is(base, "identifier")) {
      int var = ctx.world.variable_at(base);
      if (var >= 0) return ctx.world.variables()[var].type;
      auto it = objects_.find(std::string(t.text(base)));
      return it != objects_.end() ? it->second : std::string();
    }
    if (t.is(base, "call_expression")) {
      auto it = objects_.find(std::string(call_name(t, base)) + "(..)");
      return it != objects_.end() ? it->second : std::string();
    }
    return {};
  }

  Use float_use(const CheckContext& ctx, int node, bool vector3) const {
    const SyntaxTree& t = ctx.tree;
    int p = t.at(node).parent;
    while (t.is(p, "parenthesized_expression")) node = p, p = t.at(p).parent;
    // `.xyz` of a 3-vector is the vector itself: its use is the swizzle's.
    if (vector3 && t.is(p, "field_expression") && t.child_by_field(p, "argument") == node &&
        t.child_by_field(p, "field") >= 0 && t.text(t.child_by_field(p, "field")) == "xyz") {
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
      std::string_view callee = call_name(t, call);
      if (callee.empty() || matches_any(lwc_calls_, callee)) return {};
      if (matches_any(float_calls_, callee)) return {fmt::format("passed to `{}`", callee), p};
      auto args = call_arguments(t, call);
      size_t index = std::find(args.begin(), args.end(), node) - args.begin();
      std::string param = parameter_type(ctx, callee, index);
      if (!param.empty() && ctx.world.data().is_float_type(param))
        return {fmt::format("passed to `{}`, whose parameter is a `{}`", callee, param), p};
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
  static std::string parameter_type(const CheckContext& ctx, std::string_view function, size_t index) {
    const SyntaxTree& t = ctx.tree;
    std::string type;
    int defined = -1;
    size_t seen = 0;
    for (const Variable& v : ctx.world.variables()) {
      if (v.role != Variable::Role::parameter || v.function < 0) continue;
      int declarator = t.child_by_field(v.function, "declarator");
      int name = declarator >= 0 ? t.child_by_field(declarator, "declarator") : -1;
      if (name < 0 || t.text(name) != function) continue;
      if (defined >= 0 && v.function != defined) return {};
      defined = v.function;
      if (seen++ == index) type = v.type;
    }
    return type;
  }

  // The arithmetic done in the era's large-world library, rounded to float once at the end.
  void offer_fix(const CheckContext& ctx, Finding& f, int id, const Use& use, Kind kind, UnrealEra era, Vars vars) const {
    const SyntaxTree& t = ctx.tree;
    bool df = era != UnrealEra::ue5_0;
    // UE4's primitive uniform buffer: UE5 reads the same data through a call.
    int base = t.child_by_field(id, "argument");
    std::string object(t.text(base));
    if (t.is(base, "identifier") && object == uniform_buffer_ && ctx.world.variable_at(base) < 0) object = uniform_buffer_call_;
    std::string member = object + "." + vars["member"];
    // The operand that stands for the member (through parentheses and `.xyz`) is written as the member.
    auto text = [&](int n) {
      int inner = n;
      while (t.is(inner, "parenthesized_expression")) inner = t.named_child(inner);
      return inner == id || inner == use.node ? member : std::string(t.text(n));
    };
    std::string_view ptype = t.at(use.parent).type;
    int p = use.parent;
    std::string op;
    if (int o = t.child_by_field(p, "operator"); o >= 0) op = t.text(o);
    bool position = kind == Kind::absolute || kind == Kind::camera_offset;

    // A sum or difference with a position: the era's demoting add or subtract.
    if (position && (ptype == "binary_expression" || ptype == "assignment_expression") &&
        (op == "+" || op == "-" || op == "+=" || op == "-=")) {
      int left = t.child_by_field(p, "left"), right = t.child_by_field(p, "right");
      bool subtract = op[0] == '-';
      auto wrap = [&](const std::string& a, const std::string& b) {
        return df ? fmt::format("{}({}, {})", subtract ? "DFSubtractDemote" : "DFAddDemote", a, b)
                  : fmt::format("LWCToFloat({}({}, {}))", subtract ? "LWCSubtract" : "LWCAdd", a, b);
      };
      if (ptype == "binary_expression") {
        vars["call"] = df ? (subtract ? "DFSubtractDemote" : "DFAddDemote") : (subtract ? "LWCSubtract" : "LWCAdd");
        ctx.fix(f, "demote", vars, {{t.span(p), wrap(text(left), text(right))}});
        return;
      }
      // `X += M`: the target is read once more, so only a plain name or field.
      if (t.is(left, "identifier") || t.is(left, "field_expression")) {
        vars["call"] = df ? (subtract ? "DFSubtractDemote" : "DFAddDemote") : (subtract ? "LWCSubtract" : "LWCAdd");
        ctx.fix(f, "demote", vars, {{t.span(p), fmt::format("{} = {}", t.text(left), wrap(std::string(t.text(left)), member))}});
        return;
      }
    }
    // The rotation of a transform: the era's 3x3 conversion.
    if (is_matrix(kind) && ptype == "cast_expression") {
      std::string cast(t.text(t.child_by_field(p, "type")));
      std::string call = fmt::format("{}({})", df ? "DFToFloat3x3" : "LWCToFloat3x3", member);
      if (cast.ends_with("3x3")) {
        vars["call"] = df ? "DFToFloat3x3" : "LWCToFloat3x3";
        ctx.fix(f, "rotation", vars, {{t.span(p), cast.starts_with("float") ? call : "(" + cast + ")" + call}});
        return;
      }
    }
    // A row of the rotation (`M[0].xyz`): the same row of the 3x3 conversion.
    if (is_matrix(kind) && ptype == "subscript_expression") {
      int index = t.subscript_index(p);
      int outer = t.at(p).parent;
      int field = t.is(outer, "field_expression") ? t.child_by_field(outer, "field") : -1;
      std::string_view row = index >= 0 ? t.text(index) : "";
      if ((row == "0" || row == "1" || row == "2") && field >= 0 && t.text(field) == "xyz") {
        vars["call"] = df ? "DFToFloat3x3" : "LWCToFloat3x3";
        ctx.fix(f, "rotation", vars, {{t.span(outer), fmt::format("{}({})[{}]", vars["call"], member, row)}});
        return;
      }
      if (row == "3") {
        f.withheld.push_back(fmt::format("row 3 of `{}` is its absolute translation: the computation that reads it must move to translated world", t.text(id)));
        return;
      }
    }
    // A transform by the matrix: in the library, or by its translated twin.
    if (is_matrix(kind) && ptype == "argument_list" && call_name(t, t.at(p).parent) == "mul") {
      int call = t.at(p).parent;
      auto args = call_arguments(t, call);
      std::string point = args.size() == 2 ? position_of_homogeneous(t, args[0]) : "";
      if (args.size() == 2 && (args[1] == id || args[1] == use.node) && !point.empty()) {
        // `mul(float4(P, 1), M).xyz` becomes the 3-vector itself; without the swizzle, w stays 1.
        int outer = t.at(call).parent;
        bool xyz = t.is(outer, "field_expression") && t.child_by_field(outer, "field") >= 0 && t.text(t.child_by_field(outer, "field")) == "xyz";
        Span span = t.span(xyz ? outer : call);
        auto homogeneous = [&](const std::string& p3) { return xyz ? p3 : fmt::format("float4({}, 1)", p3); };
        std::string twin = twin_of(ctx, vars["member"]);
        if (kind == Kind::world_matrix) {
          vars["call"] = df ? "DFMultiply" : "LWCMultiply";
          ctx.fix(f, "transform", vars, {{span, homogeneous(df ? fmt::format("DFDemote(DFMultiply({}, {}))", point, member)
                                                               : fmt::format("LWCToFloat(LWCMultiply({}, {}))", point, member))}});
          return;
        }
        if (!twin.empty()) {
          // A projection (w is not 1): the point moves to translated world, the matrix to its twin.
          std::string translation = object + "." + (vars["member"].starts_with("Prev") ? "PrevPreViewTranslation" : "PreViewTranslation");
          std::string moved = df ? fmt::format("DFAddDemote({}, {})", point, translation) : fmt::format("LWCToFloat(LWCAdd({}, {}))", point, translation);
          vars["call"] = df ? "DFAddDemote" : "LWCAdd";
          vars["twin"] = object + "." + twin;
          ctx.fix(f, "translated-twin", vars, {{t.span(call), fmt::format("mul(float4({}, 1), {}.{})", moved, object, twin)}});
          return;
        }
        vars["call"] = df ? "DFMultiplyDemote" : "LWCMultiply";
        ctx.fix(f, "transform", vars, {{span, homogeneous(df ? fmt::format("DFMultiplyDemote(DFPromote({}), {})", point, member)
                                                             : fmt::format("LWCMultiply(LWCPromote({}), {})", point, member))}});
        return;
      }
    }
    f.withheld.push_back(fmt::format("`{}` is an `{}` and is {} here: the computation around it must move to translated world or to the large-world library first",
                                     t.text(id), vars["type"], vars["use"]));
  }

  static std::string twin_of(const CheckContext& ctx, const std::string& member) {
    const auto& twins = ctx.world.data().twins.members;
    auto it = twins.find(member);
    return it != twins.end() ? it->second : std::string();
  }

  std::map<std::string, std::string> objects_;  // engine global or call -> its struct
  std::vector<std::string> lwc_calls_, float_calls_;
  std::string uniform_buffer_, uniform_buffer_call_;
};

}  // namespace

std::unique_ptr<Check> make_large_world_member(const RuleInfo& rule) { return std::make_unique<LargeWorldMember>(rule); }

}  // namespace lwc::checks
