// Vulkan-style per-frame data on glm: the struct is named for what it holds, not as a GPU block;
// copying it into the frame's mapped uniform buffer is what makes its members GPU data.
#include <cstring>
#include <glm/glm.hpp>
#include <vector>

struct Frame {
  void* mapped = nullptr;  // vkMapMemory's pointer into this frame's uniform buffer
};

struct Globals {
  glm::vec3 sunPosition;
  float time;
  glm::vec3 eyePosition;
  float exposure;
};

// Kept on the CPU: never copied to the GPU.
struct History {
  glm::vec3 lastPosition;
};

void UpdateFrame(Frame& frame, const glm::dvec3& eyeWorldPosition, const glm::dvec3& sunWorldPosition, float time)
{
  Globals globals{};
  globals.sunPosition = glm::vec3(sunWorldPosition);
  globals.time = time;
  globals.eyePosition = glm::vec3(eyeWorldPosition);
  globals.exposure = 1.0f;
  std::memcpy(frame.mapped, &globals, sizeof(globals));
}

void Remember(History& history, const glm::dvec3& worldPosition)
{
  history.lastPosition = glm::vec3(worldPosition);
}

// A point list copied into a mapped vertex buffer. Vulkan's binding description (declared here as
// vulkan_core.h does) gives the stride as `sizeof`: a vertex layout, which no shader block mirrors.
struct VkVertexInputBindingDescription {
  unsigned binding;
  unsigned stride;
  int inputRate;
};

struct PointVertex {
  glm::vec3 position;
  double time;
};

VkVertexInputBindingDescription PointBinding() { return {0, sizeof(PointVertex), 0}; }

void UploadPoints(void* mappedVertices, std::vector<PointVertex>& points, const std::vector<glm::dvec3>& worldPositions)
{
  for (size_t i = 0; i < points.size(); ++i) {
    points[i].position = glm::vec3(worldPositions[i]);
  }
  std::memcpy(mappedVertices, points.data(), points.size() * sizeof(PointVertex));
}
