// lwc-uniform-world-float: a constant buffer / uniform member holding absolute world data in
// float32, except the documented pattern of one reference point plus offsets relative to it.
#include <set>

#include "rules/checks/util.h"

namespace lwc::checks {
namespace {

class UniformWorldFloat : public Check {
 public:
  explicit UniformWorldFloat(const RuleInfo& rule)
      : relative_(string_list(rule.data, "relative-names")),
        reference_(string_list(rule.data, "reference-names")),
        descriptions_(rule.data.at("kinds")) {}

  void run(const CheckContext& ctx) const override {
    const auto& vars = ctx.world.variables();
    // Blocks (or the global scope, -1) that store values relative to a shared reference.
    std::set<int> relative_blocks;
    for (const Variable& v : vars)
      if (v.uniform && matches_any(relative_, v.name)) relative_blocks.insert(v.block);
    for (size_t i = 0; i < vars.size(); ++i) {
      const Variable& v = vars[i];
      if (!v.uniform || v.role != Variable::Role::global || !holds_absolute(v.kind)) continue;
      // Reported where some use lets its rounding reach a result, not where it is only rotated,
      // normalised or handed to code lwcport cannot see.
      if (!ctx.world.used_where_precision_matters(static_cast<int>(i))) continue;
      if (ctx.world.combined_with_translated(static_cast<int>(i))) continue;
      if (!ctx.world.data().is_float_type(v.type) || matches_any(relative_, v.name)) continue;
      if (relative_blocks.count(v.block) && matches_any(reference_, v.name)) continue;
      std::string kind(kind_name(v.kind));
      ctx.report(ctx.tree.span(v.decl), {{"name", v.name}, {"type", v.type}, {"holds", descriptions_.value(kind, kind)}});
    }
  }

 private:
  std::vector<std::string> relative_, reference_;
  nlohmann::json descriptions_;
};

}  // namespace

std::unique_ptr<Check> make_uniform_world_float(const RuleInfo& rule) { return std::make_unique<UniformWorldFloat>(rule); }

}  // namespace lwc::checks
