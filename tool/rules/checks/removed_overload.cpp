// lwc-removed-overload: a UE4 material function called with a primitive id, an overload UE 5.0
// removed when the primitive's transform became a large-world matrix
// (`GetLocalToWorld3x3(Parameters.PrimitiveId)`). The rewrite passes the material parameters
// UE5's overload takes, or spells out UE4's body with the era's library call.
#include <fmt/format.h>

#include "rules/checks/util.h"

namespace lwc::checks {
namespace {

class RemovedOverload : public Check {
 public:
  explicit RemovedOverload(const RuleInfo& rule)
      : id_types_(string_list(rule.data, "id-types")), parameter_types_(string_list(rule.data, "parameter-types")) {
    for (const auto& [name, o] : rule.data.at("overloads").items())
      overloads_[name] = {o.at("member").get<std::string>(), o.at("why").get<std::string>()};
  }

  void run(const CheckContext& ctx) const override {
    if (!ctx.unreal) return;
    const SyntaxTree& t = ctx.tree;
    for (int call : nodes_of(t, "call_expression")) {
      std::string name(call_name(t, call));
      auto o = overloads_.find(name);
      if (o == overloads_.end() || defines_function(t, name)) continue;
      auto args = call_arguments(t, call);
      if (args.size() != 1 || !primitive_id(ctx, args[0])) continue;
      UnrealEra era = ctx.unreal->era;
      bool ue5_0 = era == UnrealEra::ue5_0;
      Vars vars{{"function", name},
                {"argument", std::string(t.text(args[0]))},
                {"why", o->second.why},
                {"when", era == UnrealEra::ue4 ? "when this code moves to UE5" : "in " + std::string(era_name(era))},
                {"library", ue5_0 ? "`LWCToFloat3x3`" : "`DFToFloat3x3`"}};
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
      vars["call"] = ue5_0 ? "LWCToFloat3x3" : "DFToFloat3x3";
      ctx.fix(f, "library", vars,
              {{t.span(call), fmt::format("{}(GetPrimitiveData({}).{})", vars["call"], t.text(args[0]), o->second.member)}});
    }
  }

 private:
  struct Overload {
    std::string member;  // the primitive's member UE4's overload read
    std::string why;
  };

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
  std::vector<std::string> id_types_, parameter_types_;
};

}  // namespace

std::unique_ptr<Check> make_removed_overload(const RuleInfo& rule) { return std::make_unique<RemovedOverload>(rule); }

}  // namespace lwc::checks
