// `vkray devices`: what the Vulkan loader sees.
#include <cstdio>

#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "gpu/driver_filter.h"
#include "gpu/vulkan_context.h"

namespace vkray::cli {

void registerDevicesCommand(CLI::App& app, int& exitCode) {
    auto* cmd = app.add_subcommand("devices", "List the Vulkan devices the loader sees");
    auto json = std::make_shared<bool>(false);
    cmd->add_flag("--json", *json, "Print JSON");
    cmd->callback([json, &exitCode] {
        const auto devices = gpu::VulkanContext::listDevices(gpu::validationRequestedByEnvironment());
        if (*json) {
            nlohmann::json out = nlohmann::json::array();
            for (const auto& d : devices)
                out.push_back({{"index", d.index}, {"name", d.name}, {"type", d.type},
                               {"driver", d.driver}, {"api_version", d.apiVersion},
                               {"max_storage_buffer_range", d.maxStorageBufferRange},
                               {"device_local_bytes", d.deviceLocalBytes},
                               {"timestamp_period_ns", d.timestampPeriodNs},
                               {"subgroup_size", d.subgroupSize},
                               {"compute", d.hasCompute},
                               {"ray_query", d.rayQuery}});
            std::printf("%s\n", out.dump(2).c_str());
        } else {
            if (devices.empty()) std::printf("no Vulkan devices\n");
            for (const auto& d : devices)
                std::printf("%u: %s\n   type %s, driver %s, Vulkan %s, maxStorageBufferRange %llu MiB, subgroups of %u, "
                            "%s%s\n",
                            d.index, d.name.c_str(), d.type.c_str(), d.driver.c_str(), d.apiVersion.c_str(),
                            (unsigned long long)(d.maxStorageBufferRange >> 20), d.subgroupSize,
                            d.rayQuery ? "ray query (--accel rayquery)" : "no ray query",
                            d.hasCompute ? "" : ", no compute queue");
            if (const auto skipped = gpu::skippedDrivers())
                std::printf("(not loaded, no DRM render node in /dev/dri: %s; VK_LOADER_DRIVERS_DISABLE= loads them)\n",
                            skipped->c_str());
        }
        exitCode = 0;
    });
}

}  // namespace vkray::cli
