#include "host/check.h"

namespace lwc::host {

std::unique_ptr<Check> make_narrowed_world_matrix(const RuleInfo&, const Tables&, Reporter&);
std::unique_ptr<Check> make_narrowed_world_upload(const RuleInfo&, const Tables&, Reporter&);

const std::map<std::string_view, CheckFactory>& check_factories() {
  static const std::map<std::string_view, CheckFactory> factories = {
      {"lwc-host-narrowed-world-matrix", make_narrowed_world_matrix},
      {"lwc-host-narrowed-world-upload", make_narrowed_world_upload},
  };
  return factories;
}

}  // namespace lwc::host
