#pragma once
// Compute kernels for verification: code under test plus an entry point that runs `body` once
// per invocation. The body reads its inputs with IN(k) (float k of this invocation's record)
// and writes results with OUT(k, value); records are `in_stride` values in and `out_stride`
// values out, float (or double for float64 reference kernels).
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "lang/syntax.h"
#include "verify/compile.h"

namespace lwc {

struct KernelSpec {
  Lang lang = Lang::glsl;
  std::string name;          // shown in compile messages
  std::string declarations;  // the library and code under test, before the entry point
  std::string body;
  int in_stride = 1;
  int out_stride = 1;
  bool float64 = false;       // double inputs and outputs (and GLSL 4.50)
  std::string glsl_version = "450";  // "310 es" for code written for GLSL ES
};

// Invocations per workgroup: records are padded to a multiple of it.
constexpr uint32_t kKernelGroupSize = 64;

std::string kernel_source(const KernelSpec& spec);
// Compiles the kernel to SPIR-V (GLSL 4.50 or HLSL SM 5), with `defines` prepended as
// `#define NAME VALUE` lines.
CompileResult compile_kernel(const KernelSpec& spec, const std::vector<std::pair<std::string, std::string>>& defines = {});

template <typename T>
std::vector<uint8_t> to_bytes(const std::vector<T>& values) {
  std::vector<uint8_t> out(values.size() * sizeof(T));
  if (!out.empty()) std::memcpy(out.data(), values.data(), out.size());
  return out;
}

template <typename T>
std::vector<T> from_bytes(const std::vector<uint8_t>& data) {
  std::vector<T> out(data.size() / sizeof(T));
  if (!out.empty()) std::memcpy(out.data(), data.data(), out.size() * sizeof(T));
  return out;
}

}  // namespace lwc
