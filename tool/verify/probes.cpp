#include "verify/probes.h"

#include <fmt/format.h>

#include <cmath>

#include "verify/kernel.h"
#include "verify/worker.h"

namespace lwc {

namespace {

// Three probes per invocation; every operand comes from the input buffer so the compiler cannot
// fold it. TwoSum is written plainly: a driver that reassociates returns 0 for its error term.
constexpr const char* kProbeBody = R"(
	float a = IN(0);
	float b = IN(1);
	float s = a + b;
	float v = s - a;
	float e = (a - (s - v)) + (b - v);
	precise float p = IN(2) * IN(3);
	precise float f = fma(IN(2), IN(3), -p);
	float d = IN(4) * IN(5);
	OUT(0, e);
	OUT(1, f);
	OUT(2, d);)";

}  // namespace

std::string probe_driver(WorkerDevice& device, DriverProbes& out) {
  constexpr int n = DriverProbes::kInputs;
  KernelSpec spec;
  spec.lang = Lang::glsl;
  spec.name = "lwcport-probe.comp";
  spec.body = kProbeBody;
  spec.in_stride = 6;
  spec.out_stride = 3;
  CompileResult compiled = compile_kernel(spec);
  if (!compiled.ok) return "the probe kernel does not compile: " + format_messages(compiled);

  // Exact answers, computed in double (every one is exact there).
  std::vector<float> in;
  std::vector<double> two_sum_error, product_error, denormal;
  for (int i = 0; i < n; ++i) {
    float a = 1.0f, b = std::ldexp(1.0f + i / 64.0f, -30);
    float x = 1.0f + std::ldexp(1.0f, -12), y = 1.0f + std::ldexp(2.0f * i + 1.0f, -12);  // odd: a rounding tie, never exact
    float m = std::ldexp(1.0f, -126), k = std::ldexp(1.0f + i / 64.0f, -(i % 20 + 1));
    in.insert(in.end(), {a, b, x, y, m, k});
    two_sum_error.push_back(double(a) + double(b) - double(a + b));
    product_error.push_back(double(x) * double(y) - double(float(double(x) * double(y))));
    denormal.push_back(double(float(double(m) * double(k))));  // correctly rounded, as the host does
  }
  std::vector<std::vector<uint8_t>> buffers = {to_bytes(in), std::vector<uint8_t>(n * 3 * sizeof(float))};
  if (std::string why = device.run(compiled.spirv, buffers, n / kKernelGroupSize); !why.empty()) return why;
  std::vector<float> got = from_bytes<float>(buffers[1]);
  out = {};
  for (int i = 0; i < n; ++i) {
    if (got[3 * i] == 0.0f && two_sum_error[i] != 0.0) ++out.reassociated;
    if (double(got[3 * i + 1]) == product_error[i]) ++out.fma_fused;
    if (got[3 * i + 2] != 0.0f && double(got[3 * i + 2]) == denormal[i]) ++out.denormals_kept;
  }
  return "";
}

std::vector<std::string> describe_probes(const DriverProbes& p) {
  constexpr int n = DriverProbes::kInputs;
  std::vector<std::string> lines;
  lines.push_back(p.reassociates()
      ? fmt::format("reassociation: applied without `precise` (TwoSum's error term folded to 0 on {} of {} inputs): "
                    "every error-free step must be precise", p.reassociated, n)
      : fmt::format("reassociation: not applied (TwoSum's error term exact on {} of {} inputs without `precise`)", n, n));
  lines.push_back(p.fuses_fma()
      ? fmt::format("fma: fused (fma(a, b, -a*b) exact on {} of {} inputs): products use the 2-flop fma form "
                    "(LWC_DF_FUSED_FMA 1)", n, n)
      : fmt::format("fma: not fused (fma(a, b, -a*b) exact on {} of {} inputs): products use Dekker's split "
                    "(LWC_DF_FUSED_FMA 0); fma-based products are only float32-accurate here", p.fma_fused, n));
  lines.push_back(p.keeps_denormals()
      ? fmt::format("denormals: kept (float32 products below 2^-126 exact on {} of {} inputs)", n, n)
      : fmt::format("denormals: flushed on {} of {} inputs: error terms below 2^-126 are lost", n - p.denormals_kept, n));
  return lines;
}

}  // namespace lwc
