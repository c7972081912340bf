// lwc-hack-marker: the searchable markers of shortcuts taken while porting to LWC.
#include "rules/checks/util.h"

namespace lwc::checks {
namespace {

class HackMarker : public Check {
 public:
  explicit HackMarker(const RuleInfo& rule) : markers_(rule.data.at("markers")) {}

  void run(const CheckContext& ctx) const override {
    const SyntaxTree& t = ctx.tree;
    for (int id = 0; id < static_cast<int>(t.nodes.size()); ++id) {
      if (!t.is(id, "identifier")) continue;
      std::string name(t.text(id));
      if (!markers_.contains(name) || is_definition_name(t, id)) continue;
      ctx.report(t.span(id), {{"marker", name}, {"loss", markers_.at(name).get<std::string>()}});
    }
  }

 private:
  nlohmann::json markers_;  // marker -> what it loses
};

}  // namespace

std::unique_ptr<Check> make_hack_marker(const RuleInfo& rule) { return std::make_unique<HackMarker>(rule); }

}  // namespace lwc::checks
