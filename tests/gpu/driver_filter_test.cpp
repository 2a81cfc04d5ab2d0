// Which Vulkan drivers vkray asks the loader to skip: only Mesa's DRM-only drivers, only without a
// render node, never against the user's own choice of drivers.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include "gpu/driver_filter.h"
#include "gpu/vulkan_context.h"

namespace vkray {
namespace {

gpu::EnvironmentLookup environment(const std::map<std::string, std::string>& vars) {
    return [vars](const char* name) -> const char* {
        const auto it = vars.find(name);
        return it == vars.end() ? nullptr : it->second.c_str();
    };
}

TEST(DriverFilter, SkipsTheDrmOnlyDriversWithoutARenderNode) {
    const auto skip = gpu::driversWithoutDevices(environment({{"HOME", "/root"}}), false);
    ASSERT_TRUE(skip.has_value());
    for (const char* driver : {"intel_icd.*", "intel_hasvk_icd.*", "radeon_icd.*"})
        EXPECT_NE(skip->find(driver), std::string::npos) << driver;
    // Drivers that find devices without DRM stay: lavapipe, and any vendor's own.
    for (const char* driver : {"lvp", "nvidia", "amd_icd", "dzn"}) EXPECT_EQ(skip->find(driver), std::string::npos) << driver;
}

TEST(DriverFilter, KeepsEveryDriverWhereARenderNodeExists) {
    EXPECT_FALSE(gpu::driversWithoutDevices(environment({}), true).has_value());
}

TEST(DriverFilter, LeavesTheUsersChoiceOfDrivers) {
    for (const char* name : {"VK_ICD_FILENAMES", "VK_DRIVER_FILES", "VK_ADD_DRIVER_FILES", "VK_LOADER_DRIVERS_SELECT",
                             "VK_LOADER_DRIVERS_DISABLE", "RADV_FORCE_FAMILY"}) {
        EXPECT_FALSE(gpu::driversWithoutDevices(environment({{name, "x"}}), false).has_value()) << name;
        // Set but empty is a choice too: the way to keep vkray from skipping anything.
        EXPECT_FALSE(gpu::driversWithoutDevices(environment({{name, ""}}), false).has_value()) << name;
    }
}

TEST(DriverFilter, FindsRenderNodesByName) {
    const std::filesystem::path dri = std::filesystem::path(VKRAY_TEST_OUTPUT_DIR) / "driver-filter-dri";
    std::filesystem::remove_all(dri);
    EXPECT_FALSE(gpu::hasRenderNode(dri));  // no folder
    std::filesystem::create_directories(dri);
    std::ofstream(dri / "card0").put('\n');
    EXPECT_FALSE(gpu::hasRenderNode(dri));  // a primary node alone
    std::ofstream(dri / "renderD128").put('\n');
    EXPECT_TRUE(gpu::hasRenderNode(dri));
    std::filesystem::remove_all(dri);
}

// With the filter applied, the loader still lists the devices it listed without it.
TEST(DriverFilter, TheLoaderListsTheSameDevices) {
    const auto before = gpu::VulkanContext::listDevices(false);
    gpu::skipDriversWithoutDevices();  // what vkray's main() does first
    if (!gpu::skippedDrivers()) GTEST_SKIP() << "this machine keeps every driver (a render node, or drivers chosen by the environment)";
    const auto after = gpu::VulkanContext::listDevices(false);
    unsetenv("VK_LOADER_DRIVERS_DISABLE");  // it was unset: nothing would have been skipped otherwise
    ASSERT_EQ(after.size(), before.size());
    for (size_t i = 0; i < before.size(); ++i) {
        EXPECT_EQ(after[i].name, before[i].name);
        EXPECT_EQ(after[i].driver, before[i].driver);
    }
}

}  // namespace
}  // namespace vkray
