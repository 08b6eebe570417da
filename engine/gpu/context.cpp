#include "engine/gpu/context.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <iostream>

#include "engine/core/error.h"
#include "engine/core/fault_injection.h"
#include "engine/gpu/vk_check.h"

namespace sky {

const char* vkResultName(VkResult r) {
  switch (r) {
#define SKY_CASE(x) \
  case x:           \
    return #x;
    SKY_CASE(VK_SUCCESS)
    SKY_CASE(VK_NOT_READY)
    SKY_CASE(VK_TIMEOUT)
    SKY_CASE(VK_INCOMPLETE)
    SKY_CASE(VK_ERROR_OUT_OF_HOST_MEMORY)
    SKY_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
    SKY_CASE(VK_ERROR_INITIALIZATION_FAILED)
    SKY_CASE(VK_ERROR_DEVICE_LOST)
    SKY_CASE(VK_ERROR_MEMORY_MAP_FAILED)
    SKY_CASE(VK_ERROR_LAYER_NOT_PRESENT)
    SKY_CASE(VK_ERROR_EXTENSION_NOT_PRESENT)
    SKY_CASE(VK_ERROR_FEATURE_NOT_PRESENT)
    SKY_CASE(VK_ERROR_INCOMPATIBLE_DRIVER)
    SKY_CASE(VK_ERROR_TOO_MANY_OBJECTS)
    SKY_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED)
    SKY_CASE(VK_ERROR_FRAGMENTED_POOL)
    SKY_CASE(VK_ERROR_OUT_OF_POOL_MEMORY)
    SKY_CASE(VK_ERROR_SURFACE_LOST_KHR)
    SKY_CASE(VK_ERROR_OUT_OF_DATE_KHR)
    SKY_CASE(VK_SUBOPTIMAL_KHR)
#undef SKY_CASE
    default:
      return "VkResult error";
  }
}

namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";
constexpr const char* kNoDevice =
    "no Vulkan 1.3 device found (install mesa-vulkan-drivers for the CPU device lavapipe)";

bool hasLayer(const char* name) {
  uint32_t count = 0;
  vkEnumerateInstanceLayerProperties(&count, nullptr);
  std::vector<VkLayerProperties> layers(count);
  vkEnumerateInstanceLayerProperties(&count, layers.data());
  return std::any_of(layers.begin(), layers.end(), [&](const VkLayerProperties& l) {
    return std::strcmp(l.layerName, name) == 0;
  });
}

// The loader says little: a driver list it cannot parse came back as
// VK_ERROR_OUT_OF_HOST_MEMORY from vkCreateInstance, or as a failed extension query (issue
// 31, 12). Say that no device could be made, and name the variables that choose the drivers
// when they are set.
[[noreturn]] void loaderFailed(VkResult r) {
  std::string why = std::string("the Vulkan loader failed with ") + vkResultName(r);
  for (const char* var : {"VK_ICD_FILENAMES", "VK_DRIVER_FILES", "VK_ADD_DRIVER_FILES"})
    if (const char* v = std::getenv(var); v && *v)
      why += std::string("; ") + var + "=" + v + " chooses the drivers: is it a driver manifest?";
  internalError("no Vulkan device could be created: " + why);
}

bool hasInstanceExtension(const char* name) {
  uint32_t count = 0;
  if (VkResult r = vkEnumerateInstanceExtensionProperties(nullptr, &count, nullptr);
      r != VK_SUCCESS)
    loaderFailed(r);
  std::vector<VkExtensionProperties> exts(count);
  if (VkResult r = vkEnumerateInstanceExtensionProperties(nullptr, &count, exts.data());
      r != VK_SUCCESS && r != VK_INCOMPLETE)
    loaderFailed(r);
  return std::any_of(exts.begin(), exts.end(), [&](const VkExtensionProperties& e) {
    return std::strcmp(e.extensionName, name) == 0;
  });
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

int typeScore(VkPhysicalDeviceType t) {
  switch (t) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
      return 4;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
      return 3;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
      return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
      return 1;
    default:
      return 0;
  }
}

std::string describeDevices(const std::vector<PhysicalDeviceInfo>& devices) {
  std::string s;
  for (const auto& d : devices) {
    if (!s.empty()) s += "; ";
    s += std::to_string(d.index) + ": " + d.name;
  }
  return s.empty() ? "none" : s;
}

}  // namespace

VKAPI_ATTR VkBool32 VKAPI_CALL debugCallback(VkDebugUtilsMessageSeverityFlagBitsEXT,
                                             VkDebugUtilsMessageTypeFlagsEXT,
                                             const VkDebugUtilsMessengerCallbackDataEXT* data,
                                             void* user) {
  auto* ctx = static_cast<Context*>(user);
  ctx->mValidationMessages.fetch_add(1);
  std::string message = data && data->pMessage ? data->pMessage : "(no message)";
  if (ctx->mOnValidation)
    ctx->mOnValidation(message);
  else
    std::cerr << "Vulkan validation: " << message << "\n";
  return VK_FALSE;
}

ContextOptions ContextOptions::fromEnvironment() {
  ContextOptions o;
  const char* v = std::getenv("SKY_VALIDATION");
  o.validation = v && std::strcmp(v, "0") != 0 && *v;
  // SKY_VALIDATION=core: the core checks alone (synchronisation validation slows a frame).
  o.syncValidation = o.validation && std::strcmp(v, "core") != 0;
  return o;
}

Context::Context(const ContextOptions& options) : mOnValidation(options.onValidationMessage) {
  try {
    createInstance(options);
    pickDevice(options.gpu);
    createDevice(options.deviceExtensions);
  } catch (...) {
    destroy();  // members are destroyed by unwinding; only the Vulkan objects need freeing
    throw;
  }
}

Context::Context(const ExternalDevice& host) {
  if (!host.instance || !host.physicalDevice || !host.device)
    internalError("a host's Vulkan device: the instance, physical device and device must be given");
  mExternal = true;
  mInstance = host.instance;
  mPhysicalDevice = host.physicalDevice;
  mDevice = host.device;
  try {
    readDeviceProperties();
    if (mProperties.apiVersion < VK_API_VERSION_1_3)
      internalError("the host's Vulkan device " + deviceName() + " does not support Vulkan 1.3");
    uint32_t n = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(mPhysicalDevice, &n, nullptr);
    std::vector<VkQueueFamilyProperties> families(n);
    vkGetPhysicalDeviceQueueFamilyProperties(mPhysicalDevice, &n, families.data());
    if (host.queueFamily >= n || !(families[host.queueFamily].queueFlags & VK_QUEUE_COMPUTE_BIT))
      internalError("the host's queue family " + std::to_string(host.queueFamily) + " on " +
                    deviceName() + " cannot run compute shaders");
    if (host.queueIndex >= families[host.queueFamily].queueCount)
      internalError("the host's queue family " + std::to_string(host.queueFamily) +
                    " has no queue " + std::to_string(host.queueIndex));
    mQueueFamily = host.queueFamily;
    useQueue(host.queueIndex);
  } catch (...) {
    destroy();
    throw;
  }
}

Context::~Context() {
  destroy();
}

void Context::destroy() {
  if (mExternal) {
    // The host's device and instance stay; only what was made here goes, once the queue has
    // finished this Context's work.
    if (mDevice && mUploadPool) {
      if (mQueue) vkQueueWaitIdle(mQueue);
      vkDestroyCommandPool(mDevice, mUploadPool, nullptr);
    }
    mUploadPool = VK_NULL_HANDLE;
    mDevice = VK_NULL_HANDLE;
    mInstance = VK_NULL_HANDLE;
    return;
  }
  if (mDevice) {
    vkDeviceWaitIdle(mDevice);
    if (mUploadPool) vkDestroyCommandPool(mDevice, mUploadPool, nullptr);
    vkDestroyDevice(mDevice, nullptr);
    mDevice = VK_NULL_HANDLE;
  }
  if (mMessenger) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(mInstance, "vkDestroyDebugUtilsMessengerEXT"));
    if (destroy) destroy(mInstance, mMessenger, nullptr);
    mMessenger = VK_NULL_HANDLE;
  }
  if (mInstance) {
    vkDestroyInstance(mInstance, nullptr);
    mInstance = VK_NULL_HANDLE;
  }
}

void Context::createInstance(const ContextOptions& options) {
  uint32_t loaderVersion = 0;
  if (vkEnumerateInstanceVersion(&loaderVersion) != VK_SUCCESS ||
      loaderVersion < VK_API_VERSION_1_3)
    internalError("the Vulkan loader is older than 1.3 (install libvulkan1 from Debian 12)");

  std::vector<const char*> layers, extensions;
  mValidation = options.validation;
  if (mValidation) {
    if (!hasLayer(kValidationLayer))
      internalError(std::string("validation requested (SKY_VALIDATION=1) but ") + kValidationLayer +
                    " is not installed (apt-get install vulkan-validationlayers)");
    layers.push_back(kValidationLayer);
  }
  mDebugUtils = hasInstanceExtension(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  if (mValidation && !mDebugUtils)
    internalError("validation needs VK_EXT_debug_utils, which this Vulkan loader lacks");
  if (mDebugUtils) extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  for (const std::string& e : options.instanceExtensions) {
    if (!hasInstanceExtension(e.c_str()))
      internalError("the Vulkan instance extension " + e + " is not available");
    extensions.push_back(e.c_str());
  }

  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "skylayers";
  app.pEngineName = "skylayers";
  app.apiVersion = VK_API_VERSION_1_3;

  VkDebugUtilsMessengerCreateInfoEXT messenger{
      VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  messenger.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                              VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  messenger.messageType =
      VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT;
  messenger.pfnUserCallback = debugCallback;
  messenger.pUserData = this;

  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  info.pApplicationInfo = &app;
  info.enabledLayerCount = static_cast<uint32_t>(layers.size());
  info.ppEnabledLayerNames = layers.data();
  info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();
  // Chained so messages from vkCreateInstance/vkDestroyInstance are caught too.
  if (mValidation) info.pNext = &messenger;
  // Synchronisation validation with the core checks (issue 31): a missing or wrong barrier
  // between two passes is a hazard message, which fails a test like any other. The frame
  // graph places every barrier, so this checks the graph's ordering, not a pass's code.
  const VkValidationFeatureEnableEXT syncValidation =
      VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
  VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
  features.enabledValidationFeatureCount = 1;
  features.pEnabledValidationFeatures = &syncValidation;
  if (mValidation && options.syncValidation) {
    features.pNext = info.pNext;
    info.pNext = &features;
  }

  VkResult r = vkCreateInstance(&info, nullptr, &mInstance);
  if (r == VK_ERROR_INCOMPATIBLE_DRIVER) internalError(kNoDevice);
  if (r != VK_SUCCESS) loaderFailed(r);

  if (mValidation) {
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(mInstance, "vkCreateDebugUtilsMessengerEXT"));
    SKY_VK(create(mInstance, &messenger, nullptr, &mMessenger));
  }
  if (mDebugUtils)
    mSetObjectName = reinterpret_cast<PFN_vkSetDebugUtilsObjectNameEXT>(
        vkGetInstanceProcAddr(mInstance, "vkSetDebugUtilsObjectNameEXT"));
}

std::vector<PhysicalDeviceInfo> Context::enumerate(VkInstance instance) {
  uint32_t count = 0;
  vkEnumeratePhysicalDevices(instance, &count, nullptr);
  std::vector<VkPhysicalDevice> devices(count);
  vkEnumeratePhysicalDevices(instance, &count, devices.data());
  std::vector<PhysicalDeviceInfo> out;
  for (uint32_t i = 0; i < count; ++i) {
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(devices[i], &p);
    out.push_back({i, p.deviceName, p.deviceType, p.apiVersion});
  }
  return out;
}

void Context::pickDevice(const std::string& request) {
  uint32_t count = 0;
  vkEnumeratePhysicalDevices(mInstance, &count, nullptr);
  std::vector<VkPhysicalDevice> devices(count);
  vkEnumeratePhysicalDevices(mInstance, &count, devices.data());
  std::vector<PhysicalDeviceInfo> infos = enumerate(mInstance);
  if (devices.empty()) internalError(kNoDevice);

  auto usable = [&](uint32_t i) {
    if (infos[i].apiVersion < VK_API_VERSION_1_3) return false;
    uint32_t n = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(devices[i], &n, nullptr);
    std::vector<VkQueueFamilyProperties> families(n);
    vkGetPhysicalDeviceQueueFamilyProperties(devices[i], &n, families.data());
    return std::any_of(families.begin(), families.end(), [](const VkQueueFamilyProperties& f) {
      return (f.queueFlags & VK_QUEUE_COMPUTE_BIT) != 0;
    });
  };

  int chosen = -1;
  if (request.empty()) {
    int best = 0;
    for (uint32_t i = 0; i < devices.size(); ++i) {
      int score = usable(i) ? typeScore(infos[i].type) + 1 : 0;
      if (score > best) best = score, chosen = static_cast<int>(i);
    }
    if (chosen < 0) internalError(kNoDevice);
  } else {
    bool numeric = std::all_of(request.begin(), request.end(),
                               [](char c) { return std::isdigit(static_cast<unsigned char>(c)); });
    for (uint32_t i = 0; i < devices.size() && chosen < 0; ++i) {
      if (numeric ? std::to_string(i) == request
                  : lower(infos[i].name).find(lower(request)) != std::string::npos)
        chosen = static_cast<int>(i);
    }
    if (chosen < 0)
      inputError("--gpu " + request +
                 ": no such Vulkan device (available: " + describeDevices(infos) + ")");
    if (!usable(static_cast<uint32_t>(chosen)))
      inputError("--gpu " + request + ": " + infos[static_cast<size_t>(chosen)].name +
                 " does not support Vulkan 1.3 compute");
  }
  mPhysicalDevice = devices[static_cast<size_t>(chosen)];
  readDeviceProperties();
}

void Context::readDeviceProperties() {
  vkGetPhysicalDeviceProperties(mPhysicalDevice, &mProperties);
  VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
  VkPhysicalDeviceProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
  properties.pNext = &driver;
  vkGetPhysicalDeviceProperties2(mPhysicalDevice, &properties);
  mDriverId = driver.driverID;
  mShaderDefines.clear();
  if (mDriverId == VK_DRIVER_ID_MESA_LLVMPIPE)
    mShaderDefines.emplace_back("SKY_UNFOLDABLE_PARAMS_INDEX", "1");
}

void Context::createDevice(const std::vector<std::string>& extraExtensions) {
  uint32_t extensionCount = 0;
  vkEnumerateDeviceExtensionProperties(mPhysicalDevice, nullptr, &extensionCount, nullptr);
  std::vector<VkExtensionProperties> available(extensionCount);
  vkEnumerateDeviceExtensionProperties(mPhysicalDevice, nullptr, &extensionCount, available.data());
  std::vector<const char*> extensions;
  for (const std::string& e : extraExtensions) {
    if (std::none_of(available.begin(), available.end(),
                     [&](const VkExtensionProperties& p) { return e == p.extensionName; }))
      internalError("the Vulkan device extension " + e + " is not available on " +
                    std::string(mProperties.deviceName));
    extensions.push_back(e.c_str());
  }

  uint32_t n = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(mPhysicalDevice, &n, nullptr);
  std::vector<VkQueueFamilyProperties> families(n);
  vkGetPhysicalDeviceQueueFamilyProperties(mPhysicalDevice, &n, families.data());
  // Prefer a family with graphics too: the window presents from the same queue.
  int family = -1;
  for (uint32_t i = 0; i < n; ++i) {
    if (!(families[i].queueFlags & VK_QUEUE_COMPUTE_BIT)) continue;
    if (family < 0 || (families[i].queueFlags & VK_QUEUE_GRAPHICS_BIT))
      family = static_cast<int>(i);
    if (families[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) break;
  }
  mQueueFamily = static_cast<uint32_t>(family);

  float priority = 1.0f;
  VkDeviceQueueCreateInfo queue{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queue.queueFamilyIndex = mQueueFamily;
  queue.queueCount = 1;
  queue.pQueuePriorities = &priority;

  VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  features.pNext = &f13;
  f13.pNext = &f12;
  vkGetPhysicalDeviceFeatures2(mPhysicalDevice, &features);
  if (!f13.synchronization2)
    internalError(std::string(mProperties.deviceName) + " lacks synchronization2");

  // Enable only what the engine relies on, so a real GPU and lavapipe behave alike.
  VkPhysicalDeviceVulkan13Features want13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  want13.synchronization2 = VK_TRUE;
  want13.maintenance4 = f13.maintenance4;
  VkPhysicalDeviceVulkan12Features want12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  want12.hostQueryReset = f12.hostQueryReset;
  want12.pNext = &want13;
  VkPhysicalDeviceFeatures2 want{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  want.pNext = &want12;

  VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  info.pNext = &want;
  info.queueCreateInfoCount = 1;
  info.pQueueCreateInfos = &queue;
  info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();
  SKY_VK(vkCreateDevice(mPhysicalDevice, &info, nullptr, &mDevice));
  useQueue(0);
}

void Context::useQueue(uint32_t index) {
  uint32_t n = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(mPhysicalDevice, &n, nullptr);
  std::vector<VkQueueFamilyProperties> families(n);
  vkGetPhysicalDeviceQueueFamilyProperties(mPhysicalDevice, &n, families.data());
  mTimestampValidBits = families[mQueueFamily].timestampValidBits;
  vkGetDeviceQueue(mDevice, mQueueFamily, index, &mQueue);

  VkCommandPoolCreateInfo pool{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pool.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
  pool.queueFamilyIndex = mQueueFamily;
  SKY_VK(vkCreateCommandPool(mDevice, &pool, nullptr, &mUploadPool));
}

uint32_t Context::memoryType(uint32_t typeBits, VkMemoryPropertyFlags flags) const {
  VkPhysicalDeviceMemoryProperties mem;
  vkGetPhysicalDeviceMemoryProperties(mPhysicalDevice, &mem);
  for (uint32_t i = 0; i < mem.memoryTypeCount; ++i)
    if ((typeBits & (1u << i)) && (mem.memoryTypes[i].propertyFlags & flags) == flags) return i;
  internalError("no Vulkan memory type with the required properties on " + deviceName());
}

void Context::submitAndWait(const std::function<void(VkCommandBuffer)>& record) const {
  VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  alloc.commandPool = mUploadPool;
  alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  alloc.commandBufferCount = 1;
  VkCommandBuffer cmd;
  SKY_VK(vkAllocateCommandBuffers(mDevice, &alloc, &cmd));
  VkFence fence = VK_NULL_HANDLE;
  try {
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    SKY_VK(vkBeginCommandBuffer(cmd, &begin));
    record(cmd);
    SKY_VK(vkEndCommandBuffer(cmd));
    VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    SKY_VK(vkCreateFence(mDevice, &fi, nullptr, &fence));
    VkCommandBufferSubmitInfo cb{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
    cb.commandBuffer = cmd;
    VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
    submit.commandBufferInfoCount = 1;
    submit.pCommandBufferInfos = &cb;
    this->submit(submit, fence);
    wait(fence);
  } catch (...) {
    if (fence) vkDestroyFence(mDevice, fence, nullptr);
    vkFreeCommandBuffers(mDevice, mUploadPool, 1, &cmd);
    throw;
  }
  vkDestroyFence(mDevice, fence, nullptr);
  vkFreeCommandBuffers(mDevice, mUploadPool, 1, &cmd);
}

void Context::setName(VkObjectType type, uint64_t handle, const std::string& name) const {
  if (!mSetObjectName || name.empty()) return;
  VkDebugUtilsObjectNameInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT};
  info.objectType = type;
  info.objectHandle = handle;
  info.pObjectName = name.c_str();
  mSetObjectName(mDevice, &info);
}

// One line for a device that stopped working: the cause is the driver's or the GPU's, and
// the run ends with exit 1 after its temporary files are removed (docs/outputs.md).
void Context::failed(VkResult r, const char* during) const {
  if (r == VK_ERROR_DEVICE_LOST)
    throw DeviceLost("the Vulkan device " + deviceName() + " was lost (VK_ERROR_DEVICE_LOST) " +
                     during + ": the driver or the GPU failed; the frame was not written");
  internalError(std::string("Vulkan ") + during + " on " + deviceName() +
                " failed: " + vkResultName(r));
}

void Context::submit(const VkSubmitInfo2& info, VkFence fence) const {
  VkResult r = faultAt(FaultPoint::DeviceLostAtSubmit) ? VK_ERROR_DEVICE_LOST
                                                       : vkQueueSubmit2(mQueue, 1, &info, fence);
  if (r != VK_SUCCESS) failed(r, "at a queue submit");
}

void Context::wait(VkFence fence) const {
  VkResult r = vkWaitForFences(mDevice, 1, &fence, VK_TRUE, UINT64_MAX);
  if (r != VK_SUCCESS) failed(r, "while waiting for the GPU");
}

VkDeviceMemory Context::allocate(const VkMemoryAllocateInfo& info, const std::string& what) const {
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkResult r = faultAt(FaultPoint::OutOfDeviceMemory)
                   ? VK_ERROR_OUT_OF_DEVICE_MEMORY
                   : vkAllocateMemory(mDevice, &info, nullptr, &memory);
  if (r == VK_ERROR_OUT_OF_DEVICE_MEMORY || r == VK_ERROR_OUT_OF_HOST_MEMORY)
    internalError("out of memory on " + deviceName() + " (" + vkResultName(r) + ") for " + what +
                  ", " + std::to_string(info.allocationSize >> 20) +
                  " MiB (lower output.width and output.height, or free the GPU)");
  if (r != VK_SUCCESS) failed(r, "allocating memory");
  return memory;
}

}  // namespace sky
