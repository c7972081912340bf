// The world-space analysis (analyzer.h): what an expression holds: names, fields, calls, operators and assignments.
#include <algorithm>
#include <cctype>
#include <set>

#include "world/analyzer.h"

namespace lwc::analysis {

std::optional<Kind> Analyzer::source_kind(const Path& path, bool declared_global) {
  bool names = declared_global || m_.names_as_evidence_;
  std::string key = std::string(names ? "n:" : "s:");
  for (const auto& s : path) key += s.name + (s.call ? "()." : ".");
  auto it = source_cache_.find(key);
  if (it != source_cache_.end()) return it->second;
  std::optional<Kind> found;
  for (const auto& s : d_.sources)
    if ((!s.by_name || (names && (!s.plain_only || m_.plain_names_))) && s.pattern.matches(path)) {
      found = s.kind;
      break;
    }
  source_cache_.emplace(key, found);
  return found;
}

std::optional<FunctionRole> Analyzer::role_of(std::string_view name) const {
  Path p{{std::string(name), false}};
  for (const auto& f : d_.functions)
    if (f.pattern.matches(p)) return f.role;
  return std::nullopt;
}

int Analyzer::lookup(std::string_view name) const {
  if (frame_) {
    auto it = frame_->scope.find(std::string(name));
    if (it != frame_->scope.end()) return it->second;
  }
  auto g = globals_.find(std::string(name));
  return g != globals_.end() ? g->second : -1;
}

void Analyzer::join_at(std::unordered_map<int, Kind>& kinds, int id, Kind k) {
  auto [it, inserted] = kinds.emplace(id, k);
  if (!inserted) it->second = join(it->second, k);
}

void Analyzer::join_at_node(int id, Kind k) {
  Kind& at = m_.kinds_[static_cast<size_t>(id)];
  at = join(at, k);
}

Kind Analyzer::record(int id, Kind k) {
  join_at_node(id, k);
  if (run_) join_at(run_kinds_, id, k);
  return k;
}

void Analyzer::refer(int identifier, int var) {
  m_.refs_[identifier] = var;
  if (run_) run_->refs.emplace_back(identifier, m_.variables_[var].decl);
}

Kind Analyzer::eval(int id, int depth) {
  if (depth > kMaxDepth) {
    m_.too_deep_.push_back(id);
    if (run_) run_->too_deep.push_back(id);
    return Kind::unknown;
  }
  return record(id, eval_node(id, depth + 1));
}

Kind Analyzer::eval_node(int id, int depth) {
  std::string_view type = t_.at(id).type;
  if (type == "parenthesized_expression") {
    int inner = t_.named_child(id);
    return inner >= 0 ? eval(inner, depth) : Kind::unknown;
  }
  if (type == "identifier") return eval_identifier(id);
  if (type == "number_literal" || type == "true" || type == "false") return Kind::local;
  if (type == "field_expression") return eval_field(id, depth);
  if (type == "subscript_expression") return eval_subscript(id, depth);
  if (int cast = t_.cast_written_as_call(id); cast >= 0 && d_.is_float_type(t_.text(cast))) {
    Kind k = eval(t_.named_child(t_.child_by_field(id, "arguments")), depth);
    return is_3x3_type(t_.text(cast)) && is_matrix(k) ? Kind::rotation_matrix : k;
  }
  if (type == "call_expression") return eval_call(id, depth);
  if (type == "binary_expression") return eval_binary(id, depth);
  if (type == "assignment_expression") return eval_assignment(id, depth);
  if (type == "cast_expression") {
    int value = t_.child_by_field(id, "value");
    Kind k = value >= 0 ? eval(value, depth) : Kind::unknown;
    int target = t_.child_by_field(id, "type");
    if (target >= 0 && is_3x3_type(t_.text(target)) && is_matrix(k)) return Kind::rotation_matrix;
    return k;
  }
  if (type == "unary_expression") {
    int arg = t_.child_by_field(id, "argument");
    Kind k = arg >= 0 ? eval(arg, depth) : Kind::unknown;
    int op = t_.child_by_field(id, "operator");
    return op >= 0 && t_.text(op) == "-" ? negate(k) : (op >= 0 && t_.text(op) == "!" ? Kind::local : k);
  }
  if (type == "conditional_expression") {
    int c = t_.child_by_field(id, "condition");
    if (c >= 0) eval(c, depth);
    int a = t_.child_by_field(id, "consequence"), b = t_.child_by_field(id, "alternative");
    return join(a >= 0 ? eval(a, depth) : Kind::unknown, b >= 0 ? eval(b, depth) : Kind::unknown);
  }
  Kind k = Kind::unknown;
  bool last_only = type == "comma_expression";
  for (int c : t_.named_children(id)) {
    Kind ck = eval(c, depth);
    k = last_only ? ck : join(k, ck);
  }
  return (type == "initializer_list" || last_only) ? k : Kind::unknown;
}

Kind Analyzer::eval_identifier(int id) {
  std::string_view name = t_.text(id);
  int var = lookup(name);
  if (var >= 0) {
    refer(id, var);
    return current(var);
  }
  if (auto k = source_kind(Path{{std::string(name), false}})) return *k;
  if (inc_) {
    auto it = inc_->globals.find(std::string(name));
    if (it != inc_->globals.end()) return it->second;
  }
  return Kind::unknown;
}

Kind Analyzer::eval_field(int id, int depth) {
  int base = t_.child_by_field(id, "argument");
  int field = t_.child_by_field(id, "field");
  Kind base_kind = base >= 0 ? eval(base, depth) : Kind::unknown;
  if (auto p = m_.path(id)) {
    if (auto k = source_kind(*p)) return *k;
  }
  if (field < 0) return Kind::unknown;
  std::string name(t_.text(field));
  // A member of a struct held in a constant buffer or uniform (`Frame.CameraPos`) is uniform data
  // too: a position named as one would be on its own. (Not a matrix: engines that keep objects
  // camera-relative on the host still call theirs `mWorld`.)
  if (base >= 0 && t_.is(base, "identifier") && !is_swizzle(name))
    if (int var = lookup(t_.text(base)); var >= 0 && m_.variables_[var].uniform && m_.variables_[var].role == Variable::Role::global)
      if (auto k = source_kind(Path{{name, false}}, true); k == Kind::absolute) return *k;
  if (base >= 0 && t_.is(base, "identifier") && block_instances_.count(std::string(t_.text(base)))) {
    int var = lookup(name);
    if (var >= 0) {
      refer(field, var);
      return current(var);
    }
  }
  if (era_column() >= 0) {
    if (const auto* e = d_.engine_member(owner_of(base), name)) return era_column() > 0 && e->ue5_kind ? *e->ue5_kind : e->kind;
  }
  if (is_swizzle(name)) {
    if (is_matrix(base_kind)) return Kind::unknown;
    // `.w` of a position is its homogeneous coordinate or a packed scalar, not a coordinate.
    if ((name == "w" || name == "a") && base_kind != Kind::unknown) return Kind::local;
    return base_kind;
  }
  std::string by_owner = owner_of(base) + "." + name;
  touch_field(by_owner);
  auto it = field_kinds_.find(by_owner);
  if (it == field_kinds_.end()) {
    touch_field("." + name);
    it = field_kinds_.find("." + name);
  }
  return it != field_kinds_.end() ? it->second : Kind::unknown;
}

int Analyzer::era_column() const {
  if (!m_.era_) return -1;
  return *m_.era_ == UnrealEra::ue4 ? 0 : *m_.era_ == UnrealEra::ue5_0 ? 1 : 2;
}

std::string Analyzer::owner_of(int base) const {
  while (base >= 0 && t_.is(base, "parenthesized_expression")) base = t_.named_child(base);
  if (base >= 0 && t_.is(base, "field_expression")) {  // a.b.c: the type of a.b
    int field = t_.child_by_field(base, "field");
    return field >= 0 ? field_type(owner_of(t_.child_by_field(base, "argument")), std::string(t_.text(field))) : std::string();
  }
  if (base < 0 || !t_.is(base, "identifier")) return {};
  int var = lookup(t_.text(base));
  return var >= 0 ? m_.variables_[var].type : std::string();
}

std::string Analyzer::field_type(const std::string& owner, const std::string& name) const {
  if (auto it = fields_.find(owner + "." + name); it != fields_.end()) return m_.variables_[it->second].type;
  if (owner.empty())
    if (auto f = fields_by_name_.find(name); f != fields_by_name_.end() && f->second.size() == 1) return m_.variables_[f->second[0]].type;
  if (inc_)
    if (auto it = inc_->field_types.find(owner + "." + name); it != inc_->field_types.end()) return it->second;
  if (era_column() >= 0)
    if (const auto* e = d_.engine_member(owner, name)) return e->types[era_column()];
  if (!inc_) return {};
  if (!owner.empty()) return {};
  // A field name only one type of field in the includes has: indexed on first use (a UE file's
  // includes declare thousands of fields, and this is asked for every unknown owner). Read in
  // key order, a type that differs from the one found so far makes the name ambiguous.
  if (!include_field_by_name_) {
    include_field_by_name_.emplace();
    std::set<std::string> ambiguous;
    for (const auto& [key, type] : inc_->field_types) {
      size_t dot = key.rfind('.');
      if (dot == std::string::npos) continue;
      std::string field = key.substr(dot + 1);
      if (ambiguous.count(field)) continue;
      auto [it, added] = include_field_by_name_->emplace(field, type);
      if (added) continue;
      if (!it->second.empty() && it->second != type) {
        ambiguous.insert(field);
        it->second.clear();
      } else {
        it->second = type;
      }
    }
  }
  auto it = include_field_by_name_->find(name);
  return it != include_field_by_name_->end() ? it->second : std::string();
}

Kind Analyzer::eval_subscript(int id, int depth) {
  int base = t_.child_by_field(id, "argument");
  int index = t_.subscript_index(id);
  Kind k = base >= 0 ? eval(base, depth) : Kind::unknown;
  if (index >= 0) eval(index, depth);
  if (!is_matrix(k)) return k;
  // A name the file does not declare (an engine's array of matrices, bgfx's u_model[0]) is
  // indexed by element: the element is the matrix.
  if (t_.is(base, "identifier") && lookup(t_.text(base)) < 0) return k;
  // Row (HLSL) or column (GLSL) 3 of a 4x4 transform is its translation.
  bool translation = index >= 0 && t_.text(index) == "3";
  if (!translation) return Kind::direction;
  if (k == Kind::world_matrix) return Kind::absolute;
  if (k == Kind::translated_world_matrix) return Kind::translated;
  return Kind::unknown;
}

bool Analyzer::matrix_typed(int n) const {
  while (n >= 0 && t_.is(n, "parenthesized_expression")) n = t_.named_child(n);
  if (n < 0) return false;
  std::string type;
  if (t_.is(n, "identifier")) {
    int var = lookup(t_.text(n));
    if (var >= 0) type = m_.variables_[var].type;
  } else if (t_.is(n, "field_expression")) {
    int field = t_.child_by_field(n, "field");
    if (field >= 0) {
      auto it = fields_.find(owner_of(t_.child_by_field(n, "argument")) + "." + std::string(t_.text(field)));
      if (it != fields_.end()) type = m_.variables_[it->second].type;
    }
  } else if (t_.is(n, "call_expression") || t_.is(n, "cast_expression")) {
    int f = t_.child_by_field(n, t_.is(n, "call_expression") ? "function" : "type");
    if (f >= 0) type = std::string(t_.text(f));
  }
  return d_.is_matrix_type(type);
}

bool Analyzer::is_point(int v) const {
  while (v >= 0 && (t_.is(v, "parenthesized_expression") || t_.is(v, "cast_expression")))
    v = t_.is(v, "cast_expression") ? t_.child_by_field(v, "value") : t_.named_child(v);
  if (v < 0) return true;
  if (t_.is(v, "call_expression")) {
    int fn = t_.child_by_field(v, "function");
    int args = t_.child_by_field(v, "arguments");
    std::string_view name = fn >= 0 ? t_.text(fn) : std::string_view();
    bool ctor4 = ends_with(name, "4") && d_.is_float_type(name);
    if (ctor4 && args >= 0) {
      auto list = t_.named_children(args);
      if (list.size() >= 2 && t_.is(list.back(), "number_literal")) {
        std::string_view w = t_.text(list.back());
        return w.find_first_of("123456789") != std::string_view::npos;
      }
    }
    if (d_.is_float_type(name) && ends_with(name, "3")) return false;
  }
  if (t_.is(v, "field_expression")) {
    int field = t_.child_by_field(v, "field");
    if (field >= 0 && is_swizzle(t_.text(field)) && t_.text(field).size() == 3) return false;
  }
  if (t_.is(v, "identifier")) {
    int var = lookup(t_.text(v));
    if (var >= 0 && ends_with(m_.variables_[var].type, "3")) return false;
  }
  return true;
}

Kind Analyzer::transform(int vec, Kind vk, Kind mk, bool as_point) {
  if (mk == Kind::rotation_matrix) return Kind::direction;
  if (!is_matrix(mk)) return Kind::unknown;
  if (vk == Kind::direction || (!as_point && !is_point(vec))) return Kind::direction;
  switch (mk) {
    case Kind::world_matrix: return Kind::absolute;
    case Kind::translated_world_matrix: return Kind::translated;
    default: return Kind::local;
  }
}

Kind Analyzer::eval_call(int id, int depth) {
  int fn = t_.child_by_field(id, "function");
  int args_node = t_.child_by_field(id, "arguments");
  std::vector<int> args = args_node >= 0 ? t_.named_children(args_node) : std::vector<int>{};
  std::erase_if(args, [&](int a) { return t_.is(a, "comment"); });  // `/* out */ Ray.Origin`
  std::vector<Kind> kinds;
  for (int a : args) kinds.push_back(eval(a, depth));
  if (fn < 0) return Kind::unknown;
  if (!t_.is(fn, "identifier")) {
    if (t_.is(fn, "field_expression")) {  // a method call: texture.Sample(...)
      int base = t_.child_by_field(fn, "argument");
      if (base >= 0) eval(base, depth);
    }
    return Kind::unknown;
  }
  std::string name(t_.text(fn));
  // A function this file defines is what it computes, whatever an engine function of that name does.
  if (functions_.count(name) == 0) {
    if (auto p = m_.path(id)) {
      if (auto k = source_kind(*p)) return *k;
    }
  }
  if (d_.is_float_type(name)) {  // a constructor: float4(P, 1), vec3(...), float3x3(M)
    Kind k = Kind::unknown;
    for (Kind a : kinds) k = join(k, a);
    if (is_3x3_type(name) && is_matrix(k)) return Kind::rotation_matrix;
    return k;
  }
  if (auto it = functions_.find(name); it != functions_.end()) return call_user(it->second, args, kinds);
  if (era_column() >= 0)
    if (auto e = d_.engine_functions.find(name); e != d_.engine_functions.end()) return e->second[era_column()];
  if (auto role = role_of(name)) return apply_role(*role, args, kinds);
  if (inc_) {
    auto it = inc_->function_returns.find(name);
    if (it != inc_->function_returns.end()) return it->second;
  }
  return Kind::unknown;
}

Kind Analyzer::apply_role(FunctionRole role, const std::vector<int>& args, const std::vector<Kind>& k) {
  Kind a = k.size() > 0 ? k[0] : Kind::unknown, b = k.size() > 1 ? k[1] : Kind::unknown;
  switch (role) {
    case FunctionRole::transform_point:
    case FunctionRole::transform:
      if (k.size() < 2) return a;
      if (is_matrix(a) && is_matrix(b)) return compose(a, b);
      if (is_matrix(b)) return transform(args[0], a, b, role == FunctionRole::transform_point);
      if (is_matrix(a)) return transform(args[1], b, a, role == FunctionRole::transform_point);
      // A matrix lwcport does not know (or any operand that is not a constant) maps the value
      // to a space it does not know either.
      if ((holds_absolute(a) && !constant(args[1])) || (holds_absolute(b) && !constant(args[0]))) return Kind::unknown;
      if (role == FunctionRole::transform && (matrix_typed(args[0]) || matrix_typed(args[1]))) return Kind::unknown;
      return scale(a, b);
    case FunctionRole::direction: return Kind::direction;
    case FunctionRole::local: return Kind::local;
    case FunctionRole::join: {
      Kind j = Kind::unknown;
      for (size_t i = 0; i < k.size() && i < 2; ++i) j = join(j, k[i]);
      return j;
    }
    case FunctionRole::invert: return invert(a);
    case FunctionRole::same: return a;
    case FunctionRole::world_value: return a == Kind::unknown ? Kind::absolute : a;
    case FunctionRole::add: return add(a, b);
    case FunctionRole::subtract: return subtract(a, b);
    case FunctionRole::translated:
      if (a == Kind::absolute || a == Kind::world_matrix || b == Kind::world_matrix || b == Kind::camera_offset ||
          a == Kind::unknown || a == Kind::local)
        return is_matrix(a) ? Kind::translated_world_matrix : Kind::translated;
      return Kind::unknown;
  }
  return Kind::unknown;
}

bool Analyzer::large_world_typed(int n) const {
  while (n >= 0 && t_.is(n, "parenthesized_expression")) n = t_.named_child(n);
  std::string type;
  if (n >= 0 && t_.is(n, "identifier")) {
    int var = lookup(t_.text(n));
    if (var >= 0) type = m_.variables_[var].type;
  } else if (n >= 0 && t_.is(n, "field_expression")) {
    int field = t_.child_by_field(n, "field");
    if (field >= 0) type = field_type(owner_of(t_.child_by_field(n, "argument")), std::string(t_.text(field)));
  }
  return type.starts_with("FDF") || type.starts_with("FLWC");
}

Kind Analyzer::call_user(const std::vector<int>& overloads, const std::vector<int>& args, const std::vector<Kind>& kinds) {
  int fn = overloads.front();
  bool arity = false;  // a definition takes as many arguments as the call passes
  for (int candidate : overloads) {
    int d = t_.child_by_field(candidate, "declarator");
    while (d >= 0 && !t_.is(d, "function_declarator")) d = t_.child_by_field(d, "declarator");
    int list = d >= 0 ? t_.child_by_field(d, "parameters") : -1;
    std::vector<int> params = list >= 0 ? t_.named_children(list) : std::vector<int>{};
    std::erase_if(params, [&](int p) { return t_.is(p, "comment"); });
    if (run_) run_->functions.push_back(candidate);
    if (list < 0 || params.size() != args.size()) continue;
    // A large-world argument never binds to a float parameter: that is another overload's call
    // (`F(float3, FDFMatrix)` beside `F(float3, float4x4)`).
    bool fits = true;
    for (size_t i = 0; i < params.size() && fits; ++i) {
      int type = t_.child_by_field(params[i], "type");
      fits = !(type >= 0 && d_.is_float_type(t_.text(type)) && large_world_typed(args[i]));
    }
    if (fits || !arity) fn = candidate, arity = fits;
  }
  // Without one (its other arm of an `#if` is the definition this variant does not see), the
  // arguments cannot be matched to parameters: none is given what the call passes.
  bool interesting = arity && std::any_of(kinds.begin(), kinds.end(), [](Kind k) { return k != Kind::unknown && k != Kind::local; });
  Summary s = analyze_function(fn, interesting ? kinds : std::vector<Kind>{});
  for (size_t i = 0; i < s.outs.size() && i < args.size(); ++i)
    if (s.outs[i] != Kind::unknown) assign(args[i], s.outs[i]);
  return s.ret;
}

Kind Analyzer::eval_binary(int id, int depth) {
  int l = t_.child_by_field(id, "left"), r = t_.child_by_field(id, "right");
  int op_node = t_.child_by_field(id, "operator");
  Kind a = l >= 0 ? eval(l, depth) : Kind::unknown;
  Kind b = r >= 0 ? eval(r, depth) : Kind::unknown;
  std::string_view op = op_node >= 0 ? t_.text(op_node) : std::string_view();
  return binary(op, l, a, r, b);
}

Kind Analyzer::binary(std::string_view op, int l, Kind a, int r, Kind b) {
  // A position minus a value of unknown space that is named as a position is a difference of
  // two positions (a direction), not a position: unknown, as the space of that value is.
  if (op == "-" && ((holds_absolute(a) && b == Kind::unknown && named_position(r)) ||
                    (holds_absolute(b) && a == Kind::unknown && named_position(l))))
    return Kind::unknown;
  if (op == "+") return add(a, b);
  if (op == "-") return subtract(a, b);
  if (op == "*" && (is_matrix(a) || is_matrix(b) || matrix_typed(l) || matrix_typed(r))) {
    if (t_.lang == Lang::glsl) {
      if (is_matrix(a) && is_matrix(b)) return compose(b, a);  // column vectors: b applies first
      if (is_matrix(a)) return transform(r, b, a);
      if (is_matrix(b)) return transform(l, a, b);
    }
    return Kind::unknown;  // a product with a matrix lwcport does not know (or HLSL's component-wise one)
  }
  if (op == "*" || op == "/") {
    // Scaled by a variable, a position moves to another space (grid cells, a unit volume):
    // only a constant (a literal, an ALL_CAPS macro such as CENTIMETER_TO_KILOMETER) or the
    // homogeneous divide keeps it.
    if ((holds_absolute(a) && !constant(r)) || (holds_absolute(b) && !constant(l))) return Kind::unknown;
    return scale(a, b);
  }
  return Kind::local;  // comparisons, logic, bit operations
}

bool Analyzer::constant(int n) const {
  while (n >= 0 && t_.is(n, "parenthesized_expression")) n = t_.named_child(n);
  if (n < 0) return false;
  if (t_.is(n, "number_literal")) return true;
  if (t_.is(n, "unary_expression")) return constant(t_.child_by_field(n, "argument"));
  // The homogeneous divide (P.xyz / P.w) keeps the position where it is.
  if (t_.is(n, "field_expression") && t_.text(t_.child_by_field(n, "field")) == "w") return true;
  if (!t_.is(n, "identifier")) return false;
  std::string_view w = t_.text(n);
  return w.size() > 1 && std::all_of(w.begin(), w.end(), [](char c) { return std::isupper(static_cast<unsigned char>(c)) || std::isdigit(static_cast<unsigned char>(c)) || c == '_'; });
}

bool Analyzer::named_position(int n) const {
  while (n >= 0 && (t_.is(n, "parenthesized_expression") ||
                    (t_.is(n, "field_expression") && is_swizzle(t_.text(t_.child_by_field(n, "field"))))))
    n = t_.is(n, "parenthesized_expression") ? t_.named_child(n) : t_.child_by_field(n, "argument");
  if (n < 0) return false;
  std::string_view name;
  if (t_.is(n, "identifier")) name = t_.text(n);
  else if (t_.is(n, "field_expression") && t_.child_by_field(n, "field") >= 0) name = t_.text(t_.child_by_field(n, "field"));
  for (std::string_view w : {"Pos", "pos", "Origin", "origin", "Center", "center"})
    if (name.find(w) != std::string_view::npos) return true;
  return false;
}

Kind Analyzer::eval_assignment(int id, int depth) {
  int l = t_.child_by_field(id, "left"), r = t_.child_by_field(id, "right");
  int op_node = t_.child_by_field(id, "operator");
  std::string_view op = op_node >= 0 ? t_.text(op_node) : "=";
  Kind k = r >= 0 ? eval(r, depth) : Kind::unknown;
  if (op != "=" && l >= 0) k = binary(op.substr(0, op.size() - 1), l, eval(l, depth), r, k);
  else if (l >= 0 && !t_.is(l, "identifier")) eval(l, depth);  // field bases and indices are uses too
  if (l >= 0) assign(l, k);
  return k;
}

void Analyzer::assign(int lhs, Kind k) {
  while (lhs >= 0 && t_.is(lhs, "parenthesized_expression")) lhs = t_.named_child(lhs);
  if (lhs < 0) return;
  if (t_.is(lhs, "identifier")) {
    int var = lookup(t_.text(lhs));
    if (var >= 0) {
      refer(lhs, var);
      hold(var, k, -1);
    }
    return;
  }
  if (t_.is(lhs, "subscript_expression") || (t_.is(lhs, "field_expression") && is_swizzle(t_.text(t_.child_by_field(lhs, "field"))) &&
                                              t_.is(t_.child_by_field(lhs, "argument"), "subscript_expression"))) {
    int sub = t_.is(lhs, "subscript_expression") ? lhs : t_.child_by_field(lhs, "argument");
    int base = t_.child_by_field(sub, "argument");
    int index = t_.subscript_index(sub);
    int var = base >= 0 && t_.is(base, "identifier") ? lookup(t_.text(base)) : -1;
    // M[3] = vec4(0, 0, 0, 1): the translation of a matrix is cleared, and it only rotates now
    // (the relative-to-eye pattern of globe engines).
    if (var >= 0 && is_matrix(current(var)) && index >= 0 && t_.text(index) == "3" && !holds_absolute(k)) {
      refer(base, var);
      m_.cleared_.insert(var);
      if (run_) run_->cleared.push_back(m_.variables_[var].decl);
      if (frame_) frame_->current[var] = Kind::rotation_matrix;
      return;
    }
    if (holds_absolute(k)) assign(base, k);
    return;
  }
  if (!t_.is(lhs, "field_expression")) return;
  int base = t_.child_by_field(lhs, "argument");
  int field = t_.child_by_field(lhs, "field");
  if (field < 0) return;
  std::string name(t_.text(field));
  if (is_swizzle(name)) {
    if (holds_absolute(k)) assign(base, k);
    return;
  }
  std::string owner = owner_of(base);
  touch_field(owner + "." + name);
  touch_field("." + name);
  Kind& by_owner = field_kinds_[owner + "." + name];
  by_owner = join(by_owner, k);
  Kind& by_name = field_kinds_["." + name];
  by_name = join(by_name, k);
  // Report at the struct's field declaration when it is in this file, else at the assignment. A
  // field of a struct reached through another (`Result.Particle.X`) whose type is not known is
  // not taken for this file's field of the same name: that struct is most likely the engine's.
  int var = -1;
  if (auto it = fields_.find(owner + "." + name); it != fields_.end()) var = it->second;
  else if (auto f = fields_by_name_.find(name); f != fields_by_name_.end() && f->second.size() == 1 && t_.is(base, "identifier"))
    var = f->second[0];
  if (var >= 0) {
    hold(var, k, -1);
    return;
  }
  // A field declared elsewhere: reported at the assignment, only when its declared type is
  // known to be a float (a header's struct the summaries read); an unknown type is not guessed.
  k = d_.named_kind(name, k);
  std::string type = owner.empty() && !t_.is(base, "identifier") ? std::string() : field_type(owner, name);
  if (holds_absolute(k) && lookup(name) < 0 && !type.empty() && d_.is_float_type(type))
    report({AbsoluteHolder::What::field, lhs, std::string(t_.text(lhs)), type, k});
}

}  // namespace lwc::analysis
