#include "verify/kernel.h"

#include <fmt/format.h>

namespace lwc {

std::string kernel_source(const KernelSpec& spec) {
  std::string io = fmt::format("#define IN(k) lwc_in[lwc_i * {}u + uint(k)]\n#define OUT(k, v) lwc_out[lwc_i * {}u + uint(k)] = (v)\n",
                               spec.in_stride, spec.out_stride);
  if (spec.lang == Lang::glsl) {
    return fmt::format(
        "{}\nlayout(local_size_x = {}) in;\n"
        "layout(std430, binding = 0) readonly buffer LwcIn {{ {} lwc_in[]; }};\n"
        "layout(std430, binding = 1) writeonly buffer LwcOut {{ {} lwc_out[]; }};\n{}"
        "void main()\n{{\n\tuint lwc_i = gl_GlobalInvocationID.x;\n{}\n}}\n",
        spec.declarations, kKernelGroupSize, spec.float64 ? "double" : "float", spec.float64 ? "double" : "float", io, spec.body);
  }
  return fmt::format(
      "{}\n[[vk::binding(0)]] StructuredBuffer<{}> lwc_in;\n"
      "[[vk::binding(1)]] RWStructuredBuffer<{}> lwc_out;\n{}"
      "[numthreads({}, 1, 1)]\nvoid main(uint3 lwc_id : SV_DispatchThreadID)\n{{\n\tuint lwc_i = lwc_id.x;\n{}\n}}\n",
      spec.declarations, spec.float64 ? "double" : "float", spec.float64 ? "double" : "float", io, kKernelGroupSize, spec.body);
}

CompileResult compile_kernel(const KernelSpec& spec, const std::vector<std::pair<std::string, std::string>>& defines) {
  CompileInput in;
  in.preamble = define_lines(defines);
  in.lang = spec.lang;
  in.stage = Stage::compute;
  in.name = spec.name;
  std::string version = spec.float64 ? "450" : spec.glsl_version;
  in.text = (spec.lang == Lang::glsl ? "#version " + version + "\n" : "") + kernel_source(spec);
  in.entry = "main";
  in.spirv = true;
  in.debug_lines = spec.float64;  // where the reference narrows to float32, by line
  return compile_shader(in);
}

}  // namespace lwc
