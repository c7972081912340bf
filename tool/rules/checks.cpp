#include "rules/rule.h"

namespace lwc {
namespace checks {
std::unique_ptr<Check> make_demote_fusion(const RuleInfo&);
std::unique_ptr<Check> make_fast_twosum_order(const RuleInfo&);
std::unique_ptr<Check> make_float_world_position(const RuleInfo&);
std::unique_ptr<Check> make_hack_marker(const RuleInfo&);
std::unique_ptr<Check> make_large_world_member(const RuleInfo&);
std::unique_ptr<Check> make_missing_precise(const RuleInfo&);
std::unique_ptr<Check> make_primary_view(const RuleInfo&);
std::unique_ptr<Check> make_removed_engine_api(const RuleInfo&);
std::unique_ptr<Check> make_tile_offset(const RuleInfo&);
std::unique_ptr<Check> make_translated_member(const RuleInfo&);
std::unique_ptr<Check> make_translated_parameter(const RuleInfo&);
std::unique_ptr<Check> make_translated_world(const RuleInfo&);
std::unique_ptr<Check> make_uniform_world_float(const RuleInfo&);
}  // namespace checks

const std::map<std::string_view, CheckFactory>& check_factories() {
  static const std::map<std::string_view, CheckFactory> factories = {
      {"lwc-demote-fusion", checks::make_demote_fusion},
      {"lwc-fast-twosum-order", checks::make_fast_twosum_order},
      {"lwc-float-world-position", checks::make_float_world_position},
      {"lwc-hack-marker", checks::make_hack_marker},
      {"lwc-large-world-member", checks::make_large_world_member},
      {"lwc-missing-precise", checks::make_missing_precise},
      {"lwc-primary-view", checks::make_primary_view},
      {"lwc-removed-engine-api", checks::make_removed_engine_api},
      {"lwc-tile-offset", checks::make_tile_offset},
      {"lwc-translated-member", checks::make_translated_member},
      {"lwc-translated-parameter", checks::make_translated_parameter},
      {"lwc-translated-world", checks::make_translated_world},
      {"lwc-uniform-world-float", checks::make_uniform_world_float},
  };
  return factories;
}

}  // namespace lwc
