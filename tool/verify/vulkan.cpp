#include "verify/vulkan.h"

#include <vulkan/vulkan.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <cmath>
#include <cstring>
#include <functional>

#include <fmt/format.h>

namespace lwc {

namespace {

const char* kInstallHint = "install the Vulkan loader and Mesa's CPU driver (Debian: libvulkan1 mesa-vulkan-drivers)";

// A Vulkan create-info struct, zeroed, with its type set.
template <typename T>
T vk_struct(VkStructureType type) {
  T value{};
  value.sType = type;
  return value;
}

// CPU time of this process, every thread: lavapipe runs a dispatch on its own threads while the
// submitting one waits, so this is the dispatch's work, not time spent waiting for a core.
double process_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec) * 1e-9;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Destroys the Vulkan objects of one run in reverse order of creation, whatever happens.
class Cleanup {
 public:
  ~Cleanup() {
    for (auto it = steps_.rbegin(); it != steps_.rend(); ++it) (*it)();
  }
  void add(std::function<void()> step) { steps_.push_back(std::move(step)); }

 private:
  std::vector<std::function<void()>> steps_;
};

}  // namespace

struct ComputeDevice::State {
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physical = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  uint32_t queue_family = 0;
  std::string name;
  bool float64 = false;
  VkPhysicalDeviceMemoryProperties memory{};
};

ComputeDevice::ComputeDevice(std::unique_ptr<State> state) : s_(std::move(state)) {}

ComputeDevice::~ComputeDevice() {
  kept_.clear();  // before the device they belong to
  if (s_->device) vkDestroyDevice(s_->device, nullptr);
  if (s_->instance) vkDestroyInstance(s_->instance, nullptr);
}

const std::string& ComputeDevice::name() const { return s_->name; }
bool ComputeDevice::supports_float64() const { return s_->float64; }

std::unique_ptr<ComputeDevice> ComputeDevice::open(std::string& error) {
  auto s = std::make_unique<State>();
  auto app = vk_struct<VkApplicationInfo>(VK_STRUCTURE_TYPE_APPLICATION_INFO);
  app.pApplicationName = "lwcport";
  app.apiVersion = VK_API_VERSION_1_1;
  auto instance_info = vk_struct<VkInstanceCreateInfo>(VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO);
  instance_info.pApplicationInfo = &app;
  if (VkResult r = vkCreateInstance(&instance_info, nullptr, &s->instance); r != VK_SUCCESS) {
    error = fmt::format("no Vulkan instance (VkResult {}): {}", static_cast<int>(r), kInstallHint);
    return nullptr;
  }
  std::unique_ptr<ComputeDevice> out(new ComputeDevice(std::move(s)));  // from here the destructor cleans up
  State& st = *out->s_;
  uint32_t count = 0;
  vkEnumeratePhysicalDevices(st.instance, &count, nullptr);
  std::vector<VkPhysicalDevice> devices(count);
  vkEnumeratePhysicalDevices(st.instance, &count, devices.data());
  for (VkPhysicalDevice d : devices) {
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(d, &p);
    if (!st.physical || p.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU) st.physical = d, st.name = p.deviceName;
    if (p.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU) break;
  }
  if (!st.physical) {
    error = fmt::format("no Vulkan device: {}", kInstallHint);
    return nullptr;
  }
  uint32_t families = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(st.physical, &families, nullptr);
  std::vector<VkQueueFamilyProperties> family_props(families);
  vkGetPhysicalDeviceQueueFamilyProperties(st.physical, &families, family_props.data());
  bool found = false;
  for (uint32_t i = 0; i < families && !found; ++i)
    if (family_props[i].queueFlags & VK_QUEUE_COMPUTE_BIT) st.queue_family = i, found = true;
  if (!found) {
    error = fmt::format("Vulkan device {} has no compute queue", st.name);
    return nullptr;
  }
  VkPhysicalDeviceFeatures supported;
  vkGetPhysicalDeviceFeatures(st.physical, &supported);
  st.float64 = supported.shaderFloat64;
  VkPhysicalDeviceFeatures enabled{};
  enabled.shaderFloat64 = supported.shaderFloat64;
  float priority = 1.0f;
  auto queue_info = vk_struct<VkDeviceQueueCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO);
  queue_info.queueFamilyIndex = st.queue_family;
  queue_info.queueCount = 1;
  queue_info.pQueuePriorities = &priority;
  auto device_info = vk_struct<VkDeviceCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO);
  device_info.queueCreateInfoCount = 1;
  device_info.pQueueCreateInfos = &queue_info;
  device_info.pEnabledFeatures = &enabled;
  if (VkResult r = vkCreateDevice(st.physical, &device_info, nullptr, &st.device); r != VK_SUCCESS) {
    error = fmt::format("cannot open Vulkan device {} (VkResult {})", st.name, static_cast<int>(r));
    return nullptr;
  }
  vkGetDeviceQueue(st.device, st.queue_family, 0, &st.queue);
  vkGetPhysicalDeviceMemoryProperties(st.physical, &st.memory);
  return out;
}

// One kernel made ready to run: its buffers, pipeline and descriptor set, and a command buffer
// with its dispatches. The Vulkan objects go with it.
struct ComputeDevice::Job {
  Cleanup cleanup;
  std::vector<VkDeviceMemory> memories;
  std::vector<size_t> sizes;
  VkPipeline pipeline = VK_NULL_HANDLE;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  VkDescriptorSet set = VK_NULL_HANDLE;
  VkCommandPool command_pool = VK_NULL_HANDLE;
  VkCommandBuffer commands = VK_NULL_HANDLE;
  VkFence fence = VK_NULL_HANDLE;
  uint32_t groups = 1;
};

namespace {
std::string vk_failed(const char* what, VkResult r) { return fmt::format("{} failed (VkResult {})", what, static_cast<int>(r)); }
}  // namespace

std::string ComputeDevice::prepare(const std::vector<uint32_t>& spirv, const std::vector<std::vector<uint8_t>>& buffers, uint32_t groups,
                                   Job& job) {
  VkDevice dev = s_->device;
  Cleanup& cleanup = job.cleanup;
  job.groups = groups;

  // Host-visible, coherent storage buffers: lavapipe's memory is the host's anyway.
  std::vector<VkBuffer> vk_buffers;
  for (const auto& data : buffers) {
    auto info = vk_struct<VkBufferCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);
    info.size = std::max<size_t>(data.size(), 4);
    info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    VkBuffer buffer;
    if (VkResult r = vkCreateBuffer(dev, &info, nullptr, &buffer); r != VK_SUCCESS) return vk_failed("vkCreateBuffer", r);
    cleanup.add([=] { vkDestroyBuffer(dev, buffer, nullptr); });
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(dev, buffer, &req);
    uint32_t type = UINT32_MAX;
    VkMemoryPropertyFlags want = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    for (uint32_t i = 0; i < s_->memory.memoryTypeCount && type == UINT32_MAX; ++i)
      if ((req.memoryTypeBits & (1u << i)) && (s_->memory.memoryTypes[i].propertyFlags & want) == want) type = i;
    if (type == UINT32_MAX) return "no host-visible memory for storage buffers";
    auto alloc = vk_struct<VkMemoryAllocateInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO);
    alloc.allocationSize = req.size;
    alloc.memoryTypeIndex = type;
    VkDeviceMemory memory;
    if (VkResult r = vkAllocateMemory(dev, &alloc, nullptr, &memory); r != VK_SUCCESS) return vk_failed("vkAllocateMemory", r);
    cleanup.add([=] { vkFreeMemory(dev, memory, nullptr); });
    vkBindBufferMemory(dev, buffer, memory, 0);
    void* mapped;
    vkMapMemory(dev, memory, 0, VK_WHOLE_SIZE, 0, &mapped);
    std::memcpy(mapped, data.data(), data.size());
    vkUnmapMemory(dev, memory);
    vk_buffers.push_back(buffer);
    job.memories.push_back(memory);
    job.sizes.push_back(data.size());
  }

  std::vector<VkDescriptorSetLayoutBinding> bindings;
  for (uint32_t i = 0; i < buffers.size(); ++i)
    bindings.push_back({i, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr});
  auto set_info = vk_struct<VkDescriptorSetLayoutCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO);
  set_info.bindingCount = static_cast<uint32_t>(bindings.size());
  set_info.pBindings = bindings.data();
  VkDescriptorSetLayout set_layout;
  if (VkResult r = vkCreateDescriptorSetLayout(dev, &set_info, nullptr, &set_layout); r != VK_SUCCESS)
    return vk_failed("vkCreateDescriptorSetLayout", r);
  cleanup.add([=] { vkDestroyDescriptorSetLayout(dev, set_layout, nullptr); });
  auto layout_info = vk_struct<VkPipelineLayoutCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO);
  layout_info.setLayoutCount = 1;
  layout_info.pSetLayouts = &set_layout;
  if (VkResult r = vkCreatePipelineLayout(dev, &layout_info, nullptr, &job.layout); r != VK_SUCCESS) return vk_failed("vkCreatePipelineLayout", r);
  cleanup.add([dev, layout = job.layout] { vkDestroyPipelineLayout(dev, layout, nullptr); });
  auto module_info = vk_struct<VkShaderModuleCreateInfo>(VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO);
  module_info.codeSize = spirv.size() * sizeof(uint32_t);
  module_info.pCode = spirv.data();
  VkShaderModule module;
  if (VkResult r = vkCreateShaderModule(dev, &module_info, nullptr, &module); r != VK_SUCCESS) return vk_failed("vkCreateShaderModule", r);
  cleanup.add([=] { vkDestroyShaderModule(dev, module, nullptr); });
  auto pipeline_info = vk_struct<VkComputePipelineCreateInfo>(VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO);
  pipeline_info.stage = vk_struct<VkPipelineShaderStageCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO);
  pipeline_info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  pipeline_info.stage.module = module;
  pipeline_info.stage.pName = "main";
  pipeline_info.layout = job.layout;
  if (VkResult r = vkCreateComputePipelines(dev, VK_NULL_HANDLE, 1, &pipeline_info, nullptr, &job.pipeline); r != VK_SUCCESS)
    return vk_failed("vkCreateComputePipelines", r);
  cleanup.add([dev, pipeline = job.pipeline] { vkDestroyPipeline(dev, pipeline, nullptr); });

  VkDescriptorPoolSize pool_size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, static_cast<uint32_t>(std::max<size_t>(buffers.size(), 1))};
  auto pool_info = vk_struct<VkDescriptorPoolCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO);
  pool_info.maxSets = 1;
  pool_info.poolSizeCount = 1;
  pool_info.pPoolSizes = &pool_size;
  VkDescriptorPool pool;
  if (VkResult r = vkCreateDescriptorPool(dev, &pool_info, nullptr, &pool); r != VK_SUCCESS) return vk_failed("vkCreateDescriptorPool", r);
  cleanup.add([=] { vkDestroyDescriptorPool(dev, pool, nullptr); });
  auto set_alloc = vk_struct<VkDescriptorSetAllocateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO);
  set_alloc.descriptorPool = pool;
  set_alloc.descriptorSetCount = 1;
  set_alloc.pSetLayouts = &set_layout;
  if (VkResult r = vkAllocateDescriptorSets(dev, &set_alloc, &job.set); r != VK_SUCCESS) return vk_failed("vkAllocateDescriptorSets", r);
  std::vector<VkDescriptorBufferInfo> infos;
  for (VkBuffer b : vk_buffers) infos.push_back({b, 0, VK_WHOLE_SIZE});
  std::vector<VkWriteDescriptorSet> writes;
  for (uint32_t i = 0; i < infos.size(); ++i) {
    auto w = vk_struct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
    w.dstSet = job.set;
    w.dstBinding = i;
    w.descriptorCount = 1;
    w.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    w.pBufferInfo = &infos[i];
    writes.push_back(w);
  }
  vkUpdateDescriptorSets(dev, static_cast<uint32_t>(writes.size()), writes.data(), 0, nullptr);

  auto command_pool_info = vk_struct<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
  command_pool_info.queueFamilyIndex = s_->queue_family;
  if (VkResult r = vkCreateCommandPool(dev, &command_pool_info, nullptr, &job.command_pool); r != VK_SUCCESS)
    return vk_failed("vkCreateCommandPool", r);
  cleanup.add([dev, command_pool = job.command_pool] { vkDestroyCommandPool(dev, command_pool, nullptr); });
  auto fence_info = vk_struct<VkFenceCreateInfo>(VK_STRUCTURE_TYPE_FENCE_CREATE_INFO);
  if (VkResult r = vkCreateFence(dev, &fence_info, nullptr, &job.fence); r != VK_SUCCESS) return vk_failed("vkCreateFence", r);
  cleanup.add([dev, fence = job.fence] { vkDestroyFence(dev, fence, nullptr); });
  return record(job, 1);
}

// A new command buffer with `dispatches` dispatches of the kernel, each after the last one's writes.
std::string ComputeDevice::record(Job& job, int dispatches) {
  auto command_alloc = vk_struct<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
  command_alloc.commandPool = job.command_pool;
  command_alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  command_alloc.commandBufferCount = 1;
  if (VkResult r = vkAllocateCommandBuffers(s_->device, &command_alloc, &job.commands); r != VK_SUCCESS)
    return vk_failed("vkAllocateCommandBuffers", r);
  auto begin = vk_struct<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
  vkBeginCommandBuffer(job.commands, &begin);
  vkCmdBindPipeline(job.commands, VK_PIPELINE_BIND_POINT_COMPUTE, job.pipeline);
  vkCmdBindDescriptorSets(job.commands, VK_PIPELINE_BIND_POINT_COMPUTE, job.layout, 0, 1, &job.set, 0, nullptr);
  for (int i = 0; i < dispatches; ++i) {
    if (i) {
      auto barrier = vk_struct<VkMemoryBarrier>(VK_STRUCTURE_TYPE_MEMORY_BARRIER);
      barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
      barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
      vkCmdPipelineBarrier(job.commands, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &barrier, 0,
                           nullptr, 0, nullptr);
    }
    vkCmdDispatch(job.commands, job.groups, 1, 1);
  }
  vkEndCommandBuffer(job.commands);
  return "";
}

// Submits the job's command buffer and waits; `seconds` gets submit to fence, `cpu_seconds` the CPU
// time the process spent meanwhile.
std::string ComputeDevice::submit(Job& job, double& seconds, double* cpu_seconds) {
  // A shader that never finishes must not hang the tool: each submission gets a deadline.
  constexpr uint64_t kTimeoutNs = 60ull * 1000 * 1000 * 1000;
  auto submit = vk_struct<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &job.commands;
  auto start = std::chrono::steady_clock::now();
  double cpu_start = cpu_seconds ? process_cpu_seconds() : 0;
  if (VkResult r = vkQueueSubmit(s_->queue, 1, &submit, job.fence); r != VK_SUCCESS) return vk_failed("vkQueueSubmit", r);
  VkResult waited = vkWaitForFences(s_->device, 1, &job.fence, VK_TRUE, kTimeoutNs);
  if (waited == VK_TIMEOUT) return "the shader did not finish within 60 s (timeout)";
  if (waited != VK_SUCCESS) return vk_failed("vkWaitForFences (device lost?)", waited);
  seconds = seconds_since(start);
  if (cpu_seconds) *cpu_seconds = process_cpu_seconds() - cpu_start;
  vkResetFences(s_->device, 1, &job.fence);
  return "";
}

std::string ComputeDevice::run(const std::vector<uint32_t>& spirv, std::vector<std::vector<uint8_t>>& buffers, uint32_t groups,
                               int repeats, DispatchTiming* timing, uint64_t* kept) {
  auto owned = std::make_unique<Job>();
  Job& job = *owned;
  auto pipeline_start = std::chrono::steady_clock::now();
  if (std::string why = prepare(spirv, buffers, groups, job); !why.empty()) return why;
  if (timing) timing->pipeline_seconds = seconds_since(pipeline_start);
  for (int i = 0; i < std::max(repeats, 1); ++i) {
    double seconds = 0;
    if (std::string why = submit(job, seconds); !why.empty()) return why;
    if (timing) timing->dispatch_seconds.push_back(seconds);
  }
  for (size_t i = 0; i < buffers.size(); ++i) {
    void* mapped;
    vkMapMemory(s_->device, job.memories[i], 0, VK_WHOLE_SIZE, 0, &mapped);
    std::memcpy(buffers[i].data(), mapped, buffers[i].size());
    vkUnmapMemory(s_->device, job.memories[i]);
  }
  if (kept) {
    *kept = next_kept_++;
    kept_[*kept] = std::move(owned);
  }
  return "";
}

std::string ComputeDevice::time_interleaved(const std::vector<uint64_t>& kept, const TimingPlan& plan, InterleavedTiming& out) {
  std::vector<std::unique_ptr<Job>> jobs;  // released on return, whatever happens
  for (uint64_t id : kept)
    if (auto it = kept_.find(id); it != kept_.end()) {
      jobs.push_back(std::move(it->second));
      kept_.erase(it);
    }
  if (jobs.size() != kept.size()) return "a kernel to time was not kept";
  out = {};
  out.seconds.assign(jobs.size(), {});
  out.dispatches_per_sample.assign(jobs.size(), 1);
  auto start = std::chrono::steady_clock::now();
  for (size_t k = 0; k < jobs.size(); ++k) {
    // Each has run (lavapipe compiled it then); one more dispatch says how long one takes, so a
    // sample holds enough dispatches to be well above the clock's jitter.
    double seconds = 0;
    if (std::string why = submit(*jobs[k], seconds); !why.empty()) return why;
    int batch = static_cast<int>(std::clamp(std::ceil(plan.sample_seconds / std::max(seconds, 1e-6)), 1.0, 64.0));
    out.dispatches_per_sample[k] = batch;
    if (batch > 1)
      if (std::string why = record(*jobs[k], batch); !why.empty()) return why;
  }
  // Rounds: every kernel once per round, starting one further along each time, so a change in the
  // machine's load falls on all of them alike.
  for (int round = 0;; ++round) {
    for (size_t i = 0; i < jobs.size(); ++i) {
      size_t k = (i + static_cast<size_t>(round)) % jobs.size();
      double seconds = 0, cpu = 0;
      if (std::string why = submit(*jobs[k], seconds, &cpu); !why.empty()) return why;
      out.seconds[k].push_back(cpu / out.dispatches_per_sample[k]);
    }
    out.rounds = round + 1;
    if (out.rounds < plan.min_rounds) continue;
    bool steady = true;
    for (const auto& samples : out.seconds) steady &= median_spread(samples) <= plan.max_spread;
    if (steady || out.rounds >= plan.max_rounds || seconds_since(start) > plan.max_seconds) break;
  }
  return "";
}

double median_of(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : (v[m - 1] + v[m]) / 2;
}

double median_spread(std::vector<double> v) {
  if (v.size() < 4) return 1;
  std::sort(v.begin(), v.end());
  // The order statistics around the middle that bound the median with about 95% confidence
  // (ranks n/2 -+ 0.98 sqrt(n), from the binomial distribution of values below it).
  double n = static_cast<double>(v.size()), half = 0.98 * std::sqrt(n);
  size_t lo = static_cast<size_t>(std::max(0.0, std::floor(n / 2 - half)));
  size_t hi = static_cast<size_t>(std::min(n - 1, std::ceil(n / 2 + half)));
  double median = median_of(v);
  return median > 0 ? (v[hi] - v[lo]) / median : 1;
}

}  // namespace lwc
