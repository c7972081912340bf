#include "rules/checks/util.h"

#include "rules/checks/chain_shapes.h"

#include <optional>
#include <algorithm>
#include <cctype>
#include <iterator>

#include <fmt/format.h>

namespace lwc::checks {

const std::vector<int>& nodes_of(const SyntaxTree& tree, std::string_view type) { return tree.of_type(type); }

std::vector<int> nodes_of(const SyntaxTree& tree, std::initializer_list<std::string_view> types) {
  std::vector<int> out;
  for (std::string_view type : types) {
    const std::vector<int>& more = tree.of_type(type);
    std::vector<int> merged;
    std::merge(out.begin(), out.end(), more.begin(), more.end(), std::back_inserter(merged));
    out = std::move(merged);
  }
  return out;
}

std::string_view call_name(const SyntaxTree& tree, int call) {
  int fn = tree.child_by_field(call, "function");
  return fn >= 0 && tree.is(fn, "identifier") ? tree.text(fn) : std::string_view();
}

std::vector<int> call_arguments(const SyntaxTree& tree, int call) {
  int args = tree.child_by_field(call, "arguments");
  std::vector<int> out = args >= 0 ? tree.named_children(args) : std::vector<int>{};
  std::erase_if(out, [&](int n) { return tree.is(n, "comment"); });  // a comment between arguments is not one
  return out;
}

std::vector<std::string> string_list(const nlohmann::json& data, const char* key) {
  std::vector<std::string> out;
  if (data.contains(key))
    for (const auto& v : data.at(key)) out.push_back(v.get<std::string>());
  return out;
}

bool matches_any(const std::vector<std::string>& globs, std::string_view text) {
  for (const auto& g : globs) {
    // Most rule lists are plain names, asked about every call or type of a file: a first byte
    // that differs settles those without the matcher.
    if (!g.empty() && !text.empty() && g[0] != '*' && g[0] != '?' && g[0] != text[0]) continue;
    if (glob_match(g, text)) return true;
  }
  return false;
}

int function_name(const SyntaxTree& tree, int definition) {
  int declarator = tree.child_by_field(definition, "declarator");
  int name = declarator >= 0 ? tree.child_by_field(declarator, "declarator") : -1;
  return name >= 0 && tree.is(name, "identifier") ? name : -1;
}

bool is_field_of(const SyntaxTree& tree, int node, int base, std::string_view name) {
  if (!tree.is(node, "field_expression") || tree.child_by_field(node, "argument") != base) return false;
  int field = tree.child_by_field(node, "field");
  return field >= 0 && tree.text(field) == name;
}

int without_xyz(const SyntaxTree& tree, int node) {
  int base = tree.is(node, "field_expression") ? tree.child_by_field(node, "argument") : -1;
  return is_field_of(tree, node, base, "xyz") ? base : node;
}

bool read_as_coordinates(const SyntaxTree& tree, int node) {
  int parent = tree.at(node).parent;
  int field = tree.is(parent, "field_expression") && tree.child_by_field(parent, "argument") == node ? tree.child_by_field(parent, "field") : -1;
  return field >= 0 && is_swizzle(tree.text(field)) && tree.text(field) != "xyz" && tree.text(field).size() <= 2;
}

bool is_definition_name(const SyntaxTree& tree, int identifier) {
  int parent = tree.at(identifier).parent;
  if (parent < 0) return false;
  std::string_view type = tree.at(parent).type;
  if (type == "preproc_def" || type == "preproc_function_def") return tree.child_by_field(parent, "name") == identifier;
  return type == "function_declarator" && tree.child_by_field(parent, "declarator") == identifier;
}

Member member_of(const SyntaxTree& tree, int node) {
  if (!tree.is(node, "field_expression")) return {};
  int object = tree.child_by_field(node, "argument"), field = tree.child_by_field(node, "field");
  if (object < 0 || field < 0) return {};
  bool call = tree.is(object, "call_expression");
  if (!call && !tree.is(object, "identifier")) return {};
  return {call ? std::string(call_name(tree, object)) + "(..)" : std::string(tree.text(object)), std::string(tree.text(field))};
}

namespace {
// A variable stored into anywhere but its declaration: assigned (whole or a part), stepped, or
// passed to an `out` or `inout` parameter of this file.
bool stored_again(const CheckContext& ctx, int var) {
  const std::vector<int>& uses = ctx.world.uses(var);
  return std::any_of(uses.begin(), uses.end(), [&](int use) { return stores_into(ctx, use); });
}

// A point minus the pre-view translation (`TranslatedP - View.PreViewTranslation`,
// `DFSubtractDemote(TranslatedP, ..)`), or a local that holds one, neither of them stored again:
// the point's text, which is the value's translated form wherever it is read.
std::string translated_source(const CheckContext& ctx, int node) {
  const SyntaxTree& t = ctx.tree;
  int value = node;
  bool local = false;
  if (int var = t.is(node, "identifier") ? ctx.world.variable_at(node) : -1; var >= 0) {
    const Variable& v = ctx.world.variables()[static_cast<size_t>(var)];
    if (v.role != Variable::Role::local || v.init < 0 || stored_again(ctx, var)) return {};
    value = v.init;
    local = true;
  }
  while (t.is(value, "parenthesized_expression")) value = t.named_child(value);
  int left = -1, right = -1;
  if (t.is(value, "binary_expression") && t.text(t.child_by_field(value, "operator")) == "-") {
    left = t.child_by_field(value, "left"), right = t.child_by_field(value, "right");
  } else if (t.is(value, "call_expression") && (call_name(t, value) == "DFSubtractDemote" || call_name(t, value) == "DFFastSubtractDemote") &&
             call_arguments(t, value).size() == 2) {
    left = call_arguments(t, value)[0], right = call_arguments(t, value)[1];
  }
  if (left < 0 || right < 0) return {};
  if (member_of(t, without_xyz(t, undemoted(t, right))).member != "PreViewTranslation") return {};
  int point = without_xyz(t, left);
  // Read later through the local, the point must still hold what it held then.
  int source = t.is(point, "identifier") ? ctx.world.variable_at(point) : -1;
  if (source < 0 || (local && stored_again(ctx, source))) return {};
  return std::string(t.text(left));
}
}  // namespace

const WorldData::TranslatedInPlace* view_member_translated_in_place(const CheckContext& ctx, int node) {
  if (!ctx.unreal || ctx.unreal->era == UnrealEra::ue4 || ctx.world.code_era() != UnrealEra::ue4) return nullptr;
  const SyntaxTree& t = ctx.tree;
  while (t.is(node, "subscript_expression")) node = t.child_by_field(node, "argument");  // `Min[CascadeIndex]`
  Member m = member_of(t, node);
  if (m.object != "View" && m.object != "ResolvedView" && m.object != "PrimaryView") return nullptr;
  const auto& table = ctx.world.data().view_translated_in_place;
  auto it = table.find(m.member);
  if (it == table.end() || static_cast<int>(ctx.unreal->era) < static_cast<int>(it->second.from)) return nullptr;
  return &it->second;
}

bool translated_in_target(const CheckContext& ctx, int node, int depth) {
  const SyntaxTree& t = ctx.tree;
  if (node < 0 || depth > 3) return false;
  // Only UE4 code moving to UE5 reads such members as UE4 did: nothing to look for otherwise.
  if (!ctx.unreal || ctx.unreal->era == UnrealEra::ue4 || ctx.world.code_era() != UnrealEra::ue4) return false;
  for (int id = node; id < static_cast<int>(t.nodes.size()) && t.at(id).begin < t.at(node).end; ++id) {
    if (t.is(id, "field_expression"))
      if (const auto* e = view_member_translated_in_place(ctx, id); e && !e->plane) return true;
    if (!t.is(id, "identifier") || (id != node && t.at(id).parent >= 0 && t.is(t.at(id).parent, "field_expression") &&
                                    t.child_by_field(t.at(id).parent, "field") == id))
      continue;
    // A local: what it was given, and what is stored into it.
    int var = ctx.world.variable_at(id);
    if (var < 0 || ctx.world.variables()[static_cast<size_t>(var)].role != Variable::Role::local) continue;
    const Variable& v = ctx.world.variables()[static_cast<size_t>(var)];
    if (v.init >= 0 && translated_in_target(ctx, v.init, depth + 1)) return true;
    for (int use : ctx.world.uses(var)) {
      int parent = t.at(use).parent;
      if (t.is(parent, "assignment_expression") && t.child_by_field(parent, "left") == use &&
          translated_in_target(ctx, t.child_by_field(parent, "right"), depth + 1))
        return true;
    }
  }
  return false;
}

std::string translated_twin(const CheckContext& ctx, int node) {
  if (node < 0) return {};  // a part the parser left out
  const SyntaxTree& t = ctx.tree;
  if (std::string source = translated_source(ctx, node); !source.empty()) return source;
  // An offset from a point with a twin (`ShadowP * SKY_UNIT_TO_CM + View.SkyPlanetCenterAndViewHeight.xyz`,
  // `Ray * Depth + View.WorldCameraOrigin`): the same offset from the twin. The other term must be
  // no position: a sum of two positions is none, and one with the pre-view translation is translated.
  if (t.is(node, "binary_expression") && t.text(t.child_by_field(node, "operator")) == "+") {
    int left = t.child_by_field(node, "left"), right = t.child_by_field(node, "right");
    for (auto [offset, point] : {std::pair{left, right}, std::pair{right, left}}) {
      Kind k = ctx.world.kind(offset);
      if (holds_absolute(k) || k == Kind::camera_offset || is_matrix(k)) continue;
      std::string twin = translated_twin(ctx, point);
      if (twin.empty()) continue;
      std::string text(t.text(node));
      size_t begin = t.at(point).begin - t.at(node).begin;
      return text.replace(begin, t.at(point).end - t.at(point).begin, twin);
    }
  }
  const WorldData::Twins& twins = ctx.world.data().twins;
  // A demotion or marker of a value with a twin (`DFHackToFloat(View.WorldCameraOrigin)`): the
  // twin is a float already.
  if (int inner = undemoted(t, node); inner != node) return translated_twin(ctx, inner);
  // The 3-vector of a value with a twin (`TransformLocalToWorld(P).xyz`, a packed member's `.xyz`).
  if (int base = t.child_by_field(node, "argument"); is_field_of(t, node, base, "xyz")) {
    std::string twin = translated_twin(ctx, base);
    return twin.empty() || twin.ends_with(".xyz") ? twin : twin + ".xyz";
  }
  if (t.is(node, "call_expression")) {
    // A twin for one arity only is keyed `Name/N` (UE4's overload with a primitive id has none).
    std::string name(call_name(t, node));
    auto it = twins.functions.find(name + "/" + std::to_string(call_arguments(t, node).size()));
    if (it == twins.functions.end()) it = twins.functions.find(name);
    if (it == twins.functions.end()) return {};
    std::string twin = it->second + std::string(t.text(t.child_by_field(node, "arguments")));
    // UE5 returns the absolute point as a large-world 3-vector and the translated one homogeneous
    // (`TransformLocalToWorld` -> `TransformLocalToTranslatedWorld`): the twin's xyz is the point.
    const auto& types = ctx.world.data().engine_function_types;
    auto own = types.find(name), other = types.find(it->second);
    std::optional<UnrealEra> era = ctx.world.code_era();
    size_t column = !era || *era == UnrealEra::ue4 ? 0 : *era == UnrealEra::ue5_0 ? 1 : 2;
    if (own != types.end() && other != types.end() && own->second[column].ends_with("3") && other->second[column] == "float4") twin += ".xyz";
    return twin;
  }
  if (ctx.unreal && ctx.unreal->era != UnrealEra::ue4)
    if (std::string twin = engine_translated_twin(ctx, node); !twin.empty()) return twin;
  Member m = member_of(t, node);
  if (m.empty()) return {};
  if (auto owner = twins.struct_members.find(engine_struct_of(ctx, node)); owner != twins.struct_members.end())
    if (auto twin = owner->second.find(m.member); twin != owner->second.end()) return m.object + "." + twin->second;
  if (!matches_any(twins.objects, m.object) || !twins.members.count(m.member)) return {};
  // UE5 keeps the view's world members on PrimaryView; the translated ones stay where they were.
  return (m.object == "View" ? "PrimaryView" : m.object) + "." + twins.members.at(m.member);
}

std::string engine_translated_twin(const CheckContext& ctx, int node) {
  const SyntaxTree& t = ctx.tree;
  const WorldData::Twins& twins = ctx.world.data().twins;
  if (t.is(node, "identifier")) {
    auto it = twins.engine_globals.find(std::string(t.text(node)));
    if (it == twins.engine_globals.end()) return {};
    // A global the file declares itself (the engine's UE4 header) keeps its name.
    for (const Variable& v : ctx.world.variables())
      if (v.role == Variable::Role::global && v.name == it->first) return {};
    return it->second;
  }
  Member m = member_of(t, node);
  int base = t.is(node, "field_expression") ? t.child_by_field(node, "argument") : -1;
  if (m.empty() || !t.is(base, "identifier")) return {};
  // A variable by its struct type; an engine global (undeclared here) by its name.
  int var = ctx.world.variable_at(base);
  std::string owner = var >= 0 ? ctx.world.variables()[static_cast<size_t>(var)].type : m.object;
  auto object = twins.engine_members.find(owner);
  if (object == twins.engine_members.end()) return {};
  // A struct the file declares itself (a copy of the engine's UE4 header) keeps its members.
  for (const Variable& v : ctx.world.variables())
    if (v.role == Variable::Role::field && v.owner == owner) return {};
  auto member = object->second.find(m.member);
  return member != object->second.end() ? m.object + "." + member->second : std::string();
}

namespace {
// The function's own declaration names the parameter `argument` is passed to as translated
// (`float3 TranslatedWorldPosition`): defined in this file, or in an included one.
bool declared_translated(const CheckContext& ctx, int call, int argument) {
  const SyntaxTree& t = ctx.tree;
  std::vector<int> args = call_arguments(t, call);
  size_t index = std::find(args.begin(), args.end(), argument) - args.begin();
  if (index == args.size()) return false;
  if (int fn = defined_function(t, call_name(t, call), args.size()); fn >= 0) {
    int p = parameter_variable(ctx, fn, index);
    if (p < 0) return false;
    const Variable& v = ctx.world.variables()[p];
    return (v.type == "float3" || v.type == "float4") && ctx.world.data().named_kind(v.name, Kind::absolute) == Kind::translated;
  }
  auto included = ctx.world.included_parameter_use(call, argument);
  return included && included->translated;
}
}  // namespace

namespace {
// The engine's function of the table, at one of its translated parameters, in the era the code
// moves to; a definition of the project's own keeps its contract, the engine's is the one the
// table reads. The first era that takes it so, or none.
std::optional<UnrealEra> engine_translated(const CheckContext& ctx, int call, int argument) {
  const SyntaxTree& t = ctx.tree;
  std::string_view name = call_name(t, call);
  const auto& table = ctx.world.data().engine_translated_parameters;
  auto entry = table.find(std::string(name));
  if (entry == table.end()) return std::nullopt;
  std::vector<int> args = call_arguments(t, call);
  const std::vector<size_t>& indices = entry->second.indices;
  if (std::none_of(indices.begin(), indices.end(), [&](size_t i) { return i < args.size() && args[i] == argument; })) return std::nullopt;
  UnrealEra target = !ctx.unreal || ctx.unreal->era == UnrealEra::ue4 ? UnrealEra::ue5_4 : ctx.unreal->era;
  if (static_cast<int>(target) < static_cast<int>(entry->second.from)) return std::nullopt;
  if (defines_function(t, name)) return std::nullopt;
  if (auto included = ctx.world.included_parameter_use(call, argument); included && !included->engine) return std::nullopt;
  return entry->second.from;
}
}  // namespace

int translated_parameter_call(const CheckContext& ctx, int argument, UnrealEra* from, bool* declared) {
  const SyntaxTree& t = ctx.tree;
  int list = t.at(argument).parent;
  if (!t.is(list, "argument_list")) return -1;
  int call = t.at(list).parent;
  if (declared) *declared = false;
  if (call_name(t, call).empty()) return -1;
  if (std::optional<UnrealEra> era = engine_translated(ctx, call, argument)) {
    if (from) *from = *era;
    return call;
  }
  if (!declared_translated(ctx, call, argument)) return -1;
  if (declared) *declared = true;
  return call;
}

RewritePlan withheld(std::string why) {
  RewritePlan plan;
  plan.blocker = std::move(why);
  return plan;
}

PlanMark mark(const RewritePlan& plan) {
  return {plan.edits.size(),     plan.helpers.size(),          plan.notes.size(),           plan.library.size(),
          plan.interface.size(), plan.moving_functions.size(), plan.moving_variables.size(), plan.followed,
          plan.bridged,          plan.blocker};
}

void roll_back(RewritePlan& plan, const PlanMark& mark) {
  plan.edits.resize(mark.edits);
  plan.helpers.resize(mark.helpers);
  plan.notes.resize(mark.notes);
  plan.library.resize(mark.library);
  plan.interface.resize(mark.interface);
  plan.moving_functions.resize(mark.functions);
  plan.moving_variables.resize(mark.variables);
  plan.followed = mark.followed;
  plan.bridged = mark.bridged;
  plan.blocker = mark.blocker;
}

std::string translated_name(const std::string& name) {
  if (name.rfind("Absolute", 0) == 0) return "Translated" + name.substr(8);
  // Insert before the world (or, failing that, the first) word, in the name's own case.
  for (const char* world : {"World", "world"}) {
    size_t at = name.find(world);
    if (at == std::string::npos) continue;
    return name.substr(0, at) + (world[0] == 'W' ? "Translated" : "translated") + "World" + name.substr(at + 5);
  }
  if (!name.empty() && std::islower(static_cast<unsigned char>(name[0])))
    return "translated" + std::string(1, static_cast<char>(std::toupper(static_cast<unsigned char>(name[0])))) + name.substr(1);
  return "Translated" + name;
}

int line_of(const SyntaxTree& tree, int node) { return tree.source->position(tree.at(node).begin).line; }

std::string ue5_spelling(const CheckContext& ctx, int node) {
  const SyntaxTree& t = ctx.tree;
  const auto& [buffer, call] = ctx.world.data().uniform_buffer;
  std::string text(t.text(node));
  int base = t.is(node, "field_expression") ? t.child_by_field(node, "argument") : -1;
  if (base >= 0 && t.is(base, "identifier") && t.text(base) == buffer && ctx.world.variable_at(base) < 0)
    return call + text.substr(buffer.size());
  return text;
}

std::string engine_struct_of(const CheckContext& ctx, int field) {
  const SyntaxTree& t = ctx.tree;
  const auto& objects = ctx.world.data().engine_objects;
  int base = t.child_by_field(field, "argument");
  if (t.is(base, "identifier")) {
    int var = ctx.world.variable_at(base);
    if (var >= 0) return ctx.world.variables()[static_cast<size_t>(var)].type;
    auto it = objects.find(std::string(t.text(base)));
    return it != objects.end() ? it->second : std::string();
  }
  if (t.is(base, "call_expression")) {
    auto it = objects.find(std::string(call_name(t, base)) + "(..)");
    return it != objects.end() ? it->second : std::string();
  }
  return {};
}

const WorldData::EngineMember* engine_member_at(const CheckContext& ctx, int node) {
  Member m = member_of(ctx.tree, node);
  std::string owner = m.empty() ? "" : engine_struct_of(ctx, node);
  return owner.empty() ? nullptr : ctx.world.data().engine_member(owner, m.member);
}

bool defines_function(const SyntaxTree& tree, std::string_view name) { return !tree.definitions_named(name).empty(); }

int defined_function(const SyntaxTree& tree, std::string_view name) {
  const std::vector<int>& defs = tree.definitions_named(name);
  return defs.size() == 1 ? defs.front() : -1;
}

size_t function_arity(const SyntaxTree& tree, int definition) {
  int declarator = tree.child_by_field(definition, "declarator");
  int list = declarator >= 0 ? tree.child_by_field(declarator, "parameters") : -1;
  size_t n = 0;
  if (list >= 0)
    for (int c : tree.named_children(list)) n += tree.is(c, "parameter_declaration");
  return n;
}

int parameter_variable(const CheckContext& ctx, int definition, size_t index) {
  const SyntaxTree& t = ctx.tree;
  int declarator = t.child_by_field(definition, "declarator");
  int list = declarator >= 0 ? t.child_by_field(declarator, "parameters") : -1;
  size_t seen = 0;
  if (list >= 0)
    for (int p : t.named_children(list)) {
      if (!t.is(p, "parameter_declaration") || seen++ != index) continue;
      int name = t.declarator_name(t.child_by_field(p, "declarator"));
      int var = name >= 0 ? ctx.world.variable_declared_at(name) : -1;
      return var >= 0 && ctx.world.variables()[static_cast<size_t>(var)].role == Variable::Role::parameter ? var : -1;
    }
  return -1;
}

int defined_function(const SyntaxTree& tree, std::string_view name, size_t arity) {
  int found = -1;
  for (int fn : tree.definitions_named(name)) {
    if (function_arity(tree, fn) != arity) continue;
    if (found >= 0) return -1;
    found = fn;
  }
  return found;
}

int undemoted(const SyntaxTree& tree, int node) {
  while (tree.is(node, "parenthesized_expression")) node = tree.named_child(node);
  if (!tree.is(node, "call_expression")) return node;
  std::string_view name = call_name(tree, node);
  auto args = call_arguments(tree, node);
  bool demotion = name == "DFDemote" || name == "DFFastDemote" || name == "DFHackToFloat" || name == "LWCHackToFloat" || name == "LWCToFloat";
  return demotion && args.size() == 1 ? args[0] : node;
}

bool unconditional_statement(const SyntaxTree& tree, int statement) {
  if (!tree.is(statement, "expression_statement")) return false;
  for (int block = tree.at(statement).parent; !tree.is(block, "function_definition"); block = tree.at(block).parent)
    if (block < 0 || !tree.is(block, "compound_statement")) return false;
  return true;
}

Span whole_lines(const SyntaxTree& tree, int node) {
  const std::string& text = tree.source->text();
  uint32_t begin = tree.at(node).begin, end = tree.at(node).end;
  uint32_t b = begin, e = end;
  while (b > 0 && (text[b - 1] == ' ' || text[b - 1] == '\t')) --b;
  while (e < text.size() && (text[e] == ' ' || text[e] == '\t')) ++e;
  if (e < text.size() && text[e] == '\r') ++e;
  bool line_start = b == 0 || text[b - 1] == '\n', line_end = e == text.size() || text[e] == '\n';
  if (!line_start || !line_end) return {begin, end};
  return {b, e < text.size() ? e + 1 : e};
}

int mul_call(const SyntaxTree& tree, int node) {
  if (tree.is(node, "field_expression")) node = tree.child_by_field(node, "argument");
  if (!tree.is(node, "call_expression") || call_name(tree, node) != "mul" || call_arguments(tree, node).size() != 2) return -1;
  return node;
}

namespace {

// The 3-vector of `float4(V, w)` / `float4(x, y, z, w)` / `vec4(..)` when w is the literal given
// ("1" or "0", in any of its spellings), as text; else "".
std::string homogeneous_part(const SyntaxTree& tree, int node, char w_digit) {
  if (!tree.is(node, "call_expression")) return {};
  std::string_view ctor = call_name(tree, node);
  if (ctor != "float4" && ctor != "vec4") return {};
  auto args = call_arguments(tree, node);
  if (args.size() < 2 || args.size() > 4) return {};
  std::string_view w = tree.text(args.back());
  std::string d(1, w_digit);
  if (w != d && w != d + ".0" && w != d + ".0f" && w != d + ".f" && w != d + "f") return {};
  if (args.size() == 2) return std::string(tree.text(args[0]));
  std::string out = ctor == "vec4" ? "vec3(" : "float3(";
  for (size_t i = 0; i + 1 < args.size(); ++i) out += std::string(i ? ", " : "") + std::string(tree.text(args[i]));
  return out + ")";
}

}  // namespace

std::string position_of_homogeneous(const SyntaxTree& tree, int node) { return homogeneous_part(tree, node, '1'); }

std::string direction_of_homogeneous(const SyntaxTree& tree, int node) { return homogeneous_part(tree, node, '0'); }

int homogeneous_wrapper(const SyntaxTree& tree, int use) {
  int list = tree.at(use).parent;
  int call = tree.is(list, "argument_list") ? tree.at(list).parent : -1;
  if (call < 0 || call_arguments(tree, call).size() != 2 || call_arguments(tree, call)[0] != use) return -1;
  return position_of_homogeneous(tree, call).empty() ? -1 : call;
}

DeclaredNames::DeclaredNames(const WorldModel& world) {
  for (const Variable& v : world.variables()) names_.emplace(v.name, std::max(v.function, -1));
}

bool DeclaredNames::taken(std::string_view name, int function) const {
  return names_.count({name, function}) || names_.count({name, -1});
}

int subtraction_partner(const SyntaxTree& tree, int use) {
  int parent = tree.at(use).parent;
  while (tree.is(parent, "parenthesized_expression")) use = parent, parent = tree.at(use).parent;
  if (!tree.is(parent, "binary_expression")) return -1;
  int op = tree.child_by_field(parent, "operator");
  if (op < 0 || tree.text(op) != "-") return -1;
  int left = tree.child_by_field(parent, "left"), right = tree.child_by_field(parent, "right");
  return left == use ? right : left;
}

std::string escape(const SyntaxTree& tree, int use) {
  int parent = tree.at(use).parent;
  int line = line_of(tree, use);
  if (tree.is(parent, "argument_list")) {
    int call = tree.at(parent).parent;
    return fmt::format("it is passed to `{}` (line {}), which expects an absolute position", call_name(tree, call), line);
  }
  if (tree.is(parent, "return_statement")) return fmt::format("it is returned (line {}) as an absolute position", line);
  if (tree.is(parent, "assignment_expression") || tree.is(parent, "init_declarator"))
    return fmt::format("it is stored (line {}: `{}`)", line, shortened(tree.text(parent)));
  if (tree.is(parent, "binary_expression")) {
    int other = tree.child_by_field(parent, "left") == use ? tree.child_by_field(parent, "right") : tree.child_by_field(parent, "left");
    return fmt::format("it is combined with `{}` (line {}), which has no translated twin", shortened(tree.text(other)), line);
  }
  return fmt::format("it is used as `{}` (line {})", shortened(tree.text(parent)), line);
}

int version_directive(const SyntaxTree& t) {
  for (int c : t.named_children(0))
    if (t.is(c, "preproc_call") && t.text(c).starts_with("#version")) return c;
  return -1;
}

std::string glsl_version_without_precise(const SyntaxTree& t) {
  if (t.lang != Lang::glsl) return {};
  int directive = version_directive(t);
  if (directive < 0) return "110";  // no #version: GLSL 1.10
  std::string version(t.text(directive).substr(8));
  version.erase(0, version.find_first_not_of(" \t"));
  version.erase(version.find_last_not_of(" \t\r\n") + 1);
  int number = std::atoi(version.c_str());
  bool es = version.find("es") != std::string::npos;
  return number < (es ? 320 : 400) ? version : std::string();
}

}  // namespace lwc::checks
