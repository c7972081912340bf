// lwc-translated-world: DoubleFloat math on an absolute position whose every use is
// camera-relative: translated world (plain float) would be cheaper and as precise.
#include "rules/checks/util.h"

namespace lwc::checks {
namespace {

class TranslatedWorld : public Check {
 public:
  explicit TranslatedWorld(const RuleInfo& rule)
      : df_types_(string_list(rule.data, "df-types")), consumers_(string_list(rule.data, "camera-relative-consumers")) {}

  void run(const CheckContext& ctx) const override {
    const SyntaxTree& t = ctx.tree;
    const auto& vars = ctx.world.variables();
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
      if (all_relative) ctx.report(t.span(v.decl), {{"name", v.name}, {"type", v.type}, {"consumer", consumer}});
    }
  }

 private:
  // The call that consumes `use` together with a camera term, or "" if the use is anything else.
  std::string relative_consumer(const CheckContext& ctx, int use) const {
    const SyntaxTree& t = ctx.tree;
    int list = t.at(use).parent;
    if (!t.is(list, "argument_list")) return {};
    int call = t.at(list).parent;
    std::string name(call_name(t, call));
    if (!matches_any(consumers_, name)) return {};
    for (int arg : call_arguments(t, call)) {
      if (arg == use) continue;
      Kind k = ctx.world.kind(arg);
      if (k == Kind::camera_offset || k == Kind::absolute) return name;
    }
    return {};
  }

  std::vector<std::string> df_types_, consumers_;
};

}  // namespace

std::unique_ptr<Check> make_translated_world(const RuleInfo& rule) { return std::make_unique<TranslatedWorld>(rule); }

}  // namespace lwc::checks
