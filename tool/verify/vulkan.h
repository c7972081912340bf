#pragma once
// Runs compute shaders on a Vulkan device through the loader: lavapipe (Mesa's CPU driver) in CI
// and on machines without a GPU. One device, one queue; each run creates its pipeline, binds the
// given storage buffers at set 0, bindings 0..n-1, dispatches and reads every buffer back.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace lwc {

struct DispatchTiming {
  double pipeline_seconds = 0;               // shader module + pipeline creation
  std::vector<double> dispatch_seconds;      // one per repeat: submit to fence
};

class ComputeDevice {
 public:
  // The CPU device (lavapipe) when there is one, else the first device; VK_ICD_FILENAMES picks
  // the driver as usual. Returns null and sets `error` (naming the packages to install) when
  // Vulkan or a device is missing.
  static std::unique_ptr<ComputeDevice> open(std::string& error);
  ~ComputeDevice();
  ComputeDevice(const ComputeDevice&) = delete;
  ComputeDevice& operator=(const ComputeDevice&) = delete;

  const std::string& name() const;
  bool supports_float64() const;

  // Runs `spirv` (entry point "main") with `buffers` as storage buffers, `groups` workgroups
  // along x, `repeats` times (at least once); the buffers hold the last run's output. Returns ""
  // or the reason it could not run.
  std::string run(const std::vector<uint32_t>& spirv, std::vector<std::vector<uint8_t>>& buffers, uint32_t groups,
                  int repeats = 1, DispatchTiming* timing = nullptr);

 private:
  struct State;
  explicit ComputeDevice(std::unique_ptr<State> state);
  std::unique_ptr<State> s_;
};

}  // namespace lwc
