// lwc-removed-engine-api: UE4 engine API that UE 5.0 removed in the code a large-world port
// touches: an overload taking a primitive id (`GetLocalToWorld3x3(Parameters.PrimitiveId)`), whose
// rewrite passes the material parameters UE5's overload takes or spells out UE4's body with the
// era's library call; and a packed member UE5 split (`ObjectWorldPositionAndRadius`), whose
// rewrite reads UE5's members, a large-world part demoted with the era's marker as UE4 read it.
#include <fmt/format.h>

#include "rules/checks/util.h"

namespace lwc::checks {
namespace {

class RemovedEngineApi : public Check {
 public:
  explicit RemovedEngineApi(const RuleInfo& rule)
      : id_types_(string_list(rule.data, "id-types")), parameter_types_(string_list(rule.data, "parameter-types")) {
    for (const auto& [name, o] : rule.data.at("overloads").items())
      overloads_[name] = {o.at("member").get<std::string>(), o.at("why").get<std::string>()};
    for (const auto& [owner, members] : rule.data.at("members").items())
      for (const auto& [name, m] : members.items())
        members_[owner][name] = {m.at("xyz").get<std::string>(), m.at("w").get<std::string>(), m.value("large-world", false),
                                 m.at("why").get<std::string>()};
  }

  void run(const CheckContext& ctx) const override {
    if (!ctx.unreal) return;
    overloads(ctx);
    split_members(ctx);
  }

 private:
  struct Overload {
    std::string member;  // the primitive's member UE4's overload read
    std::string why;
  };
  // A float4 member UE5 split in two: what its `.xyz` and `.w` read there ({object}: the struct).
  struct SplitMember {
    std::string xyz, w;
    bool large_world;  // the `.xyz` part is a large-world value in UE5
    std::string why;
  };

  void overloads(const CheckContext& ctx) const {
    const SyntaxTree& t = ctx.tree;
    for (int call : nodes_of(t, "call_expression")) {
      std::string name(call_name(t, call));
      auto o = overloads_.find(name);
      if (o == overloads_.end() || defines_function(t, name)) continue;
      auto args = call_arguments(t, call);
      if (args.size() != 1 || !primitive_id(ctx, args[0])) continue;
      UnrealEra era = ctx.unreal->era;
      bool ue5_0 = era == UnrealEra::ue5_0;
      std::string library = ue5_0 ? "LWCToFloat3x3" : "DFToFloat3x3";
      Vars vars{{"what", fmt::format("`{}` calls UE4's overload that takes a primitive id", t.text(call))},
                {"why", o->second.why},
                {"when", when(era)},
                {"instead", fmt::format("pass the material parameters (`{}(Parameters)`), or take the 3x3 part of "
                                        "`GetPrimitiveData(Id).{}` with `{}`", name, o->second.member, library)}};
      Finding& f = ctx.report(t.span(call), vars);
      if (era == UnrealEra::ue4) {
        f.withheld.push_back(fmt::format("UE4 has no other overload of `{}` to call: set \"unreal\" in .lwcport.json to the engine "
                                         "this code moves to", name));
        continue;
      }
      // `X.PrimitiveId` of a material parameters struct: UE5's overload takes `X` itself.
      int object = owner_of_id(t, args[0]);
      if (object >= 0 && matches_any(parameter_types_, declared_type(ctx, object))) {
        vars["parameters"] = t.text(object);
        ctx.fix(f, "parameters", vars, {{t.span(args[0]), std::string(t.text(object))}});
        continue;
      }
      vars["call"] = library;
      ctx.fix(f, "library", vars,
              {{t.span(call), fmt::format("{}(GetPrimitiveData({}).{})", library, t.text(args[0]), o->second.member)}});
    }
  }

  void split_members(const CheckContext& ctx) const {
    const SyntaxTree& t = ctx.tree;
    for (int id : nodes_of(t, "field_expression")) {
      Member m = member_of(t, id);
      if (m.empty()) continue;
      auto owner = members_.find(engine_struct_of(ctx, id));
      if (owner == members_.end()) continue;
      auto split = owner->second.find(m.member);
      if (split == owner->second.end() || declares_field(ctx, owner->first, m.member)) continue;
      const SplitMember& s = split->second;
      UnrealEra era = ctx.unreal->era;
      // UE4's primitive uniform buffer is read through a call in UE5.
      std::string object = ue5_spelling(ctx, id);
      object.resize(object.size() - m.member.size() - 1);
      auto part = [&](const std::string& text) { return fmt::format(fmt::runtime(text), fmt::arg("object", object)); };
      std::string marker = era == UnrealEra::ue5_0 ? "LWCHackToFloat" : "DFHackToFloat";
      std::string xyz = s.large_world ? marker + "(" + part(s.xyz) + ")" : part(s.xyz);
      Vars vars{{"what", fmt::format("`{}` reads UE4's packed `{}`", t.text(id), m.member)},
                {"why", s.why},
                {"when", when(era)},
                {"instead", fmt::format("read `{}` for its `.xyz` and `{}` for its `.w`", part(s.xyz), part(s.w))},
                {"marker", marker}};
      Finding& f = ctx.report(t.span(id), vars);
      if (era == UnrealEra::ue4) {
        f.withheld.push_back(fmt::format("UE4 has only `{}`: set \"unreal\" in .lwcport.json to the engine this code moves to", m.member));
        continue;
      }
      if (written(t, id)) {
        f.withheld.push_back(fmt::format("the line stores into `{}`: store UE5's parts by hand", m.member));
        continue;
      }
      int parent = t.at(id).parent;
      int field = t.is(parent, "field_expression") ? t.child_by_field(parent, "field") : -1;
      std::string swizzle = field >= 0 ? std::string(t.text(field)) : "";
      if (field < 0) {
        vars["parts"] = fmt::format("float4({}, {})", xyz, part(s.w));
        ctx.fix(f, s.large_world ? "parts-marked" : "parts", vars, {{t.span(id), vars["parts"]}});
      } else if (swizzle == "w") {
        vars["parts"] = part(s.w);
        ctx.fix(f, "parts", vars, {{t.span(parent), vars["parts"]}});
      } else if (swizzle.find_first_not_of("xyz") == std::string::npos && swizzle.size() <= 3) {
        vars["parts"] = swizzle == "xyz" ? xyz : xyz + "." + swizzle;
        ctx.fix(f, s.large_world ? "parts-marked" : "parts", vars, {{t.span(parent), vars["parts"]}});
      } else {
        f.withheld.push_back(fmt::format("`.{}` mixes the two parts UE5 keeps apart: read them by hand", swizzle));
      }
    }
  }

  // The file declares the struct with that member itself (a copy of the engine's header, or the
  // header): its own member, not the engine's.
  static bool declares_field(const CheckContext& ctx, const std::string& owner, const std::string& member) {
    for (const Variable& v : ctx.world.variables())
      if (v.role == Variable::Role::field && v.owner == owner && v.name == member) return true;
    return false;
  }

  // The member (or a swizzle of it) is what an assignment stores into: the code that fills it.
  static bool written(const SyntaxTree& t, int id) {
    int node = id, parent = t.at(id).parent;
    if (t.is(parent, "field_expression") && t.child_by_field(parent, "argument") == node) node = parent, parent = t.at(node).parent;
    return t.is(parent, "assignment_expression") && t.child_by_field(parent, "left") == node;
  }

  static std::string when(UnrealEra era) {
    return era == UnrealEra::ue4 ? "when this code moves to UE5" : "in " + std::string(era_name(era));
  }

  // A primitive id: `X.PrimitiveId`, or a variable of an integer type (UE5's overloads take the
  // parameters structs, whose type is never an integer).
  bool primitive_id(const CheckContext& ctx, int node) const {
    const SyntaxTree& t = ctx.tree;
    Member m = member_of(t, node);
    if (!m.empty()) return m.member == "PrimitiveId";
    return t.is(node, "identifier") && matches_any(id_types_, declared_type(ctx, node));
  }

  // `X` of `X.PrimitiveId`, or -1.
  static int owner_of_id(const SyntaxTree& t, int node) {
    if (!t.is(node, "field_expression")) return -1;
    int base = t.child_by_field(node, "argument");
    return t.is(base, "identifier") ? base : -1;
  }

  static std::string declared_type(const CheckContext& ctx, int identifier) {
    int var = ctx.world.variable_at(identifier);
    return var >= 0 ? ctx.world.variables()[static_cast<size_t>(var)].type : std::string();
  }

  std::map<std::string, Overload> overloads_;
  std::map<std::string, std::map<std::string, SplitMember>> members_;  // struct -> member -> its UE5 parts
  std::vector<std::string> id_types_, parameter_types_;
};

}  // namespace

std::unique_ptr<Check> make_removed_engine_api(const RuleInfo& rule) { return std::make_unique<RemovedEngineApi>(rule); }

}  // namespace lwc::checks
