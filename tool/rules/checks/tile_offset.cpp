// lwc-tile-offset: UE 5.0-5.3 tile/offset types and operations, superseded by DoubleFloat.
#include <fmt/format.h>

#include "rules/checks/util.h"

namespace lwc::checks {
namespace {

class TileOffset : public Check {
  struct Site {  // one tile/offset type or operation in the file
    int id;
    bool type;
    std::string name;
  };

 public:
  explicit TileOffset(const RuleInfo& rule)
      : types_(string_list(rule.data, "types")),
        functions_(string_list(rule.data, "functions")),
        excluded_(string_list(rule.data, "excluded")),
        mapping_(rule.data.value("mapping", nlohmann::json::object())),
        construct_(rule.data.value("constructors", nlohmann::json::object())),
        parts_(string_list(rule.data, "parts")) {}

  void run(const CheckContext& ctx) const override {
    const SyntaxTree& t = ctx.tree;
    std::vector<Site> sites;
    for (int id = 0; id < static_cast<int>(t.nodes.size()); ++id) {
      bool type = t.is(id, "type_identifier");
      bool call = t.is(id, "identifier") && t.is(t.at(id).parent, "call_expression") &&
                  t.child_by_field(t.at(id).parent, "function") == id;
      if (!type && !call) continue;
      std::string name(t.text(id));
      if (matches_any(excluded_, name) || !matches_any(type ? types_ : functions_, name)) continue;
      sites.push_back({id, type, name});
    }
    if (sites.empty()) return;
    // A rename is safe only when the whole file can move to DoubleFloat: every site has a
    // counterpart and no code reads the tile/offset parts, which FDF types do not have.
    std::string blocker = whole_file_blocker(t, sites);
    for (const Site& s : sites) {
      std::string replacement = mapping_.value(s.name, "");
      Vars vars{{"name", s.name},
                {"what", s.type ? "type" : "operation"},
                {"replacement", replacement.empty() ? "its FDF*/DF* counterpart" : "`" + replacement + "`"},
                {"to", replacement},
                {"blocker", blocker}};
      Finding& f = ctx.report(t.span(s.id), vars);
      if (replacement.empty()) continue;
      if (construct_.contains(s.name)) {
        // MakeLWC*(Tile, Offset) is Tile * TileSize + Offset: TwoSum makes that pair exactly.
        int call = t.at(s.id).parent;
        auto args = call_arguments(t, call);
        if (args.size() != 2) continue;
        std::string tile_size = construct_.at(s.name).get<std::string>();
        vars["tile-size"] = tile_size;
        vars["to"] = "DFTwoSum";
        bool simple = t.is(args[0], "identifier") || t.is(args[0], "field_expression") || t.is(args[0], "call_expression");
        std::string tile = simple ? std::string(t.text(args[0])) : "(" + std::string(t.text(args[0])) + ")";
        std::string text = fmt::format("DFTwoSum({} * {}, {})", tile, tile_size, t.text(args[1]));
        ctx.fix(f, "construct", vars, {{t.span(call), text}});
        continue;
      }
      ctx.fix(f, blocker.empty() ? "rename" : "rename-partial", vars, {{t.span(s.id), replacement}});
    }
  }

 private:
  std::string whole_file_blocker(const SyntaxTree& t, const std::vector<Site>& sites) const {
    for (const Site& s : sites) {
      if (!mapping_.contains(s.name)) return fmt::format("`{}` has no DoubleFloat counterpart: port that code by hand, or the file will not compile after the rename", s.name);
      if (construct_.contains(s.name))
        return fmt::format("`{}` (line {}) builds a tile/offset value and its rewrite is unsafe; the renames compile only together with it", s.name,
                           t.source->position(t.at(s.id).begin).line);
    }
    for (int id : nodes_of(t, "field_expression")) {
      int field = t.child_by_field(id, "field");
      if (field >= 0 && matches_any(parts_, t.text(field)))
        return fmt::format("the code reads `.{}` (line {}), a part FDF types do not have: port it by hand, or the file will not compile after the rename", t.text(field),
                           t.source->position(t.at(field).begin).line);
    }
    return "";
  }

  std::vector<std::string> types_, functions_, excluded_;
  nlohmann::json mapping_, construct_;
  std::vector<std::string> parts_;
};

}  // namespace

std::unique_ptr<Check> make_tile_offset(const RuleInfo& rule) { return std::make_unique<TileOffset>(rule); }

}  // namespace lwc::checks
