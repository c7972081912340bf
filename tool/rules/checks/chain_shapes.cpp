#include "rules/checks/chain_shapes.h"

#include <algorithm>

namespace lwc::checks {

// `V += PreViewTranslation;` (or `V.xyz += ...`) as a statement of the function's own body, not
// under a branch or a loop: the statement, or -1.
int rebase_statement(const CheckContext& ctx, int use) {
  const SyntaxTree& t = ctx.tree;
  int target = use, assignment = t.at(use).parent;
  if (is_field_of(t, assignment, use, "xyz")) target = assignment, assignment = t.at(assignment).parent;
  if (!t.is(assignment, "assignment_expression") || t.child_by_field(assignment, "left") != target ||
      t.text(t.child_by_field(assignment, "operator")) != "+=" || ctx.world.kind(t.child_by_field(assignment, "right")) != Kind::camera_offset)
    return -1;
  int statement = t.at(assignment).parent;
  return unconditional_statement(t, statement) ? statement : -1;
}

// The largest expression around a use that is still the same point, moved by the same
// translation: through parentheses, `.xyz`, a perspective divide (`H.xyz / H.w`), and a small
// offset added to it or taken from it.
int climb_point(const CheckContext& ctx, int n) {
  const SyntaxTree& t = ctx.tree;
  for (;;) {
    int p = t.at(n).parent;
    if (p < 0) return n;
    if (t.is(p, "parenthesized_expression") || is_field_of(t, p, n, "xyz")) {
      n = p;
      continue;
    }
    if (!t.is(p, "binary_expression")) return n;
    std::string_view op = t.text(t.child_by_field(p, "operator"));
    int left = t.child_by_field(p, "left"), right = t.child_by_field(p, "right");
    int other = left == n ? right : left;
    bool small = op == "/" ? small_vector(ctx, other) : point_offset(ctx, other, op, p);
    if ((op == "/" && left == n && small) || (op == "+" && small) || (op == "-" && left == n && small)) {
      n = p;
      continue;
    }
    return n;
  }
}

// `float4(P, W)` around P (its first argument) with W no homogeneous 0 or 1: the call, or -1.
int packed_point(const SyntaxTree& t, int point) {
  int list = t.at(point).parent;
  int call = t.is(list, "argument_list") ? t.at(list).parent : -1;
  if (call < 0 || (call_name(t, call) != "float4" && call_name(t, call) != "vec4")) return -1;
  auto args = call_arguments(t, call);
  if (args.size() != 2 || args[0] != point) return -1;
  if (!position_of_homogeneous(t, call).empty() || !direction_of_homogeneous(t, call).empty()) return -1;
  return call;
}

// A kind that is a point in some frame (absolute, translated, or the camera offset).
bool is_position(Kind k) { return k == Kind::absolute || k == Kind::translated || k == Kind::camera_offset; }

// A vector that is not a position: small by its kind, or built only from names that say so
// (`Normal * Bias`, `Dir * T`) and numbers.
namespace {
// A name that says direction or normal, in any space (`WorldNormal`, `RayDirection`, `ViewForward`):
// no position.
bool direction_name(std::string_view name) {
  for (std::string_view end : {"Normal", "normal", "Dir", "Direction", "direction", "Forward"})
    if (name.ends_with(end)) return true;
  return false;
}

bool scalar_type(std::string_view type) {
  return type == "float" || type == "half" || type == "int" || type == "uint" || type == "min16float" || type == "double";
}

bool small_vector_at(const CheckContext& ctx, int n, int depth) {
  Kind kind = ctx.world.kind(n);
  if (kind == Kind::local || kind == Kind::direction) return true;
  if (kind != Kind::unknown) return false;
  const SyntaxTree& t = ctx.tree;
  bool small = false;  // some factor is a vector known to be no position; scalars only scale it
  std::vector<int> stack{n};
  while (!stack.empty()) {
    int m = stack.back();
    stack.pop_back();
    if (t.is(m, "identifier") || t.is(m, "field_identifier")) {
      Kind k = ctx.world.kind(m);
      int var = t.is(m, "identifier") ? ctx.world.variable_at(m) : -1;
      const Variable* v = var >= 0 ? &ctx.world.variables()[var] : nullptr;
      if (k == Kind::local || k == Kind::direction || ctx.world.data().named_kind(t.text(m), Kind::absolute) == Kind::local ||
          (k == Kind::unknown && direction_name(t.text(m))))
        small = true;
      else if (k != Kind::unknown)
        return false;
      else if (v && scalar_type(v->type))
        continue;
      // A local whose value is such a vector (`float3 L = normalize(ToLight);`).
      else if (v && v->role == Variable::Role::local && v->init >= 0 && depth < 3 && small_vector_at(ctx, v->init, depth + 1))
        small = true;
      else
        return false;
    } else if (int field = t.is(m, "field_expression") ? t.child_by_field(m, "field") : -1; field >= 0) {
      // A member is what its name says (`View.ViewForward`), whatever its object is called.
      Kind k = ctx.world.kind(m);
      if (k == Kind::local || k == Kind::direction || (k == Kind::unknown && direction_name(t.text(field))))
        small = true;
      else if (k != Kind::unknown || ctx.world.data().named_kind(t.text(field), Kind::absolute) != Kind::local)
        return false;
      else
        small = true;
      continue;
    } else if (t.is(m, "call_expression")) {
      // A unit vector, whatever it was made from.
      if (call_name(t, m) != "normalize") return false;
      small = true;
      continue;
    }
    for (int c : t.named_children(m)) stack.push_back(c);
  }
  return small;
}
}  // namespace

bool small_vector(const CheckContext& ctx, int n) { return small_vector_at(ctx, n, 0); }

namespace {
// Broader than named_as_point: any name that might be a point (a corner, a ray's end, a bound)
// keeps a vector from being taken for an offset.
bool might_name_point(std::string_view name) {
  for (std::string_view w : {"Pos", "pos", "Center", "center", "Centre", "Origin", "origin", "Location", "Point", "point", "Min", "Max",
                             "Corner", "Bound", "Start", "End", "Eye", "Camera", "Sphere", "Translation"})
    if (name.find(w) != std::string_view::npos) return true;
  return false;
}

bool says_offset(std::string_view name) {
  for (std::string_view w : {"Bias", "Offset", "Delta", "Step", "Jitter", "Extent", "Radius"})
    if (name.find(w) != std::string_view::npos) return true;
  return false;
}

// No identifier, member or call in `n` is known to be a position or matrix, or named as a point.
bool holds_no_point(const CheckContext& ctx, int n) {
  const SyntaxTree& t = ctx.tree;
  std::vector<int> stack{n};
  while (!stack.empty()) {
    int m = stack.back();
    stack.pop_back();
    Kind k = ctx.world.kind(m);
    if (k != Kind::unknown && k != Kind::local && k != Kind::direction) return false;
    if (t.is(m, "identifier") || t.is(m, "field_identifier")) {
      if (might_name_point(t.text(m))) return false;
    } else if (t.is(m, "call_expression")) {
      // What a call returns is its own (a jitter made from the pixel's position is no position);
      // its kind above says where it is known.
      if (call_name(t, m) == "mul" || might_name_point(call_name(t, m))) return false;
      continue;
    }
    for (int c : t.named_children(m)) stack.push_back(c);
  }
  return true;
}

bool scalar_term(const CheckContext& ctx, int n) {
  const SyntaxTree& t = ctx.tree;
  if (t.is(n, "number_literal")) return true;
  int var = t.is(n, "identifier") ? ctx.world.variable_at(n) : -1;
  return var >= 0 && scalar_type(ctx.world.variables()[var].type) && !is_position(ctx.world.kind(n));
}

// `(A + B) * 0.5`, `(A + B) / 2`: the sum is averaged (a midpoint), not a point moved.
bool averaged(const SyntaxTree& t, int sum) {
  int n = sum, p = t.at(n).parent;
  while (t.is(p, "parenthesized_expression")) n = p, p = t.at(p).parent;
  if (!t.is(p, "binary_expression")) return false;
  std::string_view op = t.text(t.child_by_field(p, "operator"));
  return op == "*" || op == "/";
}
}  // namespace

bool point_offset(const CheckContext& ctx, int other, std::string_view op, int sum) {
  const SyntaxTree& t = ctx.tree;
  while (t.is(other, "parenthesized_expression")) other = t.named_child(other);
  if (small_vector(ctx, other) || scalar_term(ctx, other)) return true;
  if (!holds_no_point(ctx, other)) return false;
  if (op == "+") return sum < 0 || !averaged(t, sum);
  int name = t.is(other, "field_expression") ? t.child_by_field(other, "field") : other;
  return (t.is(name, "identifier") || t.is(name, "field_identifier")) && says_offset(t.text(name));
}

bool shifted_in_place(const CheckContext& ctx, int use) {
  const SyntaxTree& t = ctx.tree;
  int target = use, parent = t.at(use).parent;
  bool component = false;
  if (t.is(parent, "field_expression") && t.child_by_field(parent, "argument") == use) {
    std::string_view field = t.text(t.child_by_field(parent, "field"));
    if (field != "x" && field != "y" && field != "z" && field != "xyz") return false;
    component = field.size() == 1;
    target = parent, parent = t.at(parent).parent;
  }
  if (!t.is(parent, "assignment_expression") || t.child_by_field(parent, "left") != target) return false;
  std::string_view op = t.text(t.child_by_field(parent, "operator"));
  if (op != "+=" && op != "-=") return false;
  int offset = t.child_by_field(parent, "right");
  if (point_offset(ctx, offset, op == "+=" ? "+" : "-", -1)) return true;
  // One coordinate moved by a scalar: every identifier in it a scalar that is no position.
  if (!component) return false;
  std::vector<int> stack{offset};
  while (!stack.empty()) {
    int m = stack.back();
    stack.pop_back();
    if (t.is(m, "call_expression")) return false;
    if (t.is(m, "identifier")) {
      int var = ctx.world.variable_at(m);
      if (var < 0 || !scalar_type(ctx.world.variables()[var].type) || is_position(ctx.world.kind(m))) return false;
    }
    for (int c : t.named_children(m)) stack.push_back(c);
  }
  return true;
}

// `X + PreViewTranslation` (either order, through parentheses) around an expression: the sum, or -1.
int pre_view_sum(const CheckContext& ctx, int expr) {
  const SyntaxTree& t = ctx.tree;
  int parent = t.at(expr).parent;
  while (t.is(parent, "parenthesized_expression")) expr = parent, parent = t.at(expr).parent;
  if (!t.is(parent, "binary_expression") || t.text(t.child_by_field(parent, "operator")) != "+") return -1;
  int left = t.child_by_field(parent, "left"), right = t.child_by_field(parent, "right");
  return ctx.world.kind(left == expr ? right : left) == Kind::camera_offset ? parent : -1;
}

// `text` (which starts at `offset` in the file) with edits inside it applied.
std::string spliced(std::string text, uint32_t offset, std::vector<Edit> edits) {
  std::sort(edits.begin(), edits.end(), [](const Edit& a, const Edit& b) { return a.span.begin > b.span.begin; });
  for (const Edit& e : edits) text.replace(e.span.begin - offset, e.span.end - e.span.begin, e.text);
  return text;
}

// Some edit of the plan rewrites `span` (or text around it).
bool covered(const RewritePlan& plan, Span span) {
  return std::any_of(plan.edits.begin(), plan.edits.end(), [&](const Edit& e) { return e.span.begin <= span.begin && span.end <= e.span.end; });
}

// The calls of function `fn` in this file: its name, with as many arguments as it takes.
std::vector<int> calls_to(const SyntaxTree& t, int fn) {
  std::string_view name = t.text(function_name(t, fn));
  size_t arity = function_arity(t, fn);
  std::vector<int> out;
  for (int c : t.calls_named(name))
    if (call_arguments(t, c).size() == arity) out.push_back(c);
  return out;
}


void collect_returns(const SyntaxTree& t, int node, std::vector<int>& out) {
  if (node < 0) return;
  if (t.is(node, "return_statement")) out.push_back(node);
  for (int c : t.named_children(node))
    if (!t.is(c, "function_definition")) collect_returns(t, c, out);
}

// A file compiled as one program (an Unreal .usf, a GLSL stage): nothing outside it calls its functions.
bool whole_program(const SyntaxTree& t) {
  const std::string& p = t.source->path();
  for (const char* ext : {".usf", ".vert", ".frag", ".comp", ".geom", ".tesc", ".tese"})
    if (p.ends_with(ext)) return true;
  return false;
}

// The parameter of a function of this file that an argument is passed to, or -1.
int parameter_of(const CheckContext& ctx, int argument) {
  const SyntaxTree& t = ctx.tree;
  int list = t.at(argument).parent;
  if (!t.is(list, "argument_list")) return -1;
  int call = t.at(list).parent;
  std::string_view callee = call_name(t, call);
  auto args = call_arguments(t, call);
  size_t index = std::find(args.begin(), args.end(), argument) - args.begin();
  // The definition taking that many arguments, else the first of that name.
  const std::vector<int>& defs = t.definitions_named(callee);
  if (defs.empty()) return -1;
  int fn = defined_function(t, callee, args.size());
  if (fn < 0) fn = defs.front();
  return parameter_variable(ctx, fn, index);
}

bool stores_into(const CheckContext& ctx, int use) {
  const SyntaxTree& t = ctx.tree;
  int node = use, parent = t.at(use).parent;
  while ((t.is(parent, "field_expression") || t.is(parent, "subscript_expression")) && t.child_by_field(parent, "argument") == node)
    node = parent, parent = t.at(node).parent;
  if ((t.is(parent, "assignment_expression") && t.child_by_field(parent, "left") == node) || t.is(parent, "update_expression")) return true;
  int p = parameter_of(ctx, use);
  return p >= 0 && ctx.world.variables()[static_cast<size_t>(p)].output;
}

// The `out` parameter (not `inout`: that reads the value too) an argument is passed to, or -1.
int out_parameter_of(const CheckContext& ctx, int argument) {
  int param = parameter_of(ctx, argument);
  if (param < 0 || !ctx.world.variables()[param].output) return -1;
  auto words = leading_words(ctx.tree, ctx.world.variables()[param].declaration);
  return std::find(words.begin(), words.end(), "out") != words.end() ? param : -1;
}

int calls_of(const SyntaxTree& t, std::string_view name) { return static_cast<int>(t.calls_named(name).size()); }

bool moving(const RewritePlan& plan, int var) {
  return std::find(plan.moving_variables.begin(), plan.moving_variables.end(), var) != plan.moving_variables.end();
}

}  // namespace lwc::checks
