#pragma once
// What the driver does to float arithmetic, measured at the start of every verification run
// (LWC-BRIEF §5): the answers decide how the library is compiled and what the results mean.
#include <string>
#include <vector>

namespace lwc {

class WorkerDevice;

struct DriverProbes {
  static constexpr int kInputs = 64;
  int reassociated = 0;     // TwoSum without `precise`: inputs whose error term came back 0
  int fma_fused = 0;        // fma(a, b, -a*b): inputs that returned the product's exact error
  int denormals_kept = 0;   // float32 products in the denormal range that came back exact

  bool reassociates() const { return reassociated > 0; }
  bool fuses_fma() const { return fma_fused == kInputs; }
  bool keeps_denormals() const { return denormals_kept == kInputs; }
};

// Runs the probe kernel on `device`; returns "" or why it could not run.
std::string probe_driver(WorkerDevice& device, DriverProbes& out);

// One line per probe: the answer, the measurement behind it, and what lwcport does about it.
std::vector<std::string> describe_probes(const DriverProbes& probes);

}  // namespace lwc
