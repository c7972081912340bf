#pragma once
// The device as the verifier uses it: a ComputeDevice living in a child process, fed one kernel
// at a time over a socket. A shader that hangs the driver or crashes it costs that kernel only:
// the child is killed (or found dead), the kernel gets a clear error, and the next kernel starts
// a fresh child. This process never loads the Vulkan driver itself, so forking stays safe.
#include <sys/types.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "verify/vulkan.h"

namespace lwc {

class WorkerDevice {
 public:
  // Starts the child and opens the device in it; null and `error` (as ComputeDevice::open words
  // it, naming the packages to install) when there is none. `timeout_seconds` bounds each kernel.
  static std::unique_ptr<WorkerDevice> start(std::string& error, double timeout_seconds = 60);
  ~WorkerDevice();
  WorkerDevice(const WorkerDevice&) = delete;
  WorkerDevice& operator=(const WorkerDevice&) = delete;

  const std::string& name() const { return name_; }

  // As ComputeDevice::run, in the child. A kernel that outlives the timeout or kills the driver
  // returns why (the buffers may then hold part of an answer). Only the buffers marked in
  // `read_back` come back (all when it is empty): inputs are most of the traffic.
  std::string run(const std::vector<uint32_t>& spirv, std::vector<std::vector<uint8_t>>& buffers, uint32_t groups,
                  int repeats = 1, DispatchTiming* timing = nullptr, uint64_t* kept = nullptr,
                  const std::vector<bool>& read_back = {});

  // As ComputeDevice::time_interleaved, in the child.
  std::string time_interleaved(const std::vector<uint64_t>& kept, const TimingPlan& plan, InterleavedTiming& out);

 private:
  explicit WorkerDevice(double timeout_seconds) : timeout_seconds_(timeout_seconds) {}
  std::string spawn();  // "" or why the child could not open the device
  void stop();          // kills the child, if any, and reaps it
  std::string child_ended();  // how the child died (signal or exit status), after it is reaped
  std::string lost_child(int received);  // "" or why the child stopped answering (then it is stopped)

  double timeout_seconds_;
  std::string name_;
  pid_t child_ = -1;
  uint64_t generation_ = 0;  // driver processes started: kept kernels belong to one
  int socket_ = -1;
};

}  // namespace lwc
