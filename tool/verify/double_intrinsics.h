#pragma once
// Double versions of the HLSL intrinsics glslang's HLSL front end narrows: given double arguments
// it converts them to float, calls the float form and converts back (dot, length, normalize,
// sqrt, frac, min, max, lerp, floor...), so a reference promoted to double would be float32-accurate
// through every such call. The float64 reference calls `lwc_d_NAME` instead, defined here.
#include <set>
#include <string>
#include <string_view>

namespace lwc {

// The intrinsic names the reference calls through `lwc_d_`.
const std::set<std::string, std::less<>>& narrowed_hlsl_intrinsics();

// Their definitions, for double, double2, double3 and double4 (integer arguments convert: an
// integer overload would make `min(x, 0)` ambiguous), plus `mul` and `transpose` for double
// matrices (glslang has them for float matrices only).
std::string hlsl_double_intrinsics();

}  // namespace lwc
