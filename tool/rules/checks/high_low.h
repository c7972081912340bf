#pragma once
// The translated-world rewrite for code without Unreal's library: the seed renderer's design
// (LWC-BRIEF §7). The world matrix is split into a rotation-scale matrix and a translation High/Low
// pair, the camera position is a High/Low pair too, and the object's offset from the camera is
// (objHigh - camHigh) + (objLow - camLow) under `precise` (the library's DFFastLocalSubtractDemote).
#include <string>
#include <vector>

#include "rules/checks/util.h"

namespace lwc::checks {

// Which absolute uniforms are the camera: words their names contain (lower case).
struct CameraNames {
  std::vector<std::string> words;
  bool is_camera(const Variable& v) const;
};

// A local initialised by a world transform: it becomes camera-relative from High/Low uniforms.
RewritePlan plan_high_low(const CheckContext& ctx, int var, const CameraNames& camera);
// A stage input holding a world position (`in vec3 vWorldPosition`): it becomes the translated
// position the previous stage now writes.
RewritePlan plan_translated_input(const CheckContext& ctx, int var, const CameraNames& camera);

// Edits that make a file include lwcport's library (lwc_doublefloat.hlsl / .glsl), none when it
// already does: after the leading comments and directives (GLSL: and the include extension).
std::vector<Edit> library_include_edits(const SyntaxTree& tree);

}  // namespace lwc::checks
