#include "gpu/vulkan_context.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string_view>

#include "core/error.h"
#include "gpu/loop_budget.h"
#include "shared/gpu_layout.h"

namespace vkray::gpu {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

std::string versionString(uint32_t v) {
    return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) +
           "." + std::to_string(VK_API_VERSION_PATCH(v));
}

std::string typeName(vk::PhysicalDeviceType t) {
    switch (t) {
        case vk::PhysicalDeviceType::eDiscreteGpu: return "discrete";
        case vk::PhysicalDeviceType::eIntegratedGpu: return "integrated";
        case vk::PhysicalDeviceType::eVirtualGpu: return "virtual";
        case vk::PhysicalDeviceType::eCpu: return "cpu";
        default: return "other";
    }
}

// Default choice order: a real GPU before a software rasterizer.
int typeRank(vk::PhysicalDeviceType t) {
    switch (t) {
        case vk::PhysicalDeviceType::eDiscreteGpu: return 0;
        case vk::PhysicalDeviceType::eIntegratedGpu: return 1;
        case vk::PhysicalDeviceType::eVirtualGpu: return 2;
        case vk::PhysicalDeviceType::eCpu: return 3;
        default: return 4;
    }
}

std::optional<uint32_t> computeQueueFamily(const vk::raii::PhysicalDevice& pd) {
    auto families = pd.getQueueFamilyProperties();
    // Prefer a compute-only family (async compute on discrete GPUs), else any with compute.
    for (uint32_t i = 0; i < families.size(); ++i)
        if ((families[i].queueFlags & vk::QueueFlagBits::eCompute) &&
            !(families[i].queueFlags & vk::QueueFlagBits::eGraphics))
            return i;
    for (uint32_t i = 0; i < families.size(); ++i)
        if (families[i].queueFlags & vk::QueueFlagBits::eCompute) return i;
    return std::nullopt;
}

bool hasExtension(const std::vector<vk::ExtensionProperties>& extensions, const char* name) {
    return std::any_of(extensions.begin(), extensions.end(),
                       [&](const vk::ExtensionProperties& e) { return std::strcmp(e.extensionName.data(), name) == 0; });
}

// The extensions `--accel rayquery` needs (VK_KHR_acceleration_structure requires deferred host
// operations to be enabled with it, though vkray builds on the device).
constexpr std::array kRayQueryExtensions{VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME, VK_KHR_RAY_QUERY_EXTENSION_NAME,
                                         VK_KHR_DEFERRED_HOST_OPERATIONS_EXTENSION_NAME};

using RayQueryFeatures = vk::StructureChain<vk::PhysicalDeviceFeatures2, vk::PhysicalDeviceVulkan12Features,
                                            vk::PhysicalDeviceAccelerationStructureFeaturesKHR,
                                            vk::PhysicalDeviceRayQueryFeaturesKHR>;

bool supportsRayQuery(const vk::raii::PhysicalDevice& pd) {
    if (pd.getProperties().apiVersion < VK_API_VERSION_1_2) return false;
    const auto extensions = pd.enumerateDeviceExtensionProperties();
    for (const char* name : kRayQueryExtensions)
        if (!hasExtension(extensions, name)) return false;
    const RayQueryFeatures features = pd.getFeatures2<vk::PhysicalDeviceFeatures2, vk::PhysicalDeviceVulkan12Features,
                                                      vk::PhysicalDeviceAccelerationStructureFeaturesKHR,
                                                      vk::PhysicalDeviceRayQueryFeaturesKHR>();
    return features.get<vk::PhysicalDeviceVulkan12Features>().bufferDeviceAddress &&
           features.get<vk::PhysicalDeviceAccelerationStructureFeaturesKHR>().accelerationStructure &&
           features.get<vk::PhysicalDeviceRayQueryFeaturesKHR>().rayQuery;
}

DeviceInfo describe(const vk::raii::PhysicalDevice& pd, uint32_t index) {
    DeviceInfo d;
    d.index = index;
    auto chain = pd.getProperties2<vk::PhysicalDeviceProperties2, vk::PhysicalDeviceDriverProperties,
                                   vk::PhysicalDeviceSubgroupProperties>();
    const auto& props = chain.get<vk::PhysicalDeviceProperties2>().properties;
    const auto& drv = chain.get<vk::PhysicalDeviceDriverProperties>();
    const auto& subgroups = chain.get<vk::PhysicalDeviceSubgroupProperties>();
    d.subgroupSize = subgroups.subgroupSize;
    d.subgroupOps = (subgroups.supportedOperations & vk::SubgroupFeatureFlagBits::eVote) &&
                    (subgroups.supportedOperations & vk::SubgroupFeatureFlagBits::eArithmetic) &&
                    (subgroups.supportedStages & vk::ShaderStageFlagBits::eCompute);
    d.subgroupBallot = d.subgroupOps && (subgroups.supportedOperations & vk::SubgroupFeatureFlagBits::eBallot);
    d.name = props.deviceName.data();
    d.type = typeName(props.deviceType);
    d.driver = std::string(drv.driverName.data());
    if (drv.driverInfo[0] != '\0') d.driver += " / " + std::string(drv.driverInfo.data());
    d.apiVersion = versionString(props.apiVersion);
    d.pixelsPerInvocation = props.deviceType == vk::PhysicalDeviceType::eCpu ? VKRAY_MAX_PIXELS_PER_INVOCATION : 1;
    d.maxStorageBufferRange = props.limits.maxStorageBufferRange;
    d.maxTexelBufferElements = props.limits.maxTexelBufferElements;
    d.timestampPeriodNs = props.limits.timestampPeriod;
    // VK_EXT_memory_budget: what of each heap this process may still allocate (other processes use
    // the rest); its properties may be queried wherever the device has the extension.
    const bool budget = hasExtension(pd.enumerateDeviceExtensionProperties(), VK_EXT_MEMORY_BUDGET_EXTENSION_NAME);
    vk::PhysicalDeviceMemoryProperties mem;
    vk::PhysicalDeviceMemoryBudgetPropertiesEXT budgets;
    if (budget) {
        const auto props = pd.getMemoryProperties2<vk::PhysicalDeviceMemoryProperties2,
                                                   vk::PhysicalDeviceMemoryBudgetPropertiesEXT>();
        mem = props.get<vk::PhysicalDeviceMemoryProperties2>().memoryProperties;
        budgets = props.get<vk::PhysicalDeviceMemoryBudgetPropertiesEXT>();
    } else {
        mem = pd.getMemoryProperties();
    }
    for (uint32_t h = 0; h < mem.memoryHeapCount; ++h) {
        const vk::MemoryHeap& heap = mem.memoryHeaps[h];
        if (!(heap.flags & vk::MemoryHeapFlagBits::eDeviceLocal) || heap.size <= d.deviceLocalBytes) continue;
        d.deviceLocalBytes = heap.size;
        d.deviceLocalBudget = budget && budgets.heapBudget[h] > 0 ? std::min<uint64_t>(budgets.heapBudget[h], heap.size)
                                                                 : heap.size;
    }
    d.hasCompute = computeQueueFamily(pd).has_value();
    d.rayQuery = supportsRayQuery(pd);
    return d;
}

bool layerAvailable(const vk::raii::Context& ctx, const char* name) {
    for (const auto& l : ctx.enumerateInstanceLayerProperties())
        if (std::strcmp(l.layerName.data(), name) == 0) return true;
    return false;
}

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
    return s;
}

vk::raii::Instance createInstance(const vk::raii::Context& ctx, bool validation) {
    std::vector<const char*> layers, extensions;
    if (validation) {
        if (!layerAvailable(ctx, kValidationLayer))
            throw Error(std::string("validation was requested (VKRAY_VALIDATION=1) but ") +
                        kValidationLayer + " is not installed (Debian package vulkan-validationlayers)");
        layers.push_back(kValidationLayer);
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    }
    vk::ApplicationInfo app{.pApplicationName = "vkray",
                            .applicationVersion = VK_MAKE_API_VERSION(0, 0, 1, 0),
                            .pEngineName = "vkray",
                            .engineVersion = VK_MAKE_API_VERSION(0, 0, 1, 0),
                            .apiVersion = VK_API_VERSION_1_2};
    vk::InstanceCreateInfo info{.pApplicationInfo = &app,
                                .enabledLayerCount = uint32_t(layers.size()),
                                .ppEnabledLayerNames = layers.data(),
                                .enabledExtensionCount = uint32_t(extensions.size()),
                                .ppEnabledExtensionNames = extensions.data()};
    try {
        return vk::raii::Instance(ctx, info);
    } catch (const vk::SystemError& e) {
        throw Error(std::string("cannot create a Vulkan instance (is a Vulkan driver installed? "
                                "Debian: mesa-vulkan-drivers): ") + e.what());
    }
}

vk::raii::Context loadVulkan() {
    try {
        return vk::raii::Context();
    } catch (const std::exception& e) {
        throw Error(std::string("cannot load the Vulkan loader (Debian package libvulkan1): ") + e.what());
    }
}

}  // namespace

bool validationRequestedByEnvironment() {
    const char* v = std::getenv("VKRAY_VALIDATION");
    return v && std::string_view(v) != "" && std::string_view(v) != "0";
}

struct VulkanContext::Messenger {
    std::atomic<uint32_t> errors{0};

    static VKAPI_ATTR VkBool32 VKAPI_CALL callback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                   VkDebugUtilsMessageTypeFlagsEXT,
                                                   const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                   void* user) {
        auto* self = static_cast<Messenger*>(user);
        if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) {
            self->errors.fetch_add(1);
            std::fprintf(stderr, "vulkan validation error: %s\n", data->pMessage);
        } else if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) {
            std::fprintf(stderr, "vulkan validation warning: %s\n", data->pMessage);
        }
        return VK_FALSE;
    }
};

std::vector<DeviceInfo> VulkanContext::listDevices(bool validation) {
    vk::raii::Context ctx = loadVulkan();
    vk::raii::Instance instance = createInstance(ctx, validation);
    vk::raii::PhysicalDevices devices(instance);
    std::vector<DeviceInfo> out;
    for (uint32_t i = 0; i < devices.size(); ++i) out.push_back(describe(devices[i], i));
    return out;
}

VulkanContext::VulkanContext(const ContextOptions& options)
    : context_(loadVulkan()), messengerState_(std::make_unique<Messenger>()) {
    instance_ = createInstance(context_, options.validation);
    if (options.validation) {
        vk::DebugUtilsMessengerCreateInfoEXT info{
            .messageSeverity = vk::DebugUtilsMessageSeverityFlagBitsEXT::eWarning |
                               vk::DebugUtilsMessageSeverityFlagBitsEXT::eError,
            .messageType = vk::DebugUtilsMessageTypeFlagBitsEXT::eGeneral |
                           vk::DebugUtilsMessageTypeFlagBitsEXT::eValidation,
            .pfnUserCallback = &Messenger::callback,
            .pUserData = messengerState_.get()};
        messenger_ = vk::raii::DebugUtilsMessengerEXT(instance_, info);
    }

    vk::raii::PhysicalDevices devices(instance_);
    if (devices.empty())
        throw Error("no Vulkan device found (for the CPU driver lavapipe install mesa-vulkan-drivers)");
    std::vector<DeviceInfo> infos;
    for (uint32_t i = 0; i < devices.size(); ++i) infos.push_back(describe(devices[i], i));

    std::optional<uint32_t> chosen;
    const std::string& want = options.device;
    if (want.empty()) {
        int bestRank = 1 << 30;
        for (uint32_t i = 0; i < devices.size(); ++i) {
            int rank = typeRank(devices[i].getProperties().deviceType);
            if (infos[i].hasCompute && infos[i].subgroupOps && rank < bestRank) bestRank = rank, chosen = i;
        }
    } else if (std::all_of(want.begin(), want.end(), [](unsigned char c) { return std::isdigit(c); })) {
        uint32_t idx = uint32_t(std::min<unsigned long>(std::stoul(want), 1ul << 30));
        if (idx >= devices.size())
            throw Error("--device " + want + ": " +
                        (devices.size() == 1 ? std::string("there is only one Vulkan device, 0")
                                             : "there are only " + std::to_string(devices.size()) + " Vulkan devices, 0-" +
                                                   std::to_string(devices.size() - 1)) +
                        " (see `vkray devices`)");
        chosen = idx;
    } else {
        for (uint32_t i = 0; i < devices.size() && !chosen; ++i)
            if (lower(infos[i].name).find(lower(want)) != std::string::npos) chosen = i;
        if (!chosen) throw Error("--device " + want + ": no Vulkan device name contains it (see `vkray devices`)");
    }
    if (!chosen) throw Error("no Vulkan device with a compute queue and subgroup vote and arithmetic operations");
    if (!infos[*chosen].hasCompute)
        throw Error("Vulkan device '" + infos[*chosen].name + "' has no compute queue");
    if (!infos[*chosen].subgroupOps)
        throw Error("Vulkan device '" + infos[*chosen].name +
                    "' lacks subgroup vote or arithmetic operations in compute shaders, which vkray's kernels use");

    physical_ = std::move(devices[*chosen]);
    info_ = infos[*chosen];
    if (options.maxTexelsPerView > 0)
        info_.maxTexelBufferElements = std::min<uint64_t>(info_.maxTexelBufferElements, options.maxTexelsPerView);
    if (options.pixelsPerInvocation > 0)
        info_.pixelsPerInvocation = std::min<uint32_t>(options.pixelsPerInvocation, VKRAY_MAX_PIXELS_PER_INVOCATION);
    limits_ = physical_.getProperties().limits;
    queueFamily_ = *computeQueueFamily(physical_);
    timestampValidBits_ = physical_.getQueueFamilyProperties()[queueFamily_].timestampValidBits;

    float priority = 1.0f;
    vk::DeviceQueueCreateInfo queueInfo{.queueFamilyIndex = queueFamily_, .queueCount = 1,
                                        .pQueuePriorities = &priority};
    vk::DeviceCreateInfo deviceInfo{.queueCreateInfoCount = 1, .pQueueCreateInfos = &queueInfo};
    // Only what a render asks for is enabled: the other kernels run on the device as without it.
    RayQueryFeatures rayQuery;
    if (options.rayQuery) {
        if (!info_.rayQuery)
            throw Error("Vulkan device '" + info_.name + "' (" + info_.driver + ", Vulkan " + info_.apiVersion +
                        ") has no VK_KHR_ray_query with acceleration structures, which --accel rayquery needs "
                        "(`vkray devices` says which devices have it)");
        rayQuery.get<vk::PhysicalDeviceVulkan12Features>().bufferDeviceAddress = true;
        rayQuery.get<vk::PhysicalDeviceAccelerationStructureFeaturesKHR>().accelerationStructure = true;
        rayQuery.get<vk::PhysicalDeviceRayQueryFeaturesKHR>().rayQuery = true;
        deviceInfo.pNext = &rayQuery.get<vk::PhysicalDeviceFeatures2>();
        deviceInfo.enabledExtensionCount = uint32_t(kRayQueryExtensions.size());
        deviceInfo.ppEnabledExtensionNames = kRayQueryExtensions.data();
        rayQueryEnabled_ = true;
    }
    device_ = vk::raii::Device(physical_, deviceInfo);
    queue_ = vk::raii::Queue(device_, queueFamily_, 0);
    resumableFromStart_ = options.resumableFromStart;
    driver_ = physical_.getProperties2<vk::PhysicalDeviceProperties2, vk::PhysicalDeviceDriverProperties>()
                  .get<vk::PhysicalDeviceDriverProperties>()
                  .driverID;
}

bool VulkanContext::loopBudget() const {
    std::call_once(loopBudgetProbed_, [this] { loopBudget_ = endsLongLoops(*this, driver_); });
    return loopBudget_;
}

VulkanContext::~VulkanContext() {
    if (*device_) device_.waitIdle();
}

uint32_t VulkanContext::findMemoryType(uint32_t typeBits, vk::MemoryPropertyFlags required,
                                       vk::MemoryPropertyFlags preferred) const {
    auto mem = physical_.getMemoryProperties();
    std::optional<uint32_t> fallback;
    for (uint32_t i = 0; i < mem.memoryTypeCount; ++i) {
        if (!(typeBits & (1u << i))) continue;
        auto flags = mem.memoryTypes[i].propertyFlags;
        if ((flags & required) != required) continue;
        if ((flags & preferred) == preferred) return i;
        if (!fallback) fallback = i;
    }
    if (!fallback) throw Error("Vulkan device '" + info_.name + "' has no suitable memory type");
    return *fallback;
}

void VulkanContext::checkValidation() const {
    uint32_t n = messengerState_->errors.load();
    if (n > 0)
        throw Error("the Vulkan validation layer reported " + std::to_string(n) +
                    " error(s) (printed above)");
}

}  // namespace vkray::gpu
