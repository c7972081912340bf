#pragma once
// Turns one function of a shader into something a compute kernel can call once per invocation:
// the file (preprocessed: includes inlined, macros expanded) cut down to the function and what it
// calls, its environment (uniforms, cbuffer members, stage inputs and outputs, the engine's View
// structs) made private globals the kernel fills from the input buffer, and its results (return
// value, out parameters, stage outputs) written to the output buffer.
#include <string>
#include <vector>

#include "lang/syntax.h"

namespace lwc {

// How a value sits in shader variables: plain floats, a DoubleFloat pair (High + Low), a UE 5.0
// tile/offset pair (Tile * 2^21 + Offset), or a DoubleFloat / tile matrix (float matrix plus a
// large translation).
enum class Encoding { plain, df, lwc, df_matrix, df_inverse_matrix, lwc_matrix, lwc_inverse_matrix };

// One value the kernel sets or reads: `View.WorldCameraOrigin`, `p0` (the first parameter),
// `lwc_result.PosW`.
struct Leaf {
  std::string path;      // as written in the kernel
  std::string name;      // the last name in the path, for its role (`WorldCameraOrigin`)
  std::string type;      // the declared type (`float3`, `FDFVector3`, `mat4`)
  std::string semantic;  // HLSL semantic, if any (`SV_POSITION`)
  std::string owner;     // the struct it is a member of, if any (`FDeferredLightData`), for its role
  Encoding encoding = Encoding::plain;
  int components = 1;    // values it stands for: 3 for float3 and FDFVector3, 16 for a 4x4 matrix
  int width = 1;         // floats it takes in a record
  int offset = 0;        // first float in the record
  bool integer = false;  // int / uint / bool
};

struct HarnessKernel {
  std::string declarations;     // the cut-down file, ready to precede the entry point
  std::string body;             // entry point body: fill inputs, call, write outputs
  std::vector<Leaf> inputs, outputs;
  int in_stride = 0, out_stride = 0;
  std::string problem;          // non-empty: the function cannot be called this way, and why
  bool real_lines = false;      // `#line`s give the declarations the lines of the file and its includes
};

// `text` is preprocessed source; `function` the name to call (the first definition of that name;
// GLSL `main` is renamed). `float64` promotes every float type to double (the reference).
HarnessKernel build_harness_kernel(Lang lang, const std::string& text, const std::string& function, bool float64);

// The text with each `#line` directive blanked (its line kept).
std::string without_line_directives(std::string text);

// The names of the functions whose definitions contain each offset ("" outside any function).
std::vector<std::string> enclosing_functions(Lang lang, const std::string& text, const std::vector<uint32_t>& offsets);

// Every float type written as its double twin (float3 -> double3, vec3 -> dvec3, mat4 -> dmat4);
// transcendentals call float32 wrappers (`lwc_f32_sin`), and HLSL intrinsics that glslang would
// narrow to float call double ones (`lwc_d_length`, verify/double_intrinsics.h).
std::string promote_to_double(Lang lang, const std::string& text);

}  // namespace lwc
