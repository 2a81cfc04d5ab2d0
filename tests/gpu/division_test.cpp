// quotient() (shaders/include/division.glsl) on the Vulkan device: the IEEE-rounded quotient, which
// the device's own division need not be (Vulkan allows 2.5 ulp, NVIDIA's driver uses it, and on
// grazing rays that moved hits: docs/stability.md, "Division on GPUs"). Lavapipe divides as IEEE
// does, so the correction step is also given quotients moved by a few ulp, as such a device's.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

#include <glm/glm.hpp>
#include <gtest/gtest.h>

#include "gpu/buffer.h"
#include "gpu/compute_kernel.h"
#include "gpu_test_util.h"
#include "quotient_test_spv.h"

namespace vkray {
namespace {

// Pairs (a, b) over 2^-20 .. 2^20 in magnitude, both signs, random significands; the shapes the
// kernels divide: 1 / b (the shear's and the triangle test's) and pixel offsets over half a width;
// and quotients within rounding of the midpoint between two floats, which random pairs almost never
// give: 1 / (2^k (1 - j 2^-24)) = 2^-k (1 + j 2^-24 + j^2 2^-48 + ...) lies j^2 2^-48 above a
// midpoint for odd j (1 / (4 - 2^-22), j = 1, is a triangle test's 1 / det in
// scenes/stress/coplanar.scene).
std::vector<glm::vec4> testPairs() {
    std::mt19937 rng(20261126);
    std::uniform_real_distribution<float> significand(1.0f, 2.0f);
    std::uniform_int_distribution<int> exponent(-20, 20), sign(0, 1);
    const auto number = [&] { return (sign(rng) ? -1.0f : 1.0f) * std::ldexp(significand(rng), exponent(rng)); };
    std::vector<glm::vec4> pairs;
    for (int i = 0; i < 60000; ++i) pairs.emplace_back(number(), number(), 0.0f, 0.0f);
    for (int i = 0; i < 4000; ++i) pairs.emplace_back(1.0f, number(), 0.0f, 0.0f);
    for (int x = 0; x < 1536; ++x) pairs.emplace_back(float(x) + 0.5f - 767.0f, 767.0f, 0.0f, 0.0f);
    for (int k = -20; k <= 20; ++k)
        for (int j = 1; j < 64; j += 2) {
            const float b = std::ldexp(1.0f - float(j) * 0x1p-24f, k);
            pairs.emplace_back(1.0f, b, 0.0f, 0.0f);
            pairs.emplace_back(-1.0f, b, 0.0f, 0.0f);
        }
    return pairs;
}

TEST(Division, QuotientIsTheIeeeQuotientOnTheDevice) {
    const auto& ctx = test::gpuContext();
    std::vector<glm::vec4> pairs = testPairs();
    const uint32_t n = uint32_t(pairs.size());
    const vk::DeviceSize bytes = pairs.size() * sizeof(glm::vec4);
    gpu::Buffer buffer(ctx, bytes, vk::BufferUsageFlagBits::eStorageBuffer, gpu::MemoryUse::Readback, "test pairs");
    std::memcpy(buffer.mapped(), pairs.data(), bytes);

    const gpu::ComputeKernel::Binding binding{vk::DescriptorType::eStorageBuffer, 1};
    gpu::ComputeKernel kernel(ctx, quotient_test_spv, {&binding, 1}, sizeof(n), gpu::Specialization{});
    kernel.bind({{gpu::ComputeKernel::Resource{.buffer = buffer.handle()}}});
    gpu::OneShotCommands commands(ctx);
    const vk::raii::CommandBuffer& cmd = commands.begin();
    kernel.dispatch(cmd, &n, (n + 63) / 64, 1);
    const vk::MemoryBarrier toHost{.srcAccessMask = vk::AccessFlagBits::eShaderWrite,
                                   .dstAccessMask = vk::AccessFlagBits::eHostRead};
    cmd.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader, vk::PipelineStageFlagBits::eHost, {}, toHost,
                        nullptr, nullptr);
    commands.submitAndWait();
    std::vector<glm::vec4> results(pairs.size());
    std::memcpy(results.data(), buffer.mapped(), bytes);

    // Each result against the host's division, which is IEEE 754's (correctly rounded).
    size_t wrong[4] = {0, 0, 0, 0};
    const char* what[4] = {"quotient(a, b)", "from q - 2 ulp", "from q + 1 ulp", "from q + 2 ulp"};
    for (size_t i = 0; i < pairs.size(); ++i) {
        const float a = pairs[i].x, b = pairs[i].y, ieee = a / b;
        for (int k = 0; k < 4; ++k)
            if (results[i][k] != ieee && ++wrong[k] <= 3)
                ADD_FAILURE() << what[k] << ": " << a << " / " << b << " gave " << results[i][k] << ", IEEE " << ieee;
    }
    for (int k = 0; k < 4; ++k) EXPECT_EQ(wrong[k], 0u) << what[k] << ", of " << n;
}

}  // namespace
}  // namespace vkray
