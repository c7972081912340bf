#include "host/check.h"

namespace lwc::host {

std::unique_ptr<Check> make_broken_split(const RuleInfo&, const Tables&, Reporter&);
std::unique_ptr<Check> make_camera_dependent_scene_data(const RuleInfo&, const Tables&, Reporter&);
std::unique_ptr<Check> make_fast_math(const RuleInfo&, const Tables&, Reporter&);
std::unique_ptr<Check> make_float_world_storage(const RuleInfo&, const Tables&, Reporter&);
std::unique_ptr<Check> make_narrowed_world_matrix(const RuleInfo&, const Tables&, Reporter&);
std::unique_ptr<Check> make_narrowed_world_upload(const RuleInfo&, const Tables&, Reporter&);

const std::map<std::string_view, CheckFactory>& check_factories() {
  static const std::map<std::string_view, CheckFactory> factories = {
      {"lwc-host-broken-split", make_broken_split},
      {"lwc-host-camera-dependent-scene-data", make_camera_dependent_scene_data},
      {"lwc-host-fast-math", make_fast_math},
      {"lwc-host-float-world-storage", make_float_world_storage},
      {"lwc-host-narrowed-world-matrix", make_narrowed_world_matrix},
      {"lwc-host-narrowed-world-upload", make_narrowed_world_upload},
  };
  return factories;
}

}  // namespace lwc::host
