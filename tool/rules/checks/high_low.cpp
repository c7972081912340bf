#include "rules/checks/high_low.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>

#include <fmt/format.h>

#include "shaderlib/shaderlib.h"

namespace lwc::checks {

bool CameraNames::is_camera(const Variable& v) const {
  if (!v.uniform || v.kind != Kind::absolute) return false;
  std::string lower = v.name;
  for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return std::any_of(words.begin(), words.end(), [&](const std::string& w) { return lower.find(w) != std::string::npos; });
}

namespace {

bool glsl(const SyntaxTree& t) { return t.lang == Lang::glsl; }

int variable_named(const WorldModel& world, const std::string& name) {
  const auto& vars = world.variables();
  for (size_t i = 0; i < vars.size(); ++i)
    if (vars[i].name == name) return static_cast<int>(i);
  return -1;
}

// A global uniform referred to by an identifier node, or -1.
int uniform_at(const CheckContext& ctx, int node, Kind kind) {
  if (!ctx.tree.is(node, "identifier")) return -1;
  int var = ctx.world.variable_at(node);
  if (var < 0) return -1;
  const Variable& v = ctx.world.variables()[var];
  return v.uniform && v.role == Variable::Role::global && v.kind == kind ? var : -1;
}

uint32_t line_start(const SyntaxTree& t, uint32_t offset) {
  return t.source->offset({t.source->position(offset).line, 1});
}

// The whole declaration of a variable, from its first qualifier (HLSL masks some) to the `;`.
Span declaration_span(const SyntaxTree& t, const Variable& v) {
  auto words = leading_words(t, v.declaration);
  uint32_t begin = t.at(v.declaration).begin;
  if (!words.empty()) begin = std::min(begin, static_cast<uint32_t>(words.front().data() - t.source->text().data()));
  return {begin, t.at(v.declaration).end};
}

// One variable per declaration, and no layout qualifier to copy: the declaration can be split.
std::string why_not_splittable(const SyntaxTree& t, const Variable& v) {
  int declarators = 0;
  for (int c : t.named_children(v.declaration)) declarators += t.at(c).field && std::string_view(t.at(c).field) == "declarator";
  if (declarators != 1) return fmt::format("`{}` is declared together with other names", v.name);
  for (std::string_view w : leading_words(t, v.declaration))
    if (w == "layout") return fmt::format("`{}` has a layout qualifier, and lwcport does not choose locations for new uniforms", v.name);
  return {};
}

// The qualifiers of a declaration without matrix layout words: what a new sibling declaration takes.
std::string sibling_prefix(const SyntaxTree& t, const Variable& v) {
  std::string out;
  for (std::string_view w : leading_words(t, v.declaration))
    if (w != "row_major" && w != "column_major") out += std::string(w) + " ";
  return out;
}

std::string indentation(const SyntaxTree& t, uint32_t offset) {
  uint32_t begin = line_start(t, offset);
  std::string_view before = t.source->slice({begin, offset});
  return before.find_first_not_of(" \t") == std::string_view::npos ? std::string(before) : std::string();
}

// `use` or `use.xyz`: the node standing for the value, and its swizzle ("" when none).
struct Value {
  int node;
  std::string swizzle;
};
Value value_at(const SyntaxTree& t, int use) {
  int parent = t.at(use).parent;
  if (t.is(parent, "field_expression") && t.child_by_field(parent, "argument") == use) {
    std::string_view field = t.text(t.child_by_field(parent, "field"));
    if (!field.empty() && field.find_first_not_of("xyzw") == std::string_view::npos) return {parent, std::string(field)};
  }
  return {use, ""};
}

// The rewrite of one variable's uses into its translated name.
class Follower {
 public:
  Follower(const CheckContext& ctx, const CameraNames& camera, RewritePlan& plan) : ctx_(ctx), t_(ctx.tree), camera_(camera), plan_(plan) {}

  void follow(int var, const std::string& new_name) {
    for (int use : ctx_.world.uses(var)) {
      if (!plan_.blocker.empty()) return;
      Value value = value_at(t_, use);
      std::string renamed = new_name + (value.swizzle.empty() ? "" : "." + value.swizzle);
      if (!camera_difference(value.node, renamed) && !camera_distance(value.node, renamed) && !local_offset(value.node, use, new_name) &&
          !from_world_transform(value.node, use, new_name) && !stage_output(value.node, use, new_name))
        plan_.blocker = escape(t_, value.node);
    }
  }

 private:
  bool is_camera(int node) const {
    int var = t_.is(node, "identifier") ? ctx_.world.variable_at(node) : -1;
    return var >= 0 && camera_.is_camera(ctx_.world.variables()[var]);
  }

  // X - camera -> X'; camera - X -> -X' (unary minus binds tighter than anything around it).
  bool camera_difference(int node, const std::string& renamed) {
    int partner = subtraction_partner(t_, node);
    if (partner < 0 || !is_camera(partner)) return false;
    int difference = t_.at(partner).parent;
    bool camera_first = t_.child_by_field(difference, "left") == partner;
    plan_.edits.push_back({t_.span(difference), camera_first ? "-" + renamed : renamed});
    return true;
  }

  // distance(X, camera) -> length(X').
  bool camera_distance(int node, const std::string& renamed) {
    int list = t_.at(node).parent;
    int call = t_.is(list, "argument_list") ? t_.at(list).parent : -1;
    if (call < 0 || call_name(t_, call) != "distance") return false;
    auto args = call_arguments(t_, call);
    if (args.size() != 2 || !is_camera(args[0] == node ? args[1] : args[0])) return false;
    plan_.edits.push_back({t_.span(call), "length(" + renamed + ")"});
    return true;
  }

  // X += d, X.y -= d with d a local or a direction: moving a translated position by a small
  // offset keeps it translated.
  bool local_offset(int node, int use, const std::string& new_name) {
    int assign = t_.at(node).parent;
    if (!t_.is(assign, "assignment_expression") || t_.child_by_field(assign, "left") != node) return false;
    std::string_view op = t_.text(t_.child_by_field(assign, "operator"));
    Kind offset = ctx_.world.kind(t_.child_by_field(assign, "right"));
    if ((op != "+=" && op != "-=") || holds_absolute(offset) || offset == Kind::translated) return false;
    plan_.edits.push_back({t_.span(use), new_name});
    return true;
  }

  // viewMatrix * X (GLSL, also `P * viewMatrix * X`) or mul(X, ViewProj) (HLSL), the matrix a
  // from-world uniform read only here: it becomes its translated twin, a new uniform.
  bool from_world_transform(int node, int use, const std::string& new_name) {
    // A position used as vec4(X, 1.0) / float4(X, 1): the transform applies to the wrapper.
    if (int wrapper = homogeneous_wrapper(t_, node); wrapper >= 0) node = wrapper;
    int parent = t_.at(node).parent, matrix = -1;
    if (glsl(t_) && t_.is(parent, "binary_expression") && t_.child_by_field(parent, "right") == node &&
        t_.text(t_.child_by_field(parent, "operator")) == "*") {
      matrix = t_.child_by_field(parent, "left");
      if (t_.is(matrix, "binary_expression") && t_.text(t_.child_by_field(matrix, "operator")) == "*")
        matrix = t_.child_by_field(matrix, "right");
    } else if (!glsl(t_) && t_.is(parent, "argument_list")) {
      int call = t_.at(parent).parent;
      auto args = call_arguments(t_, call);
      if (call_name(t_, call) == "mul" && args.size() == 2 && args[0] == node) matrix = args[1];
    }
    int var = matrix >= 0 ? uniform_at(ctx_, matrix, Kind::from_world_matrix) : -1;
    if (var < 0) return false;
    const Variable& v = ctx_.world.variables()[var];
    std::string twin = translated_name(v.name);
    if (!can_rename(var, twin, fmt::format("`{}` is read", v.name))) return true;
    plan_.edits.push_back({t_.span(use), new_name});
    plan_.edits.push_back({t_.span(matrix), twin});
    plan_.edits.push_back({t_.span(v.decl), twin});
    plan_.notes.push_back(fmt::format(
        "`{}` replaces `{}`: the same matrix times a translation by the camera position, computed in double on the host "
        "(it takes camera-relative positions; for a rigid view its translation is zero)",
        twin, v.name));
    return true;
  }

  // out = X / out = X.xyz with `out` a stage output written only here: the output is renamed and
  // carries the translated position; the next stage must read it under its new name.
  bool stage_output(int node, int use, const std::string& new_name) {
    int assign = t_.at(node).parent;
    if (!t_.is(assign, "assignment_expression") || t_.child_by_field(assign, "right") != node) return false;
    int left = t_.child_by_field(assign, "left");
    int var = t_.is(left, "identifier") ? ctx_.world.variable_at(left) : -1;
    if (var < 0) return false;
    const Variable& out = ctx_.world.variables()[var];
    auto words = leading_words(t_, out.declaration);
    if (out.role != Variable::Role::global || std::find(words.begin(), words.end(), "out") == words.end()) return false;
    std::string renamed = translated_name(out.name);
    if (!can_rename(var, renamed, fmt::format("the output `{}` is written", out.name))) return true;
    plan_.edits.push_back({t_.span(use), new_name});
    plan_.edits.push_back({t_.span(left), renamed});
    plan_.edits.push_back({t_.span(out.decl), renamed});
    plan_.interface.push_back(fmt::format("`{}` -> `{}`", out.name, renamed));
    plan_.notes.push_back(fmt::format(
        "the output `{}` is now `{}`, a camera-relative position: the next stage must read `{}` (lwcport rewrites its "
        "`in {} {}` the same way)",
        out.name, renamed, renamed, out.type, out.name));
    return true;
  }

  // A uniform or output used only here may take the new name; otherwise the plan is blocked
  // (`what` says how it is used elsewhere).
  bool can_rename(int var, const std::string& renamed, const std::string& what) {
    if (ctx_.world.uses(var).size() != 1)
      plan_.blocker = fmt::format("{} elsewhere too, so it cannot become `{}`", what, renamed);
    else if (variable_named(ctx_.world, renamed) >= 0)
      plan_.blocker = fmt::format("the name `{}` is already taken", renamed);
    return plan_.blocker.empty();
  }

  const CheckContext& ctx_;
  const SyntaxTree& t_;
  const CameraNames& camera_;
  RewritePlan& plan_;
};

// `M * vec4(P, 1.0)` (GLSL), `mul(float4(P, 1), M)` or `mul(M, float4(P, 1))` (HLSL), perhaps
// parenthesised and swizzled `.xyz`, with M a world-matrix uniform.
struct WorldTransform {
  int matrix = -1;       // the identifier node
  std::string position;  // P as text, parenthesised when it is not a primary expression
  bool row_vector = false;
  bool swizzled = false;
};

std::string operand(const SyntaxTree& t, int homogeneous) {
  auto args = call_arguments(t, homogeneous);
  std::string p = position_of_homogeneous(t, homogeneous);
  bool primary = args.size() > 2 || t.is(args[0], "identifier") || t.is(args[0], "field_expression") ||
                 t.is(args[0], "call_expression") || t.is(args[0], "parenthesized_expression");
  return primary ? p : "(" + p + ")";
}

WorldTransform world_transform(const CheckContext& ctx, int node) {
  const SyntaxTree& t = ctx.tree;
  WorldTransform out;
  if (t.is(node, "field_expression")) {
    if (t.text(t.child_by_field(node, "field")) != "xyz") return out;
    node = t.child_by_field(node, "argument");
    out.swizzled = true;
  }
  while (t.is(node, "parenthesized_expression")) node = t.named_children(node).front();
  int matrix = -1, position = -1;
  if (glsl(t) && t.is(node, "binary_expression") && t.text(t.child_by_field(node, "operator")) == "*") {
    matrix = t.child_by_field(node, "left");
    position = t.child_by_field(node, "right");
  } else if (!glsl(t) && t.is(node, "call_expression") && call_name(t, node) == "mul" && call_arguments(t, node).size() == 2) {
    auto args = call_arguments(t, node);
    out.row_vector = !position_of_homogeneous(t, args[0]).empty();
    position = out.row_vector ? args[0] : args[1];
    matrix = out.row_vector ? args[1] : args[0];
  }
  if (position < 0 || position_of_homogeneous(t, position).empty() || uniform_at(ctx, matrix, Kind::world_matrix) < 0) return out;
  out.matrix = matrix;
  out.position = operand(t, position);
  return out;
}

// modelMatrix -> model, gWorld -> gWorld: the stem the new uniforms are named from.
std::string stem(const std::string& name) {
  for (const char* suffix : {"Matrix", "_matrix", "Mat"})
    if (name.size() > std::string_view(suffix).size() && name.ends_with(suffix))
      return name.substr(0, name.size() - std::string_view(suffix).size());
  return name;
}

// The file's top-level `#version` directive, or -1.
}  // namespace

RewritePlan plan_high_low(const CheckContext& ctx, int var, const CameraNames& camera) {
  const SyntaxTree& t = ctx.tree;
  const Variable& v = ctx.world.variables()[var];
  WorldTransform transform = world_transform(ctx, v.init);
  if (transform.matrix < 0)
    return withheld(fmt::format("its value (`{}`) is not a world-matrix uniform applied to a position", shortened(t.text(v.init))));
  int matrix_var = ctx.world.variable_at(transform.matrix);
  const Variable& m = ctx.world.variables()[matrix_var];
  if (ctx.world.uses(matrix_var).size() != 1)
    return withheld(fmt::format("`{}` is read elsewhere too, and only this transform can use its High/Low split", m.name));
  if (std::string why = why_not_splittable(t, m); !why.empty()) return withheld(why);

  std::string base = stem(m.name);
  bool lower = std::islower(static_cast<unsigned char>(m.name[0]));
  std::string rotation = base + "RotationScale", translation = base + "Translation";
  std::string camera_name = lower ? "cameraTranslation" : "CameraTranslation";
  std::string new_name = translated_name(v.name);
  for (const std::string& name : {rotation, translation, new_name})
    if (variable_named(ctx.world, name) >= 0) return withheld(fmt::format("the name `{}` is already taken", name));
  int existing_camera = variable_named(ctx.world, camera_name);
  if (existing_camera >= 0 && ctx.world.variables()[existing_camera].type != "FDFVector3")
    return withheld(fmt::format("the name `{}` is already taken", camera_name));

  RewritePlan plan;
  // The declarations: M becomes its rotation-scale part and its translation pair; the camera
  // pair is declared once per file, before the first uniform of M's scope, so two rewrites in one
  // file insert it at the same place (and the second waits for the next round).
  const char* mat3 = glsl(t) ? "mat3" : "float3x3";
  Span m_span = declaration_span(t, m);
  std::string prefix(t.source->slice({m_span.begin, t.at(t.child_by_field(m.declaration, "type")).begin}));
  std::string indent = indentation(t, m_span.begin);
  plan.edits.push_back({m_span, fmt::format("{}{} {};\n{}{}FDFVector3 {};", prefix, mat3, rotation, indent, sibling_prefix(t, m), translation)});
  // The library include comes first; where it lands on the camera's line, one edit holds both.
  std::vector<Edit> include = library_include_edits(t);
  if (existing_camera < 0) {
    const Variable* first = &m;
    for (const Variable& u : ctx.world.variables())
      if (u.uniform && u.role == Variable::Role::global && u.block == m.block) {
        first = &u;
        break;
      }
    Span first_span = declaration_span(t, *first);
    uint32_t at = line_start(t, first_span.begin);
    std::string text = fmt::format("{}{}FDFVector3 {};\n", indentation(t, first_span.begin), sibling_prefix(t, m), camera_name);
    auto same = std::find_if(include.begin(), include.end(), [&](const Edit& e) { return e.span.begin == at; });
    if (same != include.end()) same->text += text;
    else plan.edits.push_back({{at, at}, text});
  }
  // The value: rotation-scale times the local position, plus the object's camera-relative offset.
  std::string rotated = glsl(t) ? fmt::format("{} * {}", rotation, transform.position)
                        : transform.row_vector ? fmt::format("mul({}, {})", transform.position, rotation)
                                               : fmt::format("mul({}, {})", rotation, transform.position);
  std::string value = fmt::format("{} + DFFastLocalSubtractDemote({}, {})", rotated, translation, camera_name);
  if (!transform.swizzled) value = fmt::format("{}({}, 1.0)", glsl(t) ? "vec4" : "float4", value);
  plan.edits.push_back({t.span(v.init), value});
  plan.edits.push_back({t.span(v.decl), new_name});
  Follower(ctx, camera, plan).follow(var, new_name);
  if (!plan.blocker.empty()) return plan;

  plan.edits.insert(plan.edits.end(), include.begin(), include.end());
  plan.library = {"FDFVector3", "DFFastLocalSubtractDemote"};
  plan.notes.insert(plan.notes.begin(),
                    {fmt::format("new uniforms: `{} {}` (the rotation-scale part of `{}`), `FDFVector3 {}` (its translation as a "
                                 "High/Low pair) and `FDFVector3 {}` (the camera position as a High/Low pair); `{}` is no longer read",
                                 mat3, rotation, m.name, translation, camera_name, m.name),
                     fmt::format("host: split each double coordinate d into High = (float)d and Low = (float)(d - (double)High) "
                                 "(lwc::host::split in tool/shaderlib/lwc_host.h) and upload `{}` and `{}` as .High/.Low; the "
                                 "shader subtracts them under `precise`",
                                 translation, camera_name)});
  if (std::string version = glsl_version_without_precise(t); !version.empty())
    plan.notes.push_back(fmt::format("GLSL {} has no `precise`: the library's subtraction keeps its low part only where the driver "
                                     "does not reassociate float arithmetic; check the target driver",
                                     version));
  if (glsl(t))
    plan.notes.push_back(fmt::format("`#include \"{}\"` needs GL_GOOGLE_include_directive (glslc, glslangValidator); a loader "
                                     "without it (WebGL) pastes the file in place of that line",
                                     library_file_name(t.lang)));
  return plan;
}

RewritePlan plan_translated_input(const CheckContext& ctx, int var, const CameraNames& camera) {
  const SyntaxTree& t = ctx.tree;
  const Variable& v = ctx.world.variables()[var];
  std::string new_name = translated_name(v.name);
  if (variable_named(ctx.world, new_name) >= 0) return withheld(fmt::format("the name `{}` is already taken", new_name));
  RewritePlan plan;
  plan.edits.push_back({t.span(v.decl), new_name});
  plan.interface.push_back(fmt::format("`{}` -> `{}`", v.name, new_name));
  Follower(ctx, camera, plan).follow(var, new_name);
  plan.notes.push_back(fmt::format("the previous stage must write `{}`, a camera-relative position (lwcport rewrites its output "
                                   "the same way)",
                                   new_name));
  return plan;
}

namespace {
// The start of the first line that holds code: not blank, a comment, a precision statement, or a
// directive other than a conditional (`#if` may hold the whole file, and the include goes before it).
uint32_t first_code_line(const std::string& text) {
  bool in_comment = false;
  for (size_t line = 0; line < text.size();) {
    size_t end = std::min(text.find('\n', line), text.size());
    std::string_view l(text.data() + line, end - line);
    if (line == 0 && l.starts_with("\xEF\xBB\xBF")) l.remove_prefix(3);  // a byte-order mark is no code
    size_t i = l.find_first_not_of(" \t\r");
    bool code = false;
    while (i != std::string_view::npos && i < l.size()) {
      if (in_comment) {
        size_t close = l.find("*/", i);
        if (close == std::string_view::npos) break;
        in_comment = false;
        i = l.find_first_not_of(" \t\r", close + 2);
      } else if (l.substr(i, 2) == "/*") {
        in_comment = true;
        i += 2;
      } else if (l.substr(i, 2) == "//") {
        break;
      } else {
        // (GLSL's default precision comes before the library, whose functions need it.)
        code = (l[i] != '#' || l.substr(i).starts_with("#if")) && !l.substr(i).starts_with("precision ");
        break;
      }
    }
    if (code) return static_cast<uint32_t>(line);
    line = end + 1;
  }
  return static_cast<uint32_t>(text.size());
}
}  // namespace

std::vector<Edit> library_include_edits(const SyntaxTree& t) {
  std::string file = library_file_name(t.lang);
  const std::string& text = t.source->text();
  if (text.find("\"" + file + "\"") != std::string::npos) return {};
  // Before the first top-level node that is not a comment or a plain directive (an #ifdef may
  // hold the whole file: the include goes before it).
  uint32_t at = static_cast<uint32_t>(text.size());
  for (int c : t.named_children(0)) {
    std::string_view type = t.at(c).type;
    if (type == "comment" || type == "preproc_call" || type == "preproc_include" || type == "preproc_def" ||
        type == "preproc_function_def")
      continue;
    at = line_start(t, t.at(c).begin);
    break;
  }
  // Nor after source text the tree does not hold (a macro that opens a constant buffer,
  // `META_CB_BEGIN(0, Data)`, is masked out of it): the first line of code in the text bounds it.
  at = std::min(at, first_code_line(text));
  std::string include = "#include \"" + file + "\"\n";
  if (!glsl(t) || text.find("GL_GOOGLE_include_directive") != std::string::npos) return {{{at, at}, include}};
  // GLSL: the extension goes right after #version, before any other token.
  uint32_t after_version = 0;
  if (int version = version_directive(t); version >= 0) {
    int line = t.source->position(t.at(version).begin).line;
    after_version = line < t.source->line_count() ? t.source->offset({line + 1, 1}) : static_cast<uint32_t>(text.size());
  }
  std::string extension = "#extension GL_GOOGLE_include_directive : require\n";
  if (after_version == at) return {{{at, at}, extension + include}};
  return {{{after_version, after_version}, extension}, {{at, at}, include}};
}

}  // namespace lwc::checks
