// Vulkan-style per-frame data on glm: the struct is named for what it holds, not as a GPU block;
// copying it into the frame's mapped uniform buffer is what makes its members GPU data.
#include <cstring>
#include <glm/glm.hpp>

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
