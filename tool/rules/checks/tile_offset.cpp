// lwc-tile-offset: UE 5.0-5.3 tile/offset types and operations, superseded by DoubleFloat.
#include "rules/checks/util.h"

namespace lwc::checks {
namespace {

class TileOffset : public Check {
 public:
  explicit TileOffset(const RuleInfo& rule)
      : types_(string_list(rule.data, "types")),
        functions_(string_list(rule.data, "functions")),
        excluded_(string_list(rule.data, "excluded")),
        mapping_(rule.data.value("mapping", nlohmann::json::object())) {}

  void run(const CheckContext& ctx) const override {
    const SyntaxTree& t = ctx.tree;
    for (int id = 0; id < static_cast<int>(t.nodes.size()); ++id) {
      bool type = t.is(id, "type_identifier");
      bool call = t.is(id, "identifier") && t.is(t.at(id).parent, "call_expression") &&
                  t.child_by_field(t.at(id).parent, "function") == id;
      if (!type && !call) continue;
      std::string name(t.text(id));
      if (matches_any(excluded_, name) || !matches_any(type ? types_ : functions_, name)) continue;
      std::string replacement = mapping_.value(name, "");
      ctx.report(t.span(id), {{"name", name},
                              {"what", type ? "type" : "operation"},
                              {"replacement", replacement.empty() ? "its FDF*/DF* counterpart" : "`" + replacement + "`"}});
    }
  }

 private:
  std::vector<std::string> types_, functions_, excluded_;
  nlohmann::json mapping_;
};

}  // namespace

std::unique_ptr<Check> make_tile_offset(const RuleInfo& rule) { return std::make_unique<TileOffset>(rule); }

}  // namespace lwc::checks
