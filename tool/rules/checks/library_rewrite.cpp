#include "rules/checks/library_rewrite.h"

#include <fmt/format.h>

namespace lwc::checks {

int absolute_partner(const CheckContext& ctx, int use, Kind kind) {
  const SyntaxTree& t = ctx.tree;
  int parent = t.at(use).parent;
  while (t.is(parent, "parenthesized_expression") || is_field_of(t, parent, use, "xyz")) use = parent, parent = t.at(use).parent;
  if (!t.is(parent, "binary_expression") && !t.is(parent, "assignment_expression")) return -1;
  int op = t.child_by_field(parent, "operator");
  std::string_view o = op >= 0 ? t.text(op) : "";
  int left = t.child_by_field(parent, "left"), right = t.child_by_field(parent, "right");
  int other = left == use ? right : left;
  if (other < 0) return -1;
  Kind partner = ctx.world.kind(other);
  if ((partner == Kind::absolute || partner == Kind::camera_offset) && holds_absolute(partner)) return other;
  bool add = o == "+" || o == "+=", subtract = o == "-" || o == "-=";
  if (kind == Kind::camera_offset && add) return other;
  if (kind == Kind::absolute && subtract) return other;
  return -1;
}

namespace {
// A declared type of three components (`float3`, `half3`, `MaterialFloat3`; not `float3x3`).
bool three_component_type(std::string_view type) { return type.ends_with('3') && type.find('x') == std::string_view::npos; }

// An expression lwcport can tell is a 3-vector: a name declared so, a three-letter swizzle, or an
// engine struct's member of that type in UE4 (`FMaterialPixelParameters.CameraVector`).
bool three_vector(const CheckContext& ctx, int node) {
  const SyntaxTree& t = ctx.tree;
  while (t.is(node, "parenthesized_expression")) node = t.named_child(node);
  if (t.is(node, "identifier")) {
    int var = ctx.world.variable_at(node);
    return var >= 0 && three_component_type(ctx.world.variables()[static_cast<size_t>(var)].type);
  }
  int field = t.is(node, "field_expression") ? t.child_by_field(node, "field") : -1;
  if (field >= 0 && is_swizzle(t.text(field))) return t.text(field).size() == 3;
  const WorldData::EngineMember* e = field >= 0 ? engine_member_at(ctx, node) : nullptr;
  return e && three_component_type(e->types[0]);
}

// Whether only the first three components of `node`'s value are read: through parentheses,
// negation, arithmetic and `normalize`, it reaches a `.xyz`, a 3-vector declaration, assignment or
// return, or a `length`/`dot`/`distance`. (A 3-vector times a 4x4 transform is a 4-vector whose w
// is 0 for an affine transform: the 3x3 product is the same vector wherever only xyz count.)
bool read_as_three(const CheckContext& ctx, int node) {
  const SyntaxTree& t = ctx.tree;
  for (int p = t.at(node).parent; p >= 0; node = p, p = t.at(p).parent) {
    if (t.is(p, "parenthesized_expression") || t.is(p, "unary_expression") || t.is(p, "binary_expression")) continue;
    if (is_field_of(t, p, node, "xyz")) return true;
    if (t.is(p, "argument_list")) {
      std::string_view callee = call_name(t, t.at(p).parent);
      if (callee == "length" || callee == "dot" || callee == "distance") return true;
      if (callee != "normalize") return false;
      p = t.at(p).parent;
      continue;
    }
    if (t.is(p, "init_declarator")) {
      int declaration = t.at(p).parent;
      int type = t.is(declaration, "declaration") ? t.child_by_field(declaration, "type") : -1;
      return type >= 0 && three_component_type(t.text(type));
    }
    if (t.is(p, "assignment_expression")) return t.child_by_field(p, "right") == node && three_vector(ctx, t.child_by_field(p, "left"));
    if (t.is(p, "return_statement")) {
      int fn = p;
      while (fn >= 0 && !t.is(fn, "function_definition")) fn = t.at(fn).parent;
      int type = fn >= 0 ? t.child_by_field(fn, "type") : -1;
      return type >= 0 && three_component_type(t.text(type));
    }
    return false;
  }
  return false;
}
}  // namespace

LibraryRewrite library_rewrite(const CheckContext& ctx, const LargeWorldValue& value, bool df) {
  const SyntaxTree& t = ctx.tree;
  const WorldData& data = ctx.world.data();
  LibraryRewrite out;
  int node = value.node, p = t.at(node).parent;
  while (t.is(p, "parenthesized_expression")) node = p, p = t.at(p).parent;
  if (p < 0) return out;
  // `(float3x3)(X)` is parsed as a call: the cast is the call, its type the parenthesised name.
  int cast_type = -1;
  if (t.is(p, "argument_list") && (cast_type = t.cast_written_as_call(t.at(p).parent)) >= 0) p = t.at(p).parent;
  else if (t.is(p, "cast_expression")) cast_type = t.child_by_field(p, "type");
  // The operand that stands for the value (through parentheses) is written as the value.
  auto text = [&](int n) {
    int inner = n;
    while (t.is(inner, "parenthesized_expression")) inner = t.named_child(inner);
    return inner == value.node ? value.text : std::string(t.text(n));
  };
  std::string_view ptype = t.at(p).type;
  std::string op;
  if (int o = t.child_by_field(p, "operator"); o >= 0) op = t.text(o);
  bool position = value.kind == Kind::absolute || value.kind == Kind::camera_offset;

  // A sum or difference with a position: the era's demoting add or subtract.
  if (position && (ptype == "binary_expression" || ptype == "assignment_expression") && (op == "+" || op == "-" || op == "+=" || op == "-=")) {
    int left = t.child_by_field(p, "left"), right = t.child_by_field(p, "right");
    bool subtract = op[0] == '-';
    out.vars["call"] = df ? (subtract ? "DFSubtractDemote" : "DFAddDemote") : (subtract ? "LWCSubtract" : "LWCAdd");
    auto call = [&](const std::string& a, const std::string& b) {
      return df ? fmt::format("{}({}, {})", out.vars["call"], a, b) : fmt::format("LWCToFloat({}({}, {}))", out.vars["call"], a, b);
    };
    if (ptype == "binary_expression") {
      out.fix = "demote";
      out.edits = {{t.span(p), call(text(left), text(right))}};
      return out;
    }
    // `X += M`: the target is read once more, so only a plain name or field.
    if (t.is(left, "identifier") || t.is(left, "field_expression")) {
      out.fix = "demote";
      out.edits = {{t.span(p), fmt::format("{} = {}", t.text(left), call(std::string(t.text(left)), text(right)))}};
      return out;
    }
    return out;
  }
  if (!is_matrix(value.kind)) return out;
  std::string to3x3 = df ? "DFToFloat3x3" : "LWCToFloat3x3";
  // The rotation of a transform: the era's 3x3 conversion.
  if (cast_type >= 0) {
    std::string cast(t.text(cast_type));
    if (!cast.ends_with("3x3")) return out;
    std::string call = fmt::format("{}({})", to3x3, value.text);
    out.fix = "rotation";
    out.vars["call"] = to3x3;
    out.edits = {{t.span(p), cast.starts_with("float") ? call : "(" + cast + ")" + call}};
    return out;
  }
  // Stored into a 3x3 declaration (`float3x3 R = M;`, HLSL keeps the upper-left block): the same
  // rotation, taken by the era's 3x3 conversion.
  if (ptype == "init_declarator" && t.child_by_field(p, "value") == node) {
    int declaration = t.at(p).parent;
    int type = t.is(declaration, "declaration") ? t.child_by_field(declaration, "type") : -1;
    if (type < 0 || !t.text(type).ends_with("3x3")) return out;
    out.fix = "rotation";
    out.vars["call"] = to3x3;
    out.edits = {{t.span(node), fmt::format("{}({})", to3x3, value.text)}};
    return out;
  }
  // A row of the rotation (`M[0].xyz`): the same row of the 3x3 conversion.
  if (ptype == "subscript_expression") {
    int index = t.subscript_index(p);
    std::string_view row = index >= 0 ? t.text(index) : "";
    int outer = t.at(p).parent;
    if ((row == "0" || row == "1" || row == "2") && is_field_of(t, outer, p, "xyz")) {
      out.fix = "rotation";
      out.vars["call"] = to3x3;
      out.edits = {{t.span(outer), fmt::format("{}({})[{}]", to3x3, value.text, row)}};
    } else if (row == "3") {
      out.blocker = fmt::format("row 3 of `{}` is its absolute translation: the computation that reads it must move to translated world", t.text(node));
    }
    return out;
  }
  // A point transformed by the matrix: in the library, or by its translated twin.
  if (ptype != "argument_list" || call_name(t, t.at(p).parent) != "mul") return out;
  int call = t.at(p).parent;
  auto args = call_arguments(t, call);
  std::string point = args.size() == 2 && args[1] == node ? position_of_homogeneous(t, args[0]) : "";
  bool xyz = is_field_of(t, t.at(call).parent, call, "xyz");
  auto twin = data.twins.members.find(value.member);
  bool view = !value.object.empty() && matches_any(data.twins.objects, value.object);
  if (point.empty()) {
    // A direction (`mul(float4(D, 0), M)`): no translation moves it, so the view's translated twin
    // gives the same vector, and any transform's 3x3 part does.
    std::string direction = args.size() == 2 && args[1] == node ? direction_of_homogeneous(t, args[0]) : "";
    // A 3-vector times the 4x4 transform of an object (HLSL takes its upper 3x4 block): the
    // rotation alone, where only xyz of the product are read. A view's matrices may project
    // (w is not 0 then), so only the object's transforms.
    if (direction.empty() && args.size() == 2 && args[1] == node && !view &&
        (value.kind == Kind::world_matrix || value.kind == Kind::from_world_matrix) &&
        three_vector(ctx, args[0]) && read_as_three(ctx, call)) {
      out.fix = "rotation";
      out.vars["call"] = to3x3;
      out.edits = {{t.span(node), fmt::format("{}({})", to3x3, value.text)}};
      return out;
    }
    if (direction.empty()) return out;
    if (view && twin != data.twins.members.end()) {
      out.fix = "direction-twin";
      out.vars["twin"] = (value.object == "View" ? "PrimaryView" : value.object) + "." + twin->second;
      out.edits = {{t.span(node), out.vars["twin"]}};
    } else if (xyz) {
      out.fix = "rotation";
      out.vars["call"] = to3x3;
      out.edits = {{t.span(t.at(call).parent), fmt::format("mul({}, {}({}))", direction, to3x3, value.text)}};
    }
    return out;
  }
  // `mul(float4(P, 1), M).xyz` becomes the 3-vector itself; without the swizzle, w stays 1.
  Span span = t.span(xyz ? t.at(call).parent : call);
  auto homogeneous = [&](const std::string& p3) { return xyz ? p3 : fmt::format("float4({}, 1)", p3); };
  if (value.kind == Kind::world_matrix && !xyz && view && twin != data.twins.members.end()) {
    // From clip or screen space the product's w is not 1, and the code reads it.
    out.blocker = fmt::format("`{}` is a projection whose w the code reads: the reconstruction must move to its translated twin "
                              "(`{}`) as a whole", value.text, twin->second);
  } else if (value.kind == Kind::world_matrix) {
    out.fix = "transform";
    out.vars["call"] = df ? "DFMultiply" : "LWCMultiply";
    out.edits = {{span, homogeneous(df ? fmt::format("DFDemote(DFMultiply({}, {}))", point, value.text)
                                       : fmt::format("LWCToFloat(LWCMultiply({}, {}))", point, value.text))}};
  } else if (view && twin != data.twins.members.end()) {
    // A projection (w is not 1): the point moves to translated world, the matrix to its twin.
    std::string object = value.object == "View" ? "PrimaryView" : value.object;
    std::string translation = object + "." + (value.member.starts_with("Prev") ? "PrevPreViewTranslation" : "PreViewTranslation");
    std::string moved = df ? fmt::format("DFAddDemote({}, {})", point, translation) : fmt::format("LWCToFloat(LWCAdd({}, {}))", point, translation);
    out.fix = "translated-twin";
    out.vars["call"] = df ? "DFAddDemote" : "LWCAdd";
    out.vars["twin"] = object + "." + twin->second;
    out.edits = {{t.span(call), fmt::format("mul(float4({}, 1), {})", moved, out.vars["twin"])}};
  } else {
    out.fix = "transform";
    out.vars["call"] = df ? "DFMultiplyDemote" : "LWCMultiply";
    out.edits = {{span, homogeneous(df ? fmt::format("DFMultiplyDemote(DFPromote({}), {})", point, value.text)
                                       : fmt::format("LWCMultiply(LWCPromote({}), {})", point, value.text))}};
  }
  return out;
}

}  // namespace lwc::checks
