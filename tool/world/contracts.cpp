// The world-space analysis (analyzer.h): kinds the whole file's code settles once every function
// has been analysed: what an engine function's contract says a parameter holds, and what a value's
// structure says (a point added to the pre-view translation, a uniform point taken from one).
#include "world/analyzer.h"

namespace lwc::analysis {

void Analyzer::engine_contract_parameters() {
  // A function the file defines itself takes what it declares; the engine's own file defines the
  // engine's function, whose parameter held an absolute point in UE4 whatever it is called.
  std::map<std::string_view, std::vector<int>> defined;
  for (int fn : function_order_)
    if (int name = t_.declarator_name(t_.child_by_field(fn, "declarator")); name >= 0) defined[t_.text(name)].push_back(fn);
  auto contract = [&](int var) {
    const Variable& v = m_.variables_[var];
    if (v.role != Variable::Role::parameter || v.output || v.kind != Kind::unknown || (v.type != "float3" && v.type != "float4") ||
        d_.named_kind(v.name, Kind::absolute) != Kind::absolute)
      return;
    hold(var, Kind::absolute, v.decl);
  };
  for (const auto& [name, entry] : d_.engine_translated_parameters) {
    if (auto own = defined.find(name); own != defined.end()) {
      if (!context_.engine_file) continue;
      for (int fn : own->second) {
        std::vector<int> params;  // in declaration order
        for (int var = 0; var < static_cast<int>(m_.variables_.size()); ++var)
          if (m_.variables_[var].role == Variable::Role::parameter && m_.variables_[var].function == fn) params.push_back(var);
        for (size_t index : entry.indices)
          if (index < params.size()) contract(params[index]);
      }
      continue;
    }
    for (int call : t_.calls_named(name)) {
      std::vector<int> args = t_.named_children(t_.child_by_field(call, "arguments"));
      std::erase_if(args, [&](int n) { return t_.is(n, "comment"); });
      if (inc_) {
        auto it = inc_->parameter_uses.find(name + "/" + std::to_string(args.size()));
        if (it != inc_->parameter_uses.end() && !it->second.empty() && !it->second.front().engine) continue;  // the project's own copy
      }
      for (size_t index : entry.indices) {
        int var = index < args.size() && t_.is(args[index], "identifier") ? m_.variable_at(args[index]) : -1;
        if (var >= 0) contract(var);
      }
    }
  }
}


void Analyzer::absolute_by_translation() {
  // The variable a point operand reads (`P`, `P.xyz`), or -1.
  auto variable_of = [&](int n) {
    if (t_.is(n, "field_expression") && t_.text(t_.child_by_field(n, "field")) == "xyz") n = t_.child_by_field(n, "argument");
    return t_.is(n, "identifier") ? m_.variable_at(n) : -1;
  };
  auto vector = [](const Variable& v) { return v.type == "float3" || v.type == "float4"; };
  auto operands = [&](int n, std::string_view op) {
    std::vector<std::pair<int, int>> out;
    if (t_.is(n, "binary_expression") && t_.text(t_.child_by_field(n, "operator")) == op) {
      int left = t_.child_by_field(n, "left"), right = t_.child_by_field(n, "right");
      out = {{left, right}, {right, left}};
    }
    return out;
  };
  // `P + PreViewTranslation` makes a translated point only of an absolute one: a local or
  // parameter of no known kind added to the camera offset holds an absolute world position,
  // whatever it is called (space from structure, before names).
  for (int n = 0; n < static_cast<int>(t_.nodes.size()); ++n)
    for (auto [point, offset] : operands(n, "+")) {
      int var = m_.kind(offset) == Kind::camera_offset && m_.kind(point) == Kind::unknown ? variable_of(point) : -1;
      if (var < 0) continue;
      const Variable& v = m_.variables_[var];
      if ((v.role == Variable::Role::local || v.role == Variable::Role::parameter) && !v.output && v.kind == Kind::unknown && !v.clip &&
          vector(v))
        hold(var, Kind::absolute, v.decl);
    }
  // A uniform point taken from an absolute one, or the other way round (`length(P - LodOrigin)`),
  // is a point of the same world: a difference of points means something in one frame only. Only a
  // name that says point makes it one (a vector may be an offset).
  for (int n = 0; n < static_cast<int>(t_.nodes.size()); ++n)
    for (auto [point, other] : operands(n, "-")) {
      int p = variable_of(point);
      bool absolute = m_.kind(point) == Kind::absolute || (p >= 0 && m_.variables_[p].kind == Kind::absolute);
      int var = absolute && m_.kind(other) == Kind::unknown ? variable_of(other) : -1;
      if (var < 0) continue;
      Variable& v = m_.variables_[var];
      if (v.role == Variable::Role::global && v.uniform && v.kind == Kind::unknown && vector(v) && named_as_point(v.name)) v.kind = Kind::absolute;
    }
}

}  // namespace lwc::analysis
