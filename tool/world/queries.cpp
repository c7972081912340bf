// What a finished world model answers: the variable at an identifier and its uses, a node's kind
// and path, whether a value's uses let its rounding reach a result, the parameters a call reaches,
// and the summary it gives the files that include it. The analysis that builds it is model.cpp.
#include <algorithm>
#include <map>
#include <set>

#include "world/model.h"

namespace lwc {

int WorldModel::variable_declared_at(int identifier) const {
  return identifier >= 0 && identifier < static_cast<int>(declared_at_.size()) ? declared_at_[identifier] : -1;
}

const std::vector<int>& WorldModel::globals_named(const std::string& name) const {
  static const std::vector<int> none;
  auto it = globals_by_name_.find(name);
  return it != globals_by_name_.end() ? it->second : none;
}

Kind WorldModel::kind(int node) const {
  return node >= 0 && node < static_cast<int>(kinds_.size()) ? kinds_[node] : Kind::unknown;
}

std::optional<Path> WorldModel::path(int node) const {
  Path out;
  // Walk down the left spine: a.b(c).d -> [a, b(), d], built back to front.
  while (node >= 0) {
    std::string_view type = tree_.at(node).type;
    if (type == "identifier") {
      out.push_back({std::string(tree_.text(node)), false});
      break;
    }
    if (type == "field_expression") {
      int field = tree_.child_by_field(node, "field");
      if (field < 0) return std::nullopt;
      out.push_back({std::string(tree_.text(field)), false});
      node = tree_.child_by_field(node, "argument");
    } else if (type == "call_expression") {
      int fn = tree_.child_by_field(node, "function");
      if (fn < 0) return std::nullopt;
      if (tree_.is(fn, "identifier")) {
        out.push_back({std::string(tree_.text(fn)), true});
        break;
      }
      if (!tree_.is(fn, "field_expression")) return std::nullopt;
      int field = tree_.child_by_field(fn, "field");
      if (field < 0) return std::nullopt;
      out.push_back({std::string(tree_.text(field)), true});
      node = tree_.child_by_field(fn, "argument");
    } else if (type == "parenthesized_expression") {
      node = tree_.named_child(node);
    } else {
      return std::nullopt;
    }
  }
  if (out.empty()) return std::nullopt;
  std::reverse(out.begin(), out.end());
  return out;
}

bool WorldModel::only_harmless_uses(int var, int depth) const {
  if (depth > 3) return false;
  const Variable& v = variables_[var];
  bool matrix = is_matrix(v.kind) || data_.is_matrix_type(v.type);
  std::vector<int> list = uses(var);
  if (list.empty()) return false;
  auto strip = [&](int n) {
    int p = tree_.at(n).parent;
    while (p >= 0 && tree_.is(p, "parenthesized_expression")) n = p, p = tree_.at(n).parent;
    return n;
  };
  for (int use : list) {
    int n = strip(use), p = tree_.at(n).parent;
    // Written, not read (`sunPos = lightPosition;`): what is read later decides. A stage output
    // or an out parameter escapes when written.
    if ((v.role == Variable::Role::local || v.private_global) && tree_.is(p, "assignment_expression") && tree_.child_by_field(p, "left") == n &&
        tree_.text(tree_.child_by_field(p, "operator")) == "=")
      continue;
    // A copy into a local that is itself harmless (or whose translation is then cleared).
    if (tree_.is(p, "init_declarator")) {
      int local = variable_declared_at(tree_.declarator_name(tree_.child_by_field(p, "declarator")));
      if (local >= 0 && (cleared_.count(local) || only_harmless_uses(local, depth + 1))) continue;
      return false;
    }
    if (matrix) {
      // A direction it transforms (w = 0): the translation never acts.
      if (int other = transformed_operand(n); other >= 0 && is_direction_vector(other)) continue;
      // A basis vector (row or column 0..2), or the 3x3 rotation part.
      if (tree_.is(p, "subscript_expression") && tree_.child_by_field(p, "argument") == n) {
        int index = tree_.subscript_index(p);
        std::string_view i = index >= 0 ? tree_.text(index) : "";
        if (i == "0" || i == "1" || i == "2") continue;
        if (i == "3" && cleared_.count(var)) continue;  // the write that clears it
        return false;
      }
      int call = tree_.is(p, "argument_list") ? tree_.at(p).parent : p;
      std::string_view callee;
      if (tree_.is(call, "call_expression")) callee = tree_.text(tree_.child_by_field(call, "function"));
      else if (tree_.is(call, "cast_expression")) callee = tree_.text(tree_.child_by_field(call, "type"));
      if (callee == "mat3" || callee == "float3x3" || callee == "half3x3") continue;
      // Passed to a function (of this file or an include) that only rotates with it.
      if (tree_.is(call, "call_expression") && parameter_only_normalised(call, n, depth)) continue;
      return false;
    }
    // A position only ever normalised: its direction, which float32 keeps to 1e-7.
    int call = tree_.is(p, "argument_list") ? tree_.at(p).parent : -1;
    if (tree_.is(p, "field_expression") && is_swizzle(tree_.text(tree_.child_by_field(p, "field"))) && tree_.text(tree_.child_by_field(p, "field")).size() >= 3) {
      int q = strip(p);
      call = tree_.is(tree_.at(q).parent, "argument_list") ? tree_.at(tree_.at(q).parent).parent : -1;
    }
    if (call >= 0 && tree_.is(call, "call_expression") && tree_.text(tree_.child_by_field(call, "function")) == "normalize") continue;
    if (call >= 0 && parameter_only_normalised(call, n, depth)) continue;
    return false;
  }
  return true;
}

bool WorldModel::used_where_precision_matters(int var, int depth) const {
  if (depth > 3 || cleared_.count(var)) return false;  // a matrix whose translation is cleared only rotates
  const Variable& v = variables_[var];
  if (v.role != Variable::Role::global) return precision_matters(var, depth);
  // Every declaration of a global's name shares its uses (below): each is worked out once, not
  // once per declaration (a name declared in many #if arms).
  auto key = std::make_tuple(v.name, is_matrix(v.kind), v.decl >= 0 && tree_.is(tree_.at(v.decl).parent, "array_declarator"), depth);
  auto known = global_precision_.find(key);
  if (known != global_precision_.end()) return known->second;
  bool matters = precision_matters(var, depth);
  global_precision_.emplace(std::move(key), matters);
  return matters;
}

bool WorldModel::precision_matters(int var, int depth) const {
  // By its kind, or by its type where nothing has flowed in (a header's parameter, summarised alone).
  bool matrix = is_matrix(variables_[var].kind) || data_.is_matrix_type(variables_[var].type);
  int decl = variables_[var].decl;
  bool array = decl >= 0 && tree_.is(tree_.at(decl).parent, "array_declarator");
  // Up through parentheses, swizzles and (for an array) the element access.
  auto climb = [&](int n) {
    int p = tree_.at(n).parent;
    if (p >= 0 && tree_.is(p, "field_expression") && tree_.child_by_field(p, "field") == n) {  // block.member
      n = p;
      p = tree_.at(n).parent;
    }
    while (p >= 0 && (tree_.is(p, "parenthesized_expression") ||
                      (tree_.is(p, "field_expression") && is_swizzle(tree_.text(tree_.child_by_field(p, "field")))) ||
                      (array && tree_.is(p, "subscript_expression") && tree_.child_by_field(p, "argument") == n))) {
      array = array && !tree_.is(p, "subscript_expression");
      n = p;
      p = tree_.at(n).parent;
    }
    return n;
  };
  // A global declared in several #if arms is one name: every declaration's uses count.
  std::vector<int> list = uses(var);
  if (variables_[var].role == Variable::Role::global)
    for (int other : globals_named(variables_[var].name))
      if (other != var) {
        std::vector<int> more = uses(other);
        list.insert(list.end(), more.begin(), more.end());
      }
  if (list.empty()) return true;  // declared for the host and not read here: its name is the evidence
  for (int use : list) {
    array = decl >= 0 && tree_.is(tree_.at(decl).parent, "array_declarator");
    int n = climb(use), p = tree_.at(n).parent;
    if (p < 0) continue;
    std::string_view type = tree_.at(p).type;
    if (type == "return_statement") return true;  // it escapes as data
    if (type == "assignment_expression" && tree_.child_by_field(p, "right") == n) {
      int target = tree_.child_by_field(p, "left");
      int copy = tree_.is(target, "identifier") ? variable_at(target) : -1;
      // Stored as a field, an output or shared memory: it escapes. A local or a private global:
      // its own uses decide.
      if (copy < 0 || !(variables_[copy].role == Variable::Role::local || variables_[copy].private_global)) return true;
      if (used_where_precision_matters(copy, depth + 1)) return true;
      continue;
    }
    if (type == "init_declarator") {  // a copy: its own uses decide
      int copy = variable_declared_at(tree_.declarator_name(tree_.child_by_field(p, "declarator")));
      if (copy >= 0 && used_where_precision_matters(copy, depth + 1)) return true;
      continue;
    }
    if (type == "binary_expression") {
      std::string_view op = tree_.text(tree_.child_by_field(p, "operator"));
      int other = tree_.child_by_field(p, tree_.child_by_field(p, "left") == n ? "right" : "left");
      if (!matrix && (op == "-" || op == "+") && !tree_.is(other, "number_literal")) return true;  // a difference with a position
      if (matrix && op == "*" && !is_direction_vector(other)) return true;  // it transforms a point (GLSL)
      continue;
    }
    if (type == "subscript_expression" && matrix) {
      int index = tree_.subscript_index(p);
      if (index >= 0 && tree_.text(index) == "3" && !cleared_.count(var)) return true;  // its translation is read
      continue;
    }
    if (type == "argument_list") {
      int call = tree_.at(p).parent;
      if (!tree_.is(call, "call_expression")) continue;  // an argument list the parser recovered without its call
      std::string_view callee = tree_.text(tree_.child_by_field(call, "function"));
      if (callee == "distance") return true;
      if (callee == "mul") {
        int other = transformed_operand(n);
        if (!(matrix && other >= 0 && is_direction_vector(other))) return true;
        continue;
      }
      if (callee == "normalize" || callee == "mat3" || callee == "float3x3") continue;
      // Handed to the large-world library (DFFastToTranslatedWorld(CameraPos, ..)): used as a position.
      if (data_.unreal_api.looks_like_api(callee)) return true;
      // A function of this file, or of an include: what its parameter meets there.
      for (int param : parameters_receiving(call, n))
        if (used_where_precision_matters(param, depth + 1)) return true;
      if (auto use = included_parameter_use(call, n); use && use->matters) return true;
      continue;
    }
  }
  return false;
}

bool WorldModel::is_direction_vector(int node) const {
  while (node >= 0 && tree_.is(node, "parenthesized_expression")) node = tree_.named_child(node);
  if (node < 0 || !tree_.is(node, "call_expression")) return false;
  std::string_view fn = tree_.text(tree_.child_by_field(node, "function"));
  if (fn != "vec4" && fn != "float4" && fn != "half4" && fn != "dvec4") return false;
  std::vector<int> args = tree_.named_children(tree_.child_by_field(node, "arguments"));
  if (args.size() < 2 || !tree_.is(args.back(), "number_literal")) return false;
  std::string w(tree_.text(args.back()));
  while (!w.empty() && (w.back() == 'f' || w.back() == 'F' || w.back() == 'h')) w.pop_back();
  return w.find_first_not_of("0.") == std::string::npos && w.find('0') != std::string::npos;
}

int WorldModel::transformed_operand(int n) const {
  int p = tree_.at(n).parent;
  if (p >= 0 && tree_.is(p, "binary_expression") && tree_.text(tree_.child_by_field(p, "operator")) == "*")
    return tree_.child_by_field(p, tree_.child_by_field(p, "left") == n ? "right" : "left");
  if (p >= 0 && tree_.is(p, "argument_list") && tree_.text(tree_.child_by_field(tree_.at(p).parent, "function")) == "mul") {
    std::vector<int> args = tree_.named_children(p);
    if (args.size() == 2) return args[0] == n ? args[1] : args[0];
  }
  return -1;
}

bool WorldModel::combined_with_translated(int var) const {
  for (int use : uses(var)) {
    int n = use, p = tree_.at(n).parent;
    while (p >= 0 && (tree_.is(p, "parenthesized_expression") ||
                      (tree_.is(p, "field_expression") && is_swizzle(tree_.text(tree_.child_by_field(p, "field")))))) {
      n = p;
      p = tree_.at(n).parent;
    }
    if (p < 0 || !tree_.is(p, "binary_expression")) continue;
    std::string_view op = tree_.text(tree_.child_by_field(p, "operator"));
    int other = tree_.child_by_field(p, tree_.child_by_field(p, "left") == n ? "right" : "left");
    if ((op == "-" || op == "+") && other >= 0 && kind(other) == Kind::translated) return true;
  }
  return false;
}

// The parameters (one per overload of that arity) a call passes an argument to, for functions
// this file defines.
std::vector<int> WorldModel::parameters_receiving(int call, int argument) const {
  std::vector<int> out;
  int fn = tree_.child_by_field(call, "function");
  if (fn < 0 || !tree_.is(fn, "identifier")) return out;
  std::vector<int> list = tree_.named_children(tree_.child_by_field(call, "arguments"));
  std::erase_if(list, [&](int n) { return tree_.is(n, "comment"); });  // a comment between arguments is not one
  size_t index = 0;
  while (index < list.size() && !(tree_.at(list[index]).begin <= tree_.at(argument).begin && tree_.at(argument).end <= tree_.at(list[index]).end)) ++index;
  if (index == list.size()) return out;
  if (parameters_by_function_.empty()) {  // indexed once: name/arity -> each overload's parameters
    parameters_by_function_.emplace("", std::vector<std::vector<int>>{});
    std::map<int, std::vector<int>> by_definition;
    for (int var = 0; var < static_cast<int>(variables_.size()); ++var)
      if (variables_[var].role == Variable::Role::parameter && variables_[var].function >= 0) by_definition[variables_[var].function].push_back(var);
    for (const auto& [definition, params] : by_definition) {
      int name = tree_.declarator_name(tree_.child_by_field(definition, "declarator"));
      int d = tree_.child_by_field(definition, "declarator");
      while (d >= 0 && !tree_.is(d, "function_declarator")) d = tree_.child_by_field(d, "declarator");
      if (name < 0 || d < 0) continue;
      // Declared parameters in order (an unnamed one has no variable): match by declaration.
      std::vector<int> declared = tree_.named_children(tree_.child_by_field(d, "parameters"));
      std::vector<int> ordered(declared.size(), -1);
      for (int var : params)
        for (size_t k = 0; k < declared.size(); ++k)
          if (declared[k] == variables_[var].declaration) ordered[k] = var;
      parameters_by_function_[std::string(tree_.text(name)) + "/" + std::to_string(declared.size())].push_back(std::move(ordered));
    }
  }
  auto it = parameters_by_function_.find(std::string(tree_.text(fn)) + "/" + std::to_string(list.size()));
  if (it == parameters_by_function_.end()) return out;
  for (const std::vector<int>& overload : it->second)
    if (overload[index] >= 0) out.push_back(overload[index]);
  return out;
}

// A value passed to a function of this file whose parameter is only ever normalised.
bool WorldModel::parameter_only_normalised(int call, int argument, int depth) const {
  std::vector<int> params = parameters_receiving(call, argument);
  if (params.empty()) {
    auto use = included_parameter_use(call, argument);
    return use && use->harmless;
  }
  return std::all_of(params.begin(), params.end(), [&](int p) { return only_harmless_uses(p, depth + 1); });
}

std::optional<ParameterUse> WorldModel::included_parameter_use(int call, int argument) const {
  int fn = tree_.child_by_field(call, "function");
  if (!includes_ || fn < 0 || !tree_.is(fn, "identifier")) return std::nullopt;
  std::vector<int> list = tree_.named_children(tree_.child_by_field(call, "arguments"));
  std::erase_if(list, [&](int n) { return tree_.is(n, "comment"); });  // a comment between arguments is not one
  size_t index = 0;
  while (index < list.size() && !(tree_.at(list[index]).begin <= tree_.at(argument).begin && tree_.at(argument).end <= tree_.at(list[index]).end)) ++index;
  auto it = includes_->parameter_uses.find(std::string(tree_.text(fn)) + "/" + std::to_string(list.size()));
  if (it == includes_->parameter_uses.end() || index >= it->second.size()) return std::nullopt;
  return it->second[index];
}

int WorldModel::variable_at(int identifier) const {
  return identifier >= 0 && identifier < static_cast<int>(refs_.size()) ? refs_[identifier] : -1;
}

std::vector<int> WorldModel::uses(int variable) const {
  if (uses_.empty() && !variables_.empty()) {  // indexed once: the rules ask for many variables
    uses_.resize(variables_.size());
    for (int node = 0; node < static_cast<int>(refs_.size()); ++node)  // in node order: each list comes sorted
      if (refs_[node] >= 0) uses_[refs_[node]].push_back(node);
  }
  return variable >= 0 && variable < static_cast<int>(uses_.size()) ? uses_[variable] : std::vector<int>{};
}

std::vector<size_t> WorldModel::difference_group(int fn) const {
  std::vector<int> params;
  for (int i = 0; i < static_cast<int>(variables_.size()); ++i)
    if (variables_[i].role == Variable::Role::parameter && variables_[i].function == fn) params.push_back(i);
  std::set<int> group;
  // A parameter named as a size, direction or other vector (`BoxExtent`) is no point.
  for (int p : params)
    if (!variables_[p].output && (variables_[p].type == "float3" || variables_[p].type == "float4") &&
        data_.named_kind(variables_[p].name, Kind::absolute) == Kind::absolute)
      group.insert(p);
  auto in_group = [&](int node) { return tree_.is(node, "identifier") && group.count(variable_at(node)); };
  // An offset: no member of the group in it, and nothing the model knows as a point.
  auto offset = [&](int node) {
    Kind k = kind(node);
    if (k == Kind::absolute || k == Kind::translated || k == Kind::camera_offset) return false;
    std::vector<int> stack{node};
    while (!stack.empty()) {
      int m = stack.back();
      stack.pop_back();
      if (in_group(m)) return false;
      for (int c : tree_.named_children(m)) stack.push_back(c);
    }
    return true;
  };
  // The largest expression around a use that is still its point, moved by offsets.
  auto climb = [&](int n) {
    for (;;) {
      int p = tree_.at(n).parent;
      if (p < 0) return n;
      if (tree_.is(p, "parenthesized_expression") ||
          (tree_.is(p, "field_expression") && tree_.child_by_field(p, "argument") == n && tree_.text(tree_.child_by_field(p, "field")) == "xyz")) {
        n = p;
        continue;
      }
      if (!tree_.is(p, "binary_expression")) return n;
      std::string_view op = tree_.text(tree_.child_by_field(p, "operator"));
      int left = tree_.child_by_field(p, "left"), right = tree_.child_by_field(p, "right");
      if ((op == "+" && offset(left == n ? right : left)) || (op == "-" && left == n && offset(right))) {
        n = p;
        continue;
      }
      return n;
    }
  };
  // First the parameters that are no points of a difference at all (an extent added to a point),
  // then those whose differences are not with another member; either way until nothing changes.
  for (bool strict : {false, true})
  for (bool changed = true; changed && group.size() >= 2;) {
    changed = false;
    for (int p : std::set<int>(group)) {
      bool ok = !uses(p).empty();
      for (int use : uses(p)) {
        int point = climb(use), parent = tree_.at(point).parent;
        ok = ok && tree_.is(parent, "binary_expression") && tree_.text(tree_.child_by_field(parent, "operator")) == "-";
        if (!ok || !strict) continue;
        int other = tree_.child_by_field(parent, "left") == point ? tree_.child_by_field(parent, "right") : tree_.child_by_field(parent, "left");
        // The other side is one other member's point, moved by offsets.
        int found = -1, count = 0;
        std::vector<int> stack{other};
        while (!stack.empty()) {
          int m = stack.back();
          stack.pop_back();
          if (in_group(m)) found = m, ++count;
          for (int c : tree_.named_children(m)) stack.push_back(c);
        }
        ok = count == 1 && variable_at(found) != p && climb(found) == other;
      }
      if (!ok) {
        group.erase(p);
        changed = true;
      }
    }
  }
  std::vector<size_t> out;
  if (group.size() < 2) return out;
  for (size_t i = 0; i < params.size(); ++i)
    if (group.count(params[i])) out.push_back(i);
  return out;
}

void FileSummary::merge(const FileSummary& from, bool engine) {
  globals.insert(from.globals.begin(), from.globals.end());
  function_returns.insert(from.function_returns.begin(), from.function_returns.end());
  function_return_types.insert(from.function_return_types.begin(), from.function_return_types.end());
  macros.insert(from.macros.begin(), from.macros.end());
  field_types.insert(from.field_types.begin(), from.field_types.end());
  for (const auto& [function, uses] : from.parameter_uses) {
    auto [it, added] = parameter_uses.emplace(function, uses);
    if (added && engine)
      for (ParameterUse& u : it->second) u.engine = true;
  }
  parameter_kinds.insert(from.parameter_kinds.begin(), from.parameter_kinds.end());
  difference_groups.insert(from.difference_groups.begin(), from.difference_groups.end());
}

std::string WorldModel::function_return_type(const std::string& name) const {
  auto it = return_types_.find(name);
  return it != return_types_.end() ? it->second : "";
}

FileSummary WorldModel::summary() const {
  FileSummary s;
  for (const Variable& v : variables_) {
    if (v.role == Variable::Role::global && v.kind != Kind::unknown) s.globals[v.name] = v.kind;
    if (v.role == Variable::Role::field) s.field_types[v.owner + "." + v.name] = v.type;
  }
  s.function_returns = returns_;
  s.function_return_types = return_types_;
  // Parameters in declaration order per function; overloads of one arity share an entry.
  std::map<int, std::vector<int>> by_function;
  for (int i = 0; i < static_cast<int>(variables_.size()); ++i)
    if (variables_[i].role == Variable::Role::parameter && variables_[i].function >= 0) by_function[variables_[i].function].push_back(i);
  std::set<std::string> seen;
  for (const auto& [fn, params] : by_function) {
    int name = tree_.declarator_name(tree_.child_by_field(fn, "declarator"));
    if (name < 0) continue;
    std::string key = std::string(tree_.text(name)) + "/" + std::to_string(params.size());
    if (auto& kinds = s.parameter_kinds[std::string(tree_.text(name))]; kinds.empty())
      for (int p : params) kinds.push_back(variables_[p].kind);
    auto& entry = s.parameter_uses[key];
    bool first = seen.insert(key).second;
    if (first)
      if (std::vector<size_t> group = difference_group(fn); !group.empty()) s.difference_groups[key] = std::move(group);
    entry.resize(params.size());
    for (size_t k = 0; k < params.size(); ++k) {
      const std::string& type = variables_[params[k]].type;
      entry[k].type = first || entry[k].type == type ? type : "";
      // Only a float vector or matrix can carry a world position or transform.
      bool shaped = !type.empty() && (type.back() == '3' || type.back() == '4' || type.rfind("mat", 0) == 0);
      if (!shaped || !data_.is_float_type(type)) continue;
      bool named = data_.named_kind(variables_[params[k]].name, Kind::absolute) == Kind::translated;
      entry[k].translated = first ? named : entry[k].translated && named;
      bool used = !uses(params[k]).empty();
      bool matters = used && used_where_precision_matters(params[k]);
      bool harmless = used && only_harmless_uses(params[k]);
      entry[k].matters = entry[k].matters || matters;
      entry[k].harmless = first ? harmless : entry[k].harmless && harmless;
    }
  }
  return s;
}

}  // namespace lwc
