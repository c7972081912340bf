// lwc-float-world-position: a float variable, field, parameter or return holding absolute world data.
#include "rules/checks/util.h"

namespace lwc::checks {
namespace {

class FloatWorldPosition : public Check {
 public:
  explicit FloatWorldPosition(const RuleInfo& rule) : descriptions_(rule.data.at("kinds")) {}

  void run(const CheckContext& ctx) const override {
    for (const AbsoluteHolder& h : ctx.world.absolute_holders()) {
      std::string what = h.what == AbsoluteHolder::What::variable    ? "variable"
                         : h.what == AbsoluteHolder::What::field     ? "field"
                         : h.what == AbsoluteHolder::What::parameter ? "parameter"
                                                                     : "return value of";
      std::string kind(kind_name(h.kind));
      ctx.report(ctx.tree.span(h.site), {{"what", what},
                                         {"name", h.name},
                                         {"type", h.type.empty() ? "float" : h.type},
                                         {"holds", descriptions_.value(kind, kind)}});
    }
  }

 private:
  nlohmann::json descriptions_;  // kind -> words for the message
};

}  // namespace

std::unique_ptr<Check> make_float_world_position(const RuleInfo& rule) {
  return std::make_unique<FloatWorldPosition>(rule);
}

}  // namespace lwc::checks
