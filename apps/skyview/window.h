#pragma once
// The GLFW window: created before the Vulkan context (which needs the surface extensions it
// names) and destroyed after it. Collects key presses for the viewer; ImGui's GLFW backend,
// installed later, chains to these callbacks.
#include <cstdint>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

struct GLFWwindow;

namespace sky::view {

struct KeyPress {
  int key;   // GLFW_KEY_*
  int mods;  // GLFW_MOD_*
};

class Window {
public:
  // Initialises GLFW and opens a window of width x height screen coordinates. Internal error
  // "cannot open a window (no X display; try xvfb-run)" without a display.
  Window(int width, int height, const std::string& title);
  ~Window();
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;

  // The instance extensions a surface on this platform needs (VK_KHR_surface and one more).
  static std::vector<std::string> requiredInstanceExtensions();
  // Creates a surface for the window on `instance`; the caller destroys it before the instance.
  VkSurfaceKHR createSurface(VkInstance instance) const;

  GLFWwindow* handle() const { return mWindow; }
  // The framebuffer in pixels; 0 x 0 while minimised (really, or by iconify() on a display
  // without a window manager, where minimising does nothing: see iconify()).
  VkExtent2D framebufferSize() const;
  bool closeRequested() const;
  void requestClose();
  // The key presses (and repeats) since the last call, in order.
  std::vector<KeyPress> takeKeyPresses();
  bool keyDown(int key) const;

  // Script and test hooks. iconify() also marks the window minimised for framebufferSize(),
  // because under Xvfb without a window manager nothing would change and the zero-size path
  // could not be exercised; restore() clears it.
  void resize(int width, int height);
  void iconify();
  void restore();

private:
  static void onKey(GLFWwindow* window, int key, int scancode, int action, int mods);

  GLFWwindow* mWindow = nullptr;
  std::vector<KeyPress> mPresses;
  bool mSimulatedMinimised = false;
};

// The surface of a window on an instance, destroyed with it.
class WindowSurface {
public:
  WindowSurface(const Window& window, VkInstance instance)
      : mInstance(instance), mSurface(window.createSurface(instance)) {}
  ~WindowSurface() { vkDestroySurfaceKHR(mInstance, mSurface, nullptr); }
  WindowSurface(const WindowSurface&) = delete;
  WindowSurface& operator=(const WindowSurface&) = delete;
  VkSurfaceKHR handle() const { return mSurface; }

private:
  VkInstance mInstance;
  VkSurfaceKHR mSurface;
};

}  // namespace sky::view
