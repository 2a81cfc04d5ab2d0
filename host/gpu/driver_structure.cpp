#include "gpu/driver_structure.h"

#include <cstddef>
#include <stdexcept>
#include <string>

#include "core/error.h"
#include "gpu/batch_timer.h"

namespace vkray::gpu {
namespace {

using BU = vk::BufferUsageFlagBits;
using AsType = vk::AccelerationStructureTypeKHR;

// GpuTriangle's vertices as the driver reads them: p0, p1, p2 at 16-byte steps (material,
// original and the pad are the fourth words the stride skips).
static_assert(offsetof(GpuTriangle, p1) - offsetof(GpuTriangle, p0) == 16 &&
              offsetof(GpuTriangle, p2) - offsetof(GpuTriangle, p1) == 16 && sizeof(GpuTriangle) == 48);
constexpr vk::DeviceSize kVertexStride = 16;

vk::DeviceSize alignUp(vk::DeviceSize v, vk::DeviceSize a) { return a <= 1 ? v : (v + a - 1) / a * a; }

uint32_t scratchAlignment(const VulkanContext& ctx) {
    const auto props = ctx.physicalDevice()
                           .getProperties2<vk::PhysicalDeviceProperties2,
                                           vk::PhysicalDeviceAccelerationStructurePropertiesKHR>();
    return props.get<vk::PhysicalDeviceAccelerationStructurePropertiesKHR>().minAccelerationStructureScratchOffsetAlignment;
}

// One structure's storage and handle, created at the size the driver asks for.
struct Storage {
    Buffer buffer;
    vk::raii::AccelerationStructureKHR structure;
};

Storage makeStorage(const VulkanContext& ctx, vk::DeviceSize bytes, AsType type, const std::string& what) {
    Buffer buffer(ctx, bytes, BU::eAccelerationStructureStorageKHR | BU::eShaderDeviceAddress, MemoryUse::DeviceLocal,
                  what);
    vk::raii::AccelerationStructureKHR structure(
        ctx.device(), vk::AccelerationStructureCreateInfoKHR{.buffer = buffer.handle(), .size = bytes, .type = type});
    return {std::move(buffer), std::move(structure)};
}

// Builds one structure of `type` over `geometry` (`primitives` triangles or instances) in its own
// submission, timed; with `compactedSize`, also writes the size compaction would give into it.
struct Built {
    Storage storage;
    double ms = 0.0;
};
Built buildOne(const VulkanContext& ctx, AsType type, const vk::AccelerationStructureGeometryKHR& geometry,
               uint32_t primitives, vk::BuildAccelerationStructureFlagsKHR flags, const vk::raii::QueryPool* compactedSize,
               const std::string& what) {
    vk::AccelerationStructureBuildGeometryInfoKHR info{.type = type, .flags = flags,
                                                       .mode = vk::BuildAccelerationStructureModeKHR::eBuild,
                                                       .geometryCount = 1, .pGeometries = &geometry};
    const vk::AccelerationStructureBuildSizesInfoKHR sizes = ctx.device().getAccelerationStructureBuildSizesKHR(
        vk::AccelerationStructureBuildTypeKHR::eDevice, info, primitives);
    Storage storage = makeStorage(ctx, sizes.accelerationStructureSize, type, what);
    const vk::DeviceSize align = scratchAlignment(ctx);
    const Buffer scratch(ctx, sizes.buildScratchSize + align, BU::eStorageBuffer | BU::eShaderDeviceAddress,
                         MemoryUse::DeviceLocal, what + " (build scratch)");
    info.dstAccelerationStructure = *storage.structure;
    info.scratchData.deviceAddress = alignUp(scratch.address(), align);
    const vk::AccelerationStructureBuildRangeInfoKHR range{.primitiveCount = primitives};

    const BatchTimer timer(ctx);
    OneShotCommands commands(ctx);
    const vk::raii::CommandBuffer& cmd = commands.begin();
    timer.begin(cmd);
    cmd.buildAccelerationStructuresKHR(info, &range);
    if (compactedSize) {
        // The build's writes must land before its compacted size is read.
        const vk::MemoryBarrier built{.srcAccessMask = vk::AccessFlagBits::eAccelerationStructureWriteKHR,
                                      .dstAccessMask = vk::AccessFlagBits::eAccelerationStructureReadKHR};
        cmd.pipelineBarrier(vk::PipelineStageFlagBits::eAccelerationStructureBuildKHR,
                            vk::PipelineStageFlagBits::eAccelerationStructureBuildKHR, {}, built, nullptr, nullptr);
        cmd.resetQueryPool(**compactedSize, 0, 1);
        cmd.writeAccelerationStructuresPropertiesKHR(*storage.structure,
                                                     vk::QueryType::eAccelerationStructureCompactedSizeKHR,
                                                     **compactedSize, 0);
    }
    timer.end(cmd);
    commands.submitAndWait();
    return {std::move(storage), timer.enabled() ? timer.batchMs() : -1.0};
}

// The compacted copy of `from`, timed.
Built compact(const VulkanContext& ctx, const Storage& from, const vk::raii::QueryPool& compactedSize,
              const std::string& what) {
    auto [result, size] = compactedSize.getResult<vk::DeviceSize>(0, 1, sizeof(vk::DeviceSize),
                                                                  vk::QueryResultFlagBits::e64 |
                                                                      vk::QueryResultFlagBits::eWait);
    if (result != vk::Result::eSuccess || size == 0)
        throw Error("the driver of '" + ctx.info().name + "' gave no compacted size for " + what);
    Storage storage = makeStorage(ctx, size, AsType::eBottomLevel, what);
    const BatchTimer timer(ctx);
    OneShotCommands commands(ctx);
    const vk::raii::CommandBuffer& cmd = commands.begin();
    timer.begin(cmd);
    cmd.copyAccelerationStructureKHR(vk::CopyAccelerationStructureInfoKHR{
        .src = *from.structure, .dst = *storage.structure, .mode = vk::CopyAccelerationStructureModeKHR::eCompact});
    timer.end(cmd);
    commands.submitAndWait();
    return {std::move(storage), timer.enabled() ? timer.batchMs() : -1.0};
}

// Sums build times, -1 once any is unknown.
double plus(double a, double b) { return a < 0.0 || b < 0.0 ? -1.0 : a + b; }

}  // namespace

// Both structures, built.
struct DriverStructure::Parts {
    Buffer bottomBuffer;
    vk::raii::AccelerationStructureKHR bottom;
    Buffer topBuffer;
    vk::raii::AccelerationStructureKHR top;
    double buildMs = 0.0;
};

namespace {

vk::AccelerationStructureGeometryKHR triangleGeometry(const Buffer& vertices, uint32_t count) {
    return {.geometryType = vk::GeometryTypeKHR::eTriangles,
            .geometry = {.triangles = vk::AccelerationStructureGeometryTrianglesDataKHR{
                             .vertexFormat = vk::Format::eR32G32B32Sfloat,
                             .vertexData = {.deviceAddress = vertices.address()},
                             .vertexStride = kVertexStride,
                             .maxVertex = count > 0 ? 3 * count - 1 : 0,
                             .indexType = vk::IndexType::eNoneKHR}},
            .flags = vk::GeometryFlagBitsKHR::eOpaque};
}

// The bottom-level structure over the triangles, compacted when `build` asks.
Built buildBottom(const VulkanContext& ctx, std::span<const GpuTriangle> triangles, const accel::DriverBuild& build,
                  vk::BuildAccelerationStructureFlagsKHR preference) {
    const Buffer vertices = uploadBuffer(ctx, triangles.data(), triangles.size_bytes(),
                                         BU::eAccelerationStructureBuildInputReadOnlyKHR | BU::eShaderDeviceAddress,
                                         "rayquery's vertices");
    const std::string what = "rayquery's bottom-level structure";
    if (!build.compact)
        return buildOne(ctx, AsType::eBottomLevel, triangleGeometry(vertices, uint32_t(triangles.size())),
                        uint32_t(triangles.size()), preference, nullptr, what);
    const vk::raii::QueryPool compactedSize(
        ctx.device(),
        vk::QueryPoolCreateInfo{.queryType = vk::QueryType::eAccelerationStructureCompactedSizeKHR, .queryCount = 1});
    const Built full = buildOne(ctx, AsType::eBottomLevel, triangleGeometry(vertices, uint32_t(triangles.size())),
                                uint32_t(triangles.size()),
                                preference | vk::BuildAccelerationStructureFlagBitsKHR::eAllowCompaction,
                                &compactedSize, what);
    Built compacted = compact(ctx, full.storage, compactedSize, what + " (compacted)");
    compacted.ms = plus(full.ms, compacted.ms);
    return compacted;
}

// The top-level structure: one instance of `bottom`, identity transform, every ray mask bit.
Built buildTop(const VulkanContext& ctx, const Storage& bottom, vk::BuildAccelerationStructureFlagsKHR preference) {
    vk::TransformMatrixKHR identity{};
    identity.matrix[0][0] = identity.matrix[1][1] = identity.matrix[2][2] = 1.0f;
    vk::AccelerationStructureInstanceKHR instance{};
    instance.transform = identity;
    instance.mask = 0xFF;
    instance.setFlags(vk::GeometryInstanceFlagBitsKHR::eForceOpaque);
    instance.accelerationStructureReference = ctx.device().getAccelerationStructureAddressKHR(
        vk::AccelerationStructureDeviceAddressInfoKHR{.accelerationStructure = *bottom.structure});
    const Buffer instances = uploadBuffer(ctx, &instance, sizeof instance,
                                          BU::eAccelerationStructureBuildInputReadOnlyKHR | BU::eShaderDeviceAddress,
                                          "rayquery's instance");
    const vk::AccelerationStructureGeometryKHR geometry{
        .geometryType = vk::GeometryTypeKHR::eInstances,
        .geometry = {.instances = vk::AccelerationStructureGeometryInstancesDataKHR{
                         .data = {.deviceAddress = instances.address()}}},
        .flags = vk::GeometryFlagBitsKHR::eOpaque};
    return buildOne(ctx, AsType::eTopLevel, geometry, 1, preference, nullptr, "rayquery's top-level structure");
}

}  // namespace

DriverStructure::Parts DriverStructure::buildParts(const VulkanContext& ctx, std::span<const GpuTriangle> triangles,
                                                   const accel::DriverBuild& build) {
    if (!ctx.rayQueryEnabled()) throw std::logic_error("DriverStructure: the context has no ray query enabled");
    const vk::BuildAccelerationStructureFlagsKHR preference =
        build.preferFastBuild ? vk::BuildAccelerationStructureFlagBitsKHR::ePreferFastBuild
                              : vk::BuildAccelerationStructureFlagBitsKHR::ePreferFastTrace;
    Built bottom = buildBottom(ctx, triangles, build, preference);
    Built top = buildTop(ctx, bottom.storage, preference);
    return {std::move(bottom.storage.buffer), std::move(bottom.storage.structure), std::move(top.storage.buffer),
            std::move(top.storage.structure), plus(bottom.ms, top.ms)};
}

DriverStructure::DriverStructure(const VulkanContext& ctx, std::span<const GpuTriangle> triangles,
                                 const accel::DriverBuild& build)
    : DriverStructure(buildParts(ctx, triangles, build)) {}

DriverStructure::DriverStructure(Parts parts)
    : bottomBuffer_(std::move(parts.bottomBuffer)),
      bottom_(std::move(parts.bottom)),
      topBuffer_(std::move(parts.topBuffer)),
      top_(std::move(parts.top)),
      buildMs_(parts.buildMs) {}

}  // namespace vkray::gpu
