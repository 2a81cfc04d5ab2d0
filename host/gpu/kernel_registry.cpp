#include "gpu/kernel_registry.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "core/error.h"
#include "render_kernels.h"  // generated at build time from shaders/render_*.comp

namespace vkray::gpu {
namespace {

// A registry name ("kd_restart") against a traversal's name ("kd-restart").
constexpr bool namesKernelOf(std::string_view kernel, std::string_view traversal) {
    if (kernel.size() != traversal.size()) return false;
    for (size_t i = 0; i < kernel.size(); ++i)
        if (kernel[i] != (traversal[i] == '-' ? '_' : traversal[i])) return false;
    return true;
}

// The position of a traversal's kernel in the generated registry, -1 when it has none. An index
// rather than a pointer: comparing the address of a global with null is not a constant expression
// under AddressSanitizer.
constexpr int kernelIndex(accel::Traversal traversal) {
    for (size_t i = 0; i < std::size(generated::kRenderKernels); ++i)
        if (namesKernelOf(generated::kRenderKernels[i].name, accel::traversalName(traversal))) return int(i);
    return -1;
}

// Every accel::Traversal must have its shaders/render_<name>.comp, or the build fails here.
constexpr bool everyTraversalHasKernel() {
    for (accel::Traversal t : accel::kTraversals)
        if (kernelIndex(t) < 0) return false;
    return true;
}
static_assert(everyTraversalHasKernel(), "an accel::Traversal has no shaders/render_<kernel>.comp");

}  // namespace

std::string_view kernelName(accel::Traversal traversal) {
    return generated::kRenderKernels[kernelIndex(traversal)].name;
}

std::span<const uint32_t> builtInKernel(accel::Traversal traversal, KernelVariant variant) {
    return generated::kRenderKernels[kernelIndex(traversal)].variants[variant.index()];
}

std::vector<uint32_t> kernelFromDir(accel::Traversal traversal, KernelVariant variant) {
    const char* dir = std::getenv("VKRAY_KERNEL_DIR");
    if (!dir || !*dir) return {};
    const std::string suffix = std::string(variant.resumable ? "_resumable" : "") + (variant.splitViews ? "_split" : "");
    const std::filesystem::path file =
        std::filesystem::path(dir) / ("render_" + std::string(kernelName(traversal)) + suffix + ".spv");
    std::ifstream in(file, std::ios::binary | std::ios::ate);
    if (!in) throw Error("VKRAY_KERNEL_DIR: cannot open " + file.string());
    const std::streamsize size = in.tellg();
    if (size <= 0 || size % 4 != 0)
        throw Error("VKRAY_KERNEL_DIR: " + file.string() + " is not SPIR-V (size " + std::to_string(size) + ")");
    std::vector<uint32_t> code(size_t(size) / 4);
    in.seekg(0);
    if (!in.read(reinterpret_cast<char*>(code.data()), size) || code[0] != 0x07230203u)
        throw Error("VKRAY_KERNEL_DIR: " + file.string() + " is not SPIR-V");
    std::fprintf(stderr, "vkray: kernel %s from %s\n", std::string(kernelName(traversal)).c_str(),
                 file.c_str());
    return code;
}

}  // namespace vkray::gpu
