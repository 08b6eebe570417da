// A Sky on the host's own Vulkan device (<skylayers/vulkan.h>): the test is the host. It
// makes its instance (with the validation layers and its own messenger, as the host owns
// validation), its device and queue, renders through a Sky on them, and checks the frame is
// the one a Sky on its own device renders, that the host's device works on afterwards, and
// that destroying it reports no object the Sky left behind.
#include <atomic>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <skylayers/vulkan.h>

namespace {

std::atomic<int> gMessages{0};

VKAPI_ATTR VkBool32 VKAPI_CALL hostMessenger(VkDebugUtilsMessageSeverityFlagBitsEXT,
                                             VkDebugUtilsMessageTypeFlagsEXT,
                                             const VkDebugUtilsMessengerCallbackDataEXT* data,
                                             void*) {
  std::fprintf(stderr, "host's Vulkan validation: %s\n", data->pMessage);
  ++gMessages;
  return VK_FALSE;
}

// What a host does before it has a sky: its own instance, device and queue.
struct Host {
  VkInstance instance = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
  VkPhysicalDevice physical = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  uint32_t family = 0;

  // On the device named `name` (the one a Sky picks by itself), so the frames compare.
  explicit Host(const std::string& name) {
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "host";
    app.apiVersion = VK_API_VERSION_1_3;
    const char* layers[] = {"VK_LAYER_KHRONOS_validation"};
    const char* extensions[] = {VK_EXT_DEBUG_UTILS_EXTENSION_NAME};
    VkDebugUtilsMessengerCreateInfoEXT m{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    m.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                        VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    m.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                    VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT;
    m.pfnUserCallback = hostMessenger;
    const VkValidationFeatureEnableEXT sync =
        VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
    VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
    features.enabledValidationFeatureCount = 1;
    features.pEnabledValidationFeatures = &sync;
    features.pNext = &m;
    VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    info.pNext = &features;
    info.pApplicationInfo = &app;
    info.enabledLayerCount = 1;
    info.ppEnabledLayerNames = layers;
    info.enabledExtensionCount = 1;
    info.ppEnabledExtensionNames = extensions;
    EXPECT_EQ(vkCreateInstance(&info, nullptr, &instance), VK_SUCCESS);
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
    EXPECT_EQ(create(instance, &m, nullptr, &messenger), VK_SUCCESS);

    uint32_t count = 0;
    vkEnumeratePhysicalDevices(instance, &count, nullptr);
    std::vector<VkPhysicalDevice> devices(count);
    vkEnumeratePhysicalDevices(instance, &count, devices.data());
    physical = devices.at(0);
    for (VkPhysicalDevice p : devices) {
      VkPhysicalDeviceProperties props;
      vkGetPhysicalDeviceProperties(p, &props);
      if (name == props.deviceName) physical = p;
    }
    uint32_t n = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(physical, &n, nullptr);
    std::vector<VkQueueFamilyProperties> families(n);
    vkGetPhysicalDeviceQueueFamilyProperties(physical, &n, families.data());
    for (uint32_t i = 0; i < n; ++i)
      if (families[i].queueFlags & VK_QUEUE_COMPUTE_BIT) {
        family = i;
        break;
      }
    float priority = 1.0f;
    VkDeviceQueueCreateInfo queue{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queue.queueFamilyIndex = family;
    queue.queueCount = 1;
    queue.pQueuePriorities = &priority;
    VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    f13.synchronization2 = VK_TRUE;  // what skylayers asks of a host's device
    f13.maintenance4 = VK_TRUE;
    VkDeviceCreateInfo d{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    d.pNext = &f13;
    d.queueCreateInfoCount = 1;
    d.pQueueCreateInfos = &queue;
    EXPECT_EQ(vkCreateDevice(physical, &d, nullptr, &device), VK_SUCCESS);
  }
  ~Host() {
    if (device) vkDestroyDevice(device, nullptr);
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
    if (messenger) destroy(instance, messenger, nullptr);
    if (instance) vkDestroyInstance(instance, nullptr);
  }
};

TEST(SkylayersVulkanHost, ASkyOnTheHostsDeviceRendersTheSameFrameAndLeavesNothingBehind) {
  const std::vector<std::string> small = {"output.width=32", "output.height=18"};
  std::vector<float> ownDevice;
  std::string name;
  {
    skylayers::Sky own = skylayers::Sky::fromDefault(small);
    ownDevice = own.render().beauty.pixels;
    name = own.deviceName();
    EXPECT_EQ(own.validationMessages(), 0u);
  }
  gMessages = 0;
  {
    Host host(name);
    ASSERT_NE(host.device, VK_NULL_HANDLE);
    {
      const skylayers::VulkanDevice device{host.instance, host.physical, host.device, host.family,
                                           0};
      skylayers::DeviceOptions options;
      options.vulkan = &device;
      skylayers::Sky sky = skylayers::Sky::fromDefault(small, options);
      EXPECT_EQ(sky.render().beauty.pixels, ownDevice);
      EXPECT_EQ(sky.validationMessages(), 0u) << "the host's messenger counts, not the Sky";
      // The queries and the lights run there too.
      EXPECT_GE(sky.lighting().sun.cloudTransmittance, 0.0);
    }
    // The Sky is gone; the host's device still works, and its destruction (below) would
    // report any object the Sky made and left.
    EXPECT_EQ(vkDeviceWaitIdle(host.device), VK_SUCCESS);
  }
  EXPECT_EQ(gMessages.load(), 0) << "validation messages on the host's instance (stderr)";
}

// record()'s input errors, each one line naming what is wrong, before anything is recorded
// (examples/vulkan_host draws real frames, run by ctest as Example.VulkanHost*).
TEST(SkylayersVulkanHost, RecordRejectsWhatItCannotDrawInto) {
  const auto expectBadInput = [](skylayers::Sky& sky, const skylayers::HostFrame& frame,
                                 const std::string& says) {
    try {
      sky.record(frame);
      ADD_FAILURE() << "record() took a frame it should refuse (" << says << ")";
    } catch (const skylayers::Error& e) {
      EXPECT_EQ(e.kind(), skylayers::Error::Kind::BadInput) << e.what();
      EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "one line";
    }
  };
  std::string name;
  {
    skylayers::Sky own = skylayers::Sky::fromDefault({"output.width=32", "output.height=18"});
    name = own.deviceName();
    expectBadInput(own, {}, "DeviceOptions::vulkan");
  }
  gMessages = 0;
  Host host(name);
  ASSERT_NE(host.device, VK_NULL_HANDLE);
  {
    const skylayers::VulkanDevice device{host.instance, host.physical, host.device, host.family, 0};
    skylayers::DeviceOptions options;
    options.vulkan = &device;
    skylayers::Sky sky =
        skylayers::Sky::fromDefault({"output.width=32", "output.height=18"}, options);
    VkCommandPool pool;
    VkCommandPoolCreateInfo p{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    p.queueFamilyIndex = host.family;
    ASSERT_EQ(vkCreateCommandPool(host.device, &p, nullptr, &pool), VK_SUCCESS);
    VkCommandBuffer cmd;
    VkCommandBufferAllocateInfo a{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    a.commandPool = pool;
    a.commandBufferCount = 1;
    ASSERT_EQ(vkAllocateCommandBuffers(host.device, &a, &cmd), VK_SUCCESS);

    skylayers::HostFrame frame;
    expectBadInput(sky, frame, "commandBuffer");
    frame.commandBuffer = cmd;
    expectBadInput(sky, frame, "colour.image");
    // Handles the checks refuse before they are used.
    frame.colour = {reinterpret_cast<VkImage>(uint64_t(1)), VK_FORMAT_R8G8B8A8_UNORM,
                    VK_IMAGE_LAYOUT_GENERAL, 32, 18};
    expectBadInput(sky, frame, "R16G16B16A16_SFLOAT or R32G32B32A32_SFLOAT");
    frame.colour.format = VK_FORMAT_R16G16B16A16_SFLOAT;
    frame.depth = {reinterpret_cast<VkImage>(uint64_t(2)), VK_FORMAT_R32_SFLOAT,
                   VK_IMAGE_LAYOUT_GENERAL, 32, 18};
    expectBadInput(sky, frame, "not a depth format");
    frame.depth.format = VK_FORMAT_D32_SFLOAT;
    frame.depth.width = 64;
    expectBadInput(sky, frame, "depth is 64x18, the colour 32x18");
    frame.depth.width = 32;
    frame.depthConvention.nearM = 0.0;
    expectBadInput(sky, frame, "need 0 < near < far");
    frame.depthConvention = {};
    frame.depthConvention.useProjection = true;  // all zeros: no perspective
    expectBadInput(sky, frame, "not a perspective one");
    vkDestroyCommandPool(host.device, pool, nullptr);
  }
  EXPECT_EQ(gMessages.load(), 0) << "validation messages on the host's instance (stderr)";
}

TEST(SkylayersVulkanHost, AnIncompleteHostDeviceIsAnError) {
  skylayers::VulkanDevice none{};
  skylayers::DeviceOptions options;
  options.vulkan = &none;
  try {
    skylayers::Sky::fromDefault({}, options);
    FAIL() << "a host device without handles was taken";
  } catch (const skylayers::Error& e) {
    EXPECT_EQ(e.kind(), skylayers::Error::Kind::Internal);
    EXPECT_NE(std::string(e.what()).find("instance, physical device and device"), std::string::npos)
        << e.what();
  }
}

}  // namespace
