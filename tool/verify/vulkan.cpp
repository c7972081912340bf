#include "verify/vulkan.h"

#include <vulkan/vulkan.h>

#include <chrono>
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

std::string ComputeDevice::run(const std::vector<uint32_t>& spirv, std::vector<std::vector<uint8_t>>& buffers, uint32_t groups,
                               int repeats, DispatchTiming* timing) {
  VkDevice dev = s_->device;
  Cleanup cleanup;
  auto fail = [](const char* what, VkResult r) { return fmt::format("{} failed (VkResult {})", what, static_cast<int>(r)); };

  // Host-visible, coherent storage buffers: lavapipe's memory is the host's anyway.
  std::vector<VkBuffer> vk_buffers;
  std::vector<VkDeviceMemory> memories;
  for (const auto& data : buffers) {
    auto info = vk_struct<VkBufferCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);
    info.size = std::max<size_t>(data.size(), 4);
    info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    VkBuffer buffer;
    if (VkResult r = vkCreateBuffer(dev, &info, nullptr, &buffer); r != VK_SUCCESS) return fail("vkCreateBuffer", r);
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
    if (VkResult r = vkAllocateMemory(dev, &alloc, nullptr, &memory); r != VK_SUCCESS) return fail("vkAllocateMemory", r);
    cleanup.add([=] { vkFreeMemory(dev, memory, nullptr); });
    vkBindBufferMemory(dev, buffer, memory, 0);
    void* mapped;
    vkMapMemory(dev, memory, 0, VK_WHOLE_SIZE, 0, &mapped);
    std::memcpy(mapped, data.data(), data.size());
    vkUnmapMemory(dev, memory);
    vk_buffers.push_back(buffer);
    memories.push_back(memory);
  }

  auto pipeline_start = std::chrono::steady_clock::now();
  std::vector<VkDescriptorSetLayoutBinding> bindings;
  for (uint32_t i = 0; i < buffers.size(); ++i)
    bindings.push_back({i, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr});
  auto set_info = vk_struct<VkDescriptorSetLayoutCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO);
  set_info.bindingCount = static_cast<uint32_t>(bindings.size());
  set_info.pBindings = bindings.data();
  VkDescriptorSetLayout set_layout;
  if (VkResult r = vkCreateDescriptorSetLayout(dev, &set_info, nullptr, &set_layout); r != VK_SUCCESS)
    return fail("vkCreateDescriptorSetLayout", r);
  cleanup.add([=] { vkDestroyDescriptorSetLayout(dev, set_layout, nullptr); });
  auto layout_info = vk_struct<VkPipelineLayoutCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO);
  layout_info.setLayoutCount = 1;
  layout_info.pSetLayouts = &set_layout;
  VkPipelineLayout layout;
  if (VkResult r = vkCreatePipelineLayout(dev, &layout_info, nullptr, &layout); r != VK_SUCCESS) return fail("vkCreatePipelineLayout", r);
  cleanup.add([=] { vkDestroyPipelineLayout(dev, layout, nullptr); });
  auto module_info = vk_struct<VkShaderModuleCreateInfo>(VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO);
  module_info.codeSize = spirv.size() * sizeof(uint32_t);
  module_info.pCode = spirv.data();
  VkShaderModule module;
  if (VkResult r = vkCreateShaderModule(dev, &module_info, nullptr, &module); r != VK_SUCCESS) return fail("vkCreateShaderModule", r);
  cleanup.add([=] { vkDestroyShaderModule(dev, module, nullptr); });
  auto pipeline_info = vk_struct<VkComputePipelineCreateInfo>(VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO);
  pipeline_info.stage = vk_struct<VkPipelineShaderStageCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO);
  pipeline_info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  pipeline_info.stage.module = module;
  pipeline_info.stage.pName = "main";
  pipeline_info.layout = layout;
  VkPipeline pipeline;
  if (VkResult r = vkCreateComputePipelines(dev, VK_NULL_HANDLE, 1, &pipeline_info, nullptr, &pipeline); r != VK_SUCCESS)
    return fail("vkCreateComputePipelines", r);
  cleanup.add([=] { vkDestroyPipeline(dev, pipeline, nullptr); });
  if (timing) timing->pipeline_seconds = seconds_since(pipeline_start);

  VkDescriptorPoolSize pool_size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, static_cast<uint32_t>(std::max<size_t>(buffers.size(), 1))};
  auto pool_info = vk_struct<VkDescriptorPoolCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO);
  pool_info.maxSets = 1;
  pool_info.poolSizeCount = 1;
  pool_info.pPoolSizes = &pool_size;
  VkDescriptorPool pool;
  if (VkResult r = vkCreateDescriptorPool(dev, &pool_info, nullptr, &pool); r != VK_SUCCESS) return fail("vkCreateDescriptorPool", r);
  cleanup.add([=] { vkDestroyDescriptorPool(dev, pool, nullptr); });
  auto set_alloc = vk_struct<VkDescriptorSetAllocateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO);
  set_alloc.descriptorPool = pool;
  set_alloc.descriptorSetCount = 1;
  set_alloc.pSetLayouts = &set_layout;
  VkDescriptorSet set;
  if (VkResult r = vkAllocateDescriptorSets(dev, &set_alloc, &set); r != VK_SUCCESS) return fail("vkAllocateDescriptorSets", r);
  std::vector<VkDescriptorBufferInfo> infos;
  for (VkBuffer b : vk_buffers) infos.push_back({b, 0, VK_WHOLE_SIZE});
  std::vector<VkWriteDescriptorSet> writes;
  for (uint32_t i = 0; i < infos.size(); ++i) {
    auto w = vk_struct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
    w.dstSet = set;
    w.dstBinding = i;
    w.descriptorCount = 1;
    w.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    w.pBufferInfo = &infos[i];
    writes.push_back(w);
  }
  vkUpdateDescriptorSets(dev, static_cast<uint32_t>(writes.size()), writes.data(), 0, nullptr);

  auto command_pool_info = vk_struct<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
  command_pool_info.queueFamilyIndex = s_->queue_family;
  VkCommandPool command_pool;
  if (VkResult r = vkCreateCommandPool(dev, &command_pool_info, nullptr, &command_pool); r != VK_SUCCESS) return fail("vkCreateCommandPool", r);
  cleanup.add([=] { vkDestroyCommandPool(dev, command_pool, nullptr); });
  auto command_alloc = vk_struct<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
  command_alloc.commandPool = command_pool;
  command_alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  command_alloc.commandBufferCount = 1;
  VkCommandBuffer commands;
  if (VkResult r = vkAllocateCommandBuffers(dev, &command_alloc, &commands); r != VK_SUCCESS) return fail("vkAllocateCommandBuffers", r);
  auto begin = vk_struct<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
  vkBeginCommandBuffer(commands, &begin);
  vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
  vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_COMPUTE, layout, 0, 1, &set, 0, nullptr);
  vkCmdDispatch(commands, groups, 1, 1);
  vkEndCommandBuffer(commands);
  auto fence_info = vk_struct<VkFenceCreateInfo>(VK_STRUCTURE_TYPE_FENCE_CREATE_INFO);
  VkFence fence;
  if (VkResult r = vkCreateFence(dev, &fence_info, nullptr, &fence); r != VK_SUCCESS) return fail("vkCreateFence", r);
  cleanup.add([=] { vkDestroyFence(dev, fence, nullptr); });
  // A shader that never finishes must not hang the tool: each dispatch gets a deadline.
  constexpr uint64_t kTimeoutNs = 60ull * 1000 * 1000 * 1000;
  for (int i = 0; i < std::max(repeats, 1); ++i) {
    auto submit = vk_struct<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &commands;
    auto start = std::chrono::steady_clock::now();
    if (VkResult r = vkQueueSubmit(s_->queue, 1, &submit, fence); r != VK_SUCCESS) return fail("vkQueueSubmit", r);
    VkResult waited = vkWaitForFences(dev, 1, &fence, VK_TRUE, kTimeoutNs);
    if (waited == VK_TIMEOUT) return "the shader did not finish within 60 s (timeout)";
    if (waited != VK_SUCCESS) return fail("vkWaitForFences (device lost?)", waited);
    if (timing) timing->dispatch_seconds.push_back(seconds_since(start));
    vkResetFences(dev, 1, &fence);
  }
  for (size_t i = 0; i < buffers.size(); ++i) {
    void* mapped;
    vkMapMemory(dev, memories[i], 0, VK_WHOLE_SIZE, 0, &mapped);
    std::memcpy(buffers[i].data(), mapped, buffers[i].size());
    vkUnmapMemory(dev, memories[i]);
  }
  return "";
}

}  // namespace lwc
