// lwc-translated-world: DoubleFloat math on an absolute position whose every use is
// camera-relative: translated world (plain float) would be cheaper and as precise. The rewrite
// computes it in translated world from the start and turns each use into plain float math.
#include <optional>

#include <fmt/format.h>

#include "rules/checks/util.h"

namespace lwc::checks {
namespace {

class TranslatedWorld : public Check {
 public:
  explicit TranslatedWorld(const RuleInfo& rule)
      : df_types_(string_list(rule.data, "df-types")),
        consumers_(string_list(rule.data, "camera-relative-consumers")),
        to_translated_(string_list(rule.data, "to-translated")),
        camera_differences_(string_list(rule.data, "camera-differences")) {}

  void run(const CheckContext& ctx) const override {
    const SyntaxTree& t = ctx.tree;
    const auto& vars = ctx.world.variables();
    std::optional<DeclaredNames> names;  // for the rewrites' new names, made at the first one
    for (size_t i = 0; i < vars.size(); ++i) {
      const Variable& v = vars[i];
      if (v.role != Variable::Role::local || v.kind != Kind::absolute || !matches_any(df_types_, v.type)) continue;
      auto uses = ctx.world.uses(static_cast<int>(i));
      if (uses.empty()) continue;
      std::string consumer;
      bool all_relative = true;
      for (int use : uses) {
        std::string c = relative_consumer(ctx, use);
        if (c.empty()) {
          all_relative = false;
          break;
        }
        if (consumer.empty()) consumer = c;
      }
      if (!all_relative) continue;
      Finding& f = ctx.report(t.span(v.decl), {{"name", v.name}, {"type", v.type}, {"consumer", consumer}});
      if (!names) names.emplace(ctx.world);
      RewritePlan plan = plan_rewrite(ctx, static_cast<int>(i), *names);
      if (plan.blocker.empty()) ctx.fix(f, "translated", {{"name", v.name}, {"new-name", translated_name(v.name)}}, plan.edits);
      else f.withheld.push_back("translated world: " + plan.blocker);
    }
  }

 private:
  // The call that consumes `use` together with the camera, or "" if the use is anything else.
  std::string relative_consumer(const CheckContext& ctx, int use) const {
    const SyntaxTree& t = ctx.tree;
    int list = t.at(use).parent;
    if (!t.is(list, "argument_list")) return {};
    int call = t.at(list).parent;
    std::string name(call_name(t, call));
    if (!matches_any(consumers_, name)) return {};
    // The other operand must be the camera: the pre-view translation, or a camera position with a
    // translated twin (an absolute point that is not the camera, such as a volume's origin, is not).
    for (int arg : call_arguments(t, call)) {
      if (arg == use) continue;
      Kind k = ctx.world.kind(arg);
      if (k == Kind::camera_offset || (k == Kind::absolute && !translated_twin(ctx, arg).empty())) return name;
    }
    return {};
  }

  // FDFVector3 X = DFMultiply(P, LocalToWorld) -> float3 TranslatedX =
  // DFTransformLocalToTranslatedWorld(P, LocalToWorld, PrimaryView.PreViewTranslation); each use
  // (a camera difference or the move to translated world) becomes plain float.
  RewritePlan plan_rewrite(const CheckContext& ctx, int var, const DeclaredNames& names) const {
    const SyntaxTree& t = ctx.tree;
    const Variable& v = ctx.world.variables()[var];
    if (v.type != "FDFVector3") return withheld(fmt::format("`{}` is tile/offset or not a position vector: port it to `FDFVector3` first", v.type));
    int init = v.init;
    auto args = t.is(init, "call_expression") && call_name(t, init) == "DFMultiply" ? call_arguments(t, init) : std::vector<int>{};
    if (args.size() != 2 || ctx.world.kind(args[1]) != Kind::world_matrix)
      return withheld(fmt::format("its value (`{}`) is not a local position times a local-to-world matrix", init >= 0 ? shortened(t.text(init)) : ""));
    std::string name = translated_name(v.name);
    if (names.taken(name, v.function)) return withheld(fmt::format("the name `{}` is already taken", name));
    RewritePlan plan;
    plan.edits.push_back({t.span(t.child_by_field(v.declaration, "type")), "float3"});
    plan.edits.push_back({t.span(v.decl), name});
    plan.edits.push_back({t.span(init), fmt::format("DFTransformLocalToTranslatedWorld({}, {}, PrimaryView.PreViewTranslation)",
                                                    t.text(args[0]), t.text(args[1]))});
    for (int use : ctx.world.uses(var)) {
      int call = t.at(t.at(use).parent).parent;
      auto call_args = call_arguments(t, call);
      int other = call_args.size() == 2 ? call_args[call_args[0] == use ? 1 : 0] : -1;
      std::string consumer(call_name(t, call));
      std::string text;
      if (ctx.world.kind(other) == Kind::camera_offset && matches_any(to_translated_, consumer)) {
        text = name;
      } else if (std::string twin = translated_twin(ctx, other); !twin.empty() && matches_any(camera_differences_, consumer)) {
        text = call_args[0] == use ? name + " - " + twin : twin + " - " + name;
        if (!bare_context(t, call)) text = "(" + text + ")";
      } else {
        return withheld(fmt::format("`{}` (line {}) keeps the result in DoubleFloat, so the value must stay one", shortened(t.text(call)), line_of(t, call)));
      }
      plan.edits.push_back({t.span(call), text});
    }
    return plan;
  }

  // Where `a - b` may stand without parentheses: a whole argument, initialiser or statement.
  static bool bare_context(const SyntaxTree& t, int node) {
    int parent = t.at(node).parent;
    for (const char* type : {"argument_list", "init_declarator", "return_statement", "expression_statement", "parenthesized_expression"})
      if (t.is(parent, type)) return true;
    return t.is(parent, "assignment_expression") && t.child_by_field(parent, "right") == node;
  }

  std::vector<std::string> df_types_, consumers_;
  // Consumers whose float result is the translated position, or its difference with the camera.
  std::vector<std::string> to_translated_, camera_differences_;
};

}  // namespace

std::unique_ptr<Check> make_translated_world(const RuleInfo& rule) { return std::make_unique<TranslatedWorld>(rule); }

}  // namespace lwc::checks
