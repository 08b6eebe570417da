#pragma once
// Dear ImGui on the window: its GLFW backend (input, chained to the window's callbacks) and its
// Vulkan backend drawing in the swapchain's render pass. Create after the swapchain's first
// recreate() (it needs the image count) and destroy before the swapchain.
#include <cstdint>

#include <vulkan/vulkan.h>

namespace sky {
class Context;
}

namespace sky::view {

class Swapchain;
class Window;

class ImguiLayer {
public:
  ImguiLayer(const Context& ctx, Window& window, const Swapchain& swapchain);
  ~ImguiLayer();
  ImguiLayer(const ImguiLayer&) = delete;
  ImguiLayer& operator=(const ImguiLayer&) = delete;

  // After a swapchain recreate: the backend sizes its per-image buffers by the image count.
  void swapchainRecreated(const Swapchain& swapchain);
  // Starts an ImGui frame (input from GLFW); widgets go between this and draw().
  void beginFrame();
  // Ends the frame and records its draw commands into `cmd`, inside the render pass.
  void draw(VkCommandBuffer cmd);
  // Whether ImGui uses the mouse / keyboard now (a drag over the panel is not a camera drag).
  bool wantsMouse() const;
  bool wantsKeyboard() const;

private:
  const Context& mCtx;
  VkDescriptorPool mPool = VK_NULL_HANDLE;
  bool mFrameOpen = false;
};

}  // namespace sky::view
