#include "gpu/driver_filter.h"

#include <cstdlib>
#include <system_error>

namespace vkray::gpu {
namespace {

// Settings by which a user picks the loader's drivers; any of them set leaves the choice to them.
constexpr const char* kUserDriverChoice[] = {"VK_ICD_FILENAMES", "VK_DRIVER_FILES", "VK_ADD_DRIVER_FILES",
                                             "VK_LOADER_DRIVERS_SELECT", "VK_LOADER_DRIVERS_DISABLE"};

// Manifest file names (globs on the name, as the loader matches them) of Mesa's drivers that look
// for devices among the DRM render nodes alone.
constexpr const char* kDrmOnlyDrivers = "intel_icd.*,intel_hasvk_icd.*,radeon_icd.*,nouveau_icd.*,virtio_icd.*";

std::optional<std::string> gSkipped;  // set once, before any thread starts

}  // namespace

std::optional<std::string> driversWithoutDevices(const EnvironmentLookup& env, bool renderNodes) {
    if (renderNodes) return std::nullopt;
    for (const char* name : kUserDriverChoice)
        if (env(name)) return std::nullopt;
    if (env("RADV_FORCE_FAMILY")) return std::nullopt;  // radv's device without hardware
    return std::string(kDrmOnlyDrivers);
}

bool hasRenderNode(const std::filesystem::path& dri) {
    std::error_code ec;
    for (std::filesystem::directory_iterator it(dri, ec), end; !ec && it != end; it.increment(ec))
        if (it->path().filename().string().starts_with("renderD")) return true;
    return false;  // no such folder, or unreadable: the drivers could not open a node either
}

void skipDriversWithoutDevices() {
    const auto skip = driversWithoutDevices([](const char* name) { return std::getenv(name); }, hasRenderNode());
    if (skip && setenv("VK_LOADER_DRIVERS_DISABLE", skip->c_str(), 0) == 0) gSkipped = skip;
}

std::optional<std::string> skippedDrivers() { return gSkipped; }

}  // namespace vkray::gpu
