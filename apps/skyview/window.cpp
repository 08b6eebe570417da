#include "window.h"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include "engine/core/error.h"
#include "engine/gpu/vk_check.h"

namespace sky::view {

namespace {

// GLFW reports errors through a callback; the last one explains a failed call.
std::string gLastGlfwError;

void onGlfwError(int, const char* description) {
  gLastGlfwError = description ? description : "";
}

}  // namespace

Window::Window(int width, int height, const std::string& title) {
  glfwSetErrorCallback(onGlfwError);
  if (!glfwInit()) {
    // GLFW 3.3 on X11 fails here without $DISPLAY or when the display cannot be opened.
    internalError("cannot open a window (no X display; try xvfb-run)" +
                  (gLastGlfwError.empty() ? std::string() : ": " + gLastGlfwError));
  }
  if (!glfwVulkanSupported()) {
    glfwTerminate();
    internalError("cannot open a window: GLFW finds no Vulkan loader");
  }
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  mWindow = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (!mWindow) {
    glfwTerminate();
    internalError("cannot open a window: " + gLastGlfwError);
  }
  glfwSetWindowUserPointer(mWindow, this);
  glfwSetKeyCallback(mWindow, onKey);
}

Window::~Window() {
  glfwDestroyWindow(mWindow);
  glfwTerminate();
}

std::vector<std::string> Window::requiredInstanceExtensions() {
  uint32_t count = 0;
  const char** names = glfwGetRequiredInstanceExtensions(&count);
  if (!names) internalError("cannot open a window: " + gLastGlfwError);
  return std::vector<std::string>(names, names + count);
}

VkSurfaceKHR Window::createSurface(VkInstance instance) const {
  VkSurfaceKHR surface = VK_NULL_HANDLE;
  SKY_VK(glfwCreateWindowSurface(instance, mWindow, nullptr, &surface));
  return surface;
}

VkExtent2D Window::framebufferSize() const {
  if (mSimulatedMinimised || glfwGetWindowAttrib(mWindow, GLFW_ICONIFIED)) return {0, 0};
  int w = 0, h = 0;
  glfwGetFramebufferSize(mWindow, &w, &h);
  return {static_cast<uint32_t>(std::max(w, 0)), static_cast<uint32_t>(std::max(h, 0))};
}

bool Window::closeRequested() const {
  return glfwWindowShouldClose(mWindow);
}

void Window::requestClose() {
  glfwSetWindowShouldClose(mWindow, GLFW_TRUE);
}

std::vector<KeyPress> Window::takeKeyPresses() {
  std::vector<KeyPress> out;
  out.swap(mPresses);
  return out;
}

bool Window::keyDown(int key) const {
  return glfwGetKey(mWindow, key) == GLFW_PRESS;
}

void Window::resize(int width, int height) {
  glfwSetWindowSize(mWindow, width, height);
}

void Window::iconify() {
  glfwIconifyWindow(mWindow);
  mSimulatedMinimised = true;
}

void Window::restore() {
  glfwRestoreWindow(mWindow);
  mSimulatedMinimised = false;
}

void Window::onKey(GLFWwindow* window, int key, int, int action, int mods) {
  auto* self = static_cast<Window*>(glfwGetWindowUserPointer(window));
  if (self && (action == GLFW_PRESS || action == GLFW_REPEAT))
    self->mPresses.push_back({key, mods});
}

}  // namespace sky::view
