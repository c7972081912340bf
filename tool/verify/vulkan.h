#pragma once
// Runs compute shaders on a Vulkan device through the loader: lavapipe (Mesa's CPU driver) in CI
// and on machines without a GPU. One device, one queue; each run creates its pipeline, binds the
// given storage buffers at set 0, bindings 0..n-1, dispatches and reads every buffer back.
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace lwc {

struct DispatchTiming {
  double pipeline_seconds = 0;               // shader module + pipeline creation
  std::vector<double> dispatch_seconds;      // one per repeat: submit to fence
};

// How kernels are timed against each other (ComputeDevice::time_interleaved).
struct TimingPlan {
  int min_rounds = 7;
  int max_rounds = 31;
  double max_spread = 0.10;     // stop once every kernel's median is known to within this (median_spread)
  double max_seconds = 1.5;     // or after this long
  double sample_seconds = 0.001;  // dispatches per sample: enough to take about this long
};
struct InterleavedTiming {
  std::vector<std::vector<double>> seconds;  // per kernel, one per round: CPU seconds per dispatch (every driver thread)
  std::vector<int> dispatches_per_sample;
  int rounds = 0;
};

// The middle value; and the width of its 95% confidence interval over it (1 with fewer than 4 values).
double median_of(std::vector<double> v);
double median_spread(std::vector<double> v);

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
  // or the reason it could not run. With `kept`, the kernel, its pipeline and buffers stay for
  // time_interleaved, which takes this id.
  std::string run(const std::vector<uint32_t>& spirv, std::vector<std::vector<uint8_t>>& buffers, uint32_t groups,
                  int repeats = 1, DispatchTiming* timing = nullptr, uint64_t* kept = nullptr);

  // Times kept kernels in rounds, each once per round in a rotating order, until each one's median
  // is known to within the plan's spread (or its limits are reached), then lets them go.
  std::string time_interleaved(const std::vector<uint64_t>& kept, const TimingPlan& plan, InterleavedTiming& out);

 private:
  struct State;
  struct Job;
  std::string prepare(const std::vector<uint32_t>& spirv, const std::vector<std::vector<uint8_t>>& buffers, uint32_t groups, Job& job);
  std::string record(Job& job, int dispatches);
  std::string submit(Job& job, double& seconds, double* cpu_seconds = nullptr);
  explicit ComputeDevice(std::unique_ptr<State> state);
  std::unique_ptr<State> s_;
  std::map<uint64_t, std::unique_ptr<Job>> kept_;
  uint64_t next_kept_ = 1;
};

}  // namespace lwc
