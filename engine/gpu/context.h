#pragma once
// The Vulkan 1.3 instance, device and compute queue every other GPU object hangs off.
// One Context per process is the normal case; it must outlive everything created from it.
#include <atomic>
#include <functional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <vulkan/vulkan.h>

#include "engine/core/error.h"

namespace sky {

struct ContextOptions {
  // "" picks automatically (a discrete GPU, then integrated, virtual, and finally the CPU device
  // lavapipe); a decimal number picks by index, anything else by case-insensitive name substring.
  std::string gpu;
  // Khronos validation layers; defaults to $SKY_VALIDATION=1.
  bool validation = false;
  // With validation, synchronisation validation too (hazards between passes); on unless
  // $SKY_VALIDATION=core.
  bool syncValidation = true;
  // Receives every validation message (warnings and errors). Default: print to stderr with the
  // prefix "Vulkan validation: ".
  std::function<void(std::string_view)> onValidationMessage;
  // Extensions enabled on top of the engine's own, for a caller that needs more than compute
  // (skyview: VK_KHR_surface and the platform's surface extension, VK_KHR_swapchain). Each must
  // exist, else an Internal error naming it. Empty for every compute-only caller.
  std::vector<std::string> instanceExtensions;
  std::vector<std::string> deviceExtensions;

  static ContextOptions fromEnvironment();  // validation from $SKY_VALIDATION
};

// A device that belongs to someone else (a host program embedding the engine): Vulkan 1.3,
// created with synchronization2 and maintenance4 enabled, and a queue of `queueFamily` that can
// compute. The Context borrows it: it records, submits on that queue and waits for its own work,
// and destroys only what it made. The host must keep the objects alive longer than the Context, and
// not use the queue from another thread while the engine submits.
struct ExternalDevice {
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  uint32_t queueFamily = 0;
  uint32_t queueIndex = 0;
};

struct PhysicalDeviceInfo {
  uint32_t index;
  std::string name;
  VkPhysicalDeviceType type;
  uint32_t apiVersion;
};

// The GPU stopped working (VK_ERROR_DEVICE_LOST): nothing more can run on this device. An
// Internal error (exit 1) of its own type, so an app that keeps a window (skyview) can show the
// message and stop drawing instead of retrying.
class DeviceLost : public Error {
public:
  explicit DeviceLost(const std::string& message) : Error(ErrorKind::Internal, message) {}
};

class Context {
public:
  explicit Context(const ContextOptions& options = ContextOptions::fromEnvironment());
  // On a host's device (ExternalDevice). Validation is the host's instance's business: no
  // messenger is made, and validationMessageCount() stays 0. Internal error naming what is
  // missing when the device cannot serve (no Vulkan 1.3, no compute on the family).
  explicit Context(const ExternalDevice& host);
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  VkInstance instance() const { return mInstance; }
  VkPhysicalDevice physicalDevice() const { return mPhysicalDevice; }
  VkDevice device() const { return mDevice; }
  VkQueue queue() const { return mQueue; }
  uint32_t queueFamily() const { return mQueueFamily; }
  const VkPhysicalDeviceProperties& properties() const { return mProperties; }
  std::string deviceName() const { return mProperties.deviceName; }
  bool validationEnabled() const { return mValidation; }
  // Number of validation messages seen so far (tests fail when it moves).
  uint64_t validationMessageCount() const { return mValidationMessages.load(); }
  // Nanoseconds per timestamp tick, and whether the compute queue has timestamps at all.
  double timestampPeriodNs() const { return mProperties.limits.timestampPeriod; }
  bool hasTimestamps() const { return mTimestampValidBits > 0; }
  // The driver (VK_DRIVER_ID_MESA_LLVMPIPE for lavapipe).
  VkDriverId driverId() const { return mDriverId; }
  // Defines every shader built for this device gets (driver workarounds, name and value):
  // SKY_UNFOLDABLE_PARAMS_INDEX=1 on lavapipe (shaders/common/params_block.glsl says why).
  const std::vector<std::pair<std::string, std::string>>& shaderDefines() const {
    return mShaderDefines;
  }

  // A memory type index with all of `flags` among `typeBits`; Internal error if none.
  uint32_t memoryType(uint32_t typeBits, VkMemoryPropertyFlags flags) const;
  // vkQueueSubmit2 on the compute queue. A lost device is DeviceLost, which says so (exit 1);
  // any other failure an Internal error; SKY_FAULT=device_lost_submit injects the loss.
  void submit(const VkSubmitInfo2& info, VkFence fence) const;
  // Throws for a device call that returned `r` (not VK_SUCCESS) `during` something ("at
  // present"): DeviceLost for VK_ERROR_DEVICE_LOST, else an Internal error naming the result.
  [[noreturn]] void failed(VkResult r, const char* during) const;
  // Waits for `fence`; a device lost while waiting is the same Internal error.
  void wait(VkFence fence) const;
  // vkAllocateMemory. Out of device or host memory is an Internal error naming `what`, its
  // size and the device, with what to lower; SKY_FAULT=out_of_device_memory injects it.
  VkDeviceMemory allocate(const VkMemoryAllocateInfo& info, const std::string& what) const;
  // Records with `record`, submits on the compute queue and waits. For uploads and tests.
  void submitAndWait(const std::function<void(VkCommandBuffer)>& record) const;
  // Gives a Vulkan object a debug name (shown in validation messages) when debug utils exist.
  void setName(VkObjectType type, uint64_t handle, const std::string& name) const;

  // Every physical device the loader sees, for --gpu and error messages.
  static std::vector<PhysicalDeviceInfo> enumerate(VkInstance instance);

private:
  void createInstance(const ContextOptions& options);
  void pickDevice(const std::string& request);
  void createDevice(const std::vector<std::string>& extraExtensions);
  // The chosen physical device's properties, driver and shader defines.
  void readDeviceProperties();
  // The upload command pool and the queue's timestamp bits, for a device in hand.
  void useQueue(uint32_t index);
  void destroy();

  VkInstance mInstance = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT mMessenger = VK_NULL_HANDLE;
  VkPhysicalDevice mPhysicalDevice = VK_NULL_HANDLE;
  VkPhysicalDeviceProperties mProperties{};
  VkDevice mDevice = VK_NULL_HANDLE;
  VkQueue mQueue = VK_NULL_HANDLE;
  uint32_t mQueueFamily = 0;
  uint32_t mTimestampValidBits = 0;
  VkDriverId mDriverId = VkDriverId(0);
  std::vector<std::pair<std::string, std::string>> mShaderDefines;
  VkCommandPool mUploadPool = VK_NULL_HANDLE;
  bool mValidation = false;
  bool mDebugUtils = false;
  bool mExternal = false;  // the instance and device are the host's: not destroyed here
  PFN_vkSetDebugUtilsObjectNameEXT mSetObjectName = nullptr;
  std::function<void(std::string_view)> mOnValidation;
  std::atomic<uint64_t> mValidationMessages{0};

  friend VKAPI_ATTR VkBool32 VKAPI_CALL debugCallback(VkDebugUtilsMessageSeverityFlagBitsEXT,
                                                      VkDebugUtilsMessageTypeFlagsEXT,
                                                      const VkDebugUtilsMessengerCallbackDataEXT*,
                                                      void*);
};

}  // namespace sky
