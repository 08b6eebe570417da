#include "imgui_layer.h"

#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>
#include <imgui.h>

#include "engine/core/error.h"
#include "engine/gpu/context.h"
#include "engine/gpu/vk_check.h"
#include "swapchain.h"
#include "window.h"

namespace sky::view {

namespace {

void checkImguiVk(VkResult r) {
  if (r < 0) internalError(std::string("ImGui Vulkan backend: ") + vkResultName(r));
}

}  // namespace

ImguiLayer::ImguiLayer(const Context& ctx, Window& window, const Swapchain& swapchain) : mCtx(ctx) {
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // no imgui.ini dropped in whatever folder skyview ran from
  ImGui::StyleColorsDark();
  // true: ImGui installs its callbacks and chains to the window's own (key presses).
  ImGui_ImplGlfw_InitForVulkan(window.handle(), true);

  // The backend needs one combined image sampler (the font atlas); a few spare.
  VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 8};
  VkDescriptorPoolCreateInfo pool{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pool.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
  pool.maxSets = 8;
  pool.poolSizeCount = 1;
  pool.pPoolSizes = &size;
  SKY_VK(vkCreateDescriptorPool(ctx.device(), &pool, nullptr, &mPool));

  ImGui_ImplVulkan_InitInfo info{};
  info.Instance = ctx.instance();
  info.PhysicalDevice = ctx.physicalDevice();
  info.Device = ctx.device();
  info.QueueFamily = ctx.queueFamily();
  info.Queue = ctx.queue();
  info.DescriptorPool = mPool;
  info.Subpass = 0;
  info.MinImageCount = swapchain.minImageCount();
  info.ImageCount = swapchain.imageCount();
  info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
  info.CheckVkResultFn = checkImguiVk;
  if (!ImGui_ImplVulkan_Init(&info, swapchain.renderPass()))
    internalError("ImGui's Vulkan backend failed to initialise");
  ctx.submitAndWait([](VkCommandBuffer cmd) { ImGui_ImplVulkan_CreateFontsTexture(cmd); });
  ImGui_ImplVulkan_DestroyFontUploadObjects();
}

ImguiLayer::~ImguiLayer() {
  vkDeviceWaitIdle(mCtx.device());
  if (mFrameOpen) ImGui::EndFrame();
  ImGui_ImplVulkan_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  vkDestroyDescriptorPool(mCtx.device(), mPool, nullptr);
}

void ImguiLayer::swapchainRecreated(const Swapchain& swapchain) {
  ImGui_ImplVulkan_SetMinImageCount(swapchain.minImageCount());
}

void ImguiLayer::beginFrame() {
  if (mFrameOpen) ImGui::EndFrame();
  ImGui_ImplVulkan_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
  mFrameOpen = true;
}

void ImguiLayer::draw(VkCommandBuffer cmd) {
  ImGui::Render();
  mFrameOpen = false;
  ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cmd);
}

bool ImguiLayer::wantsMouse() const {
  return ImGui::GetIO().WantCaptureMouse;
}

bool ImguiLayer::wantsKeyboard() const {
  return ImGui::GetIO().WantCaptureKeyboard;
}

}  // namespace sky::view
