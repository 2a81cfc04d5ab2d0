// Morton codes, the radix sort and the AAC reduction function against direct definitions.
#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "accel/bvh/aac_builder.h"
#include "accel/bvh/morton.h"

namespace vkray::bvh {
namespace {

// Bit-by-bit interleave, the definition expandBits' multiply-and-mask trick must reproduce.
uint32_t interleaveSlowly(uint32_t x, uint32_t y, uint32_t z) {
    uint32_t code = 0;
    for (int i = 0; i < kMortonBitsPerAxis; ++i) {
        code |= ((x >> i) & 1u) << (3 * i + 2);
        code |= ((y >> i) & 1u) << (3 * i + 1);
        code |= ((z >> i) & 1u) << (3 * i);
    }
    return code;
}

TEST(Morton, ExpandBitsSpreadsEveryBit) {
    for (uint32_t v = 0; v < 1024; ++v) EXPECT_EQ(expandBits(v), interleaveSlowly(0, 0, v)) << v;
}

TEST(Morton, CodesInterleaveXYZWithinTheBounds) {
    Aabb bounds;
    bounds.grow(glm::vec3(-2.0f, 0.0f, 10.0f));
    bounds.grow(glm::vec3(2.0f, 4.0f, 10.0f));  // zero extent in z: every z maps to cell 0
    EXPECT_EQ(mortonCode(bounds.lo, bounds), 0u);
    EXPECT_EQ(mortonCode(bounds.hi, bounds), interleaveSlowly(1023, 1023, 0));
    // The centre falls in cell 512 of x and y.
    EXPECT_EQ(mortonCode({0.0f, 2.0f, 10.0f}, bounds), interleaveSlowly(512, 512, 0));
    // Outside the bounds clamps rather than wraps.
    EXPECT_EQ(mortonCode({-5.0f, 9.0f, 10.0f}, bounds), interleaveSlowly(0, 1023, 0));
}

TEST(Morton, RadixSortEqualsStableSortAcrossBlocks) {
    std::mt19937 rng(5);
    // Sizes around the 65536-key block of the parallel passes; few distinct codes so that equal
    // codes must keep their order.
    for (size_t n : {size_t(0), size_t(1), size_t(1000), size_t(65536), size_t(200003)}) {
        std::uniform_int_distribution<uint32_t> code(0, n > 1000 ? (1u << kMortonBits) - 1 : 7u);
        BuildArray<MortonKey> keys(n);
        for (size_t i = 0; i < n; ++i) keys[i] = (MortonKey(code(rng)) << 32) | i;
        std::vector<MortonKey> expected(keys.begin(), keys.end());
        std::stable_sort(expected.begin(), expected.end(),
                         [](MortonKey a, MortonKey b) { return keyCode(a) < keyCode(b); });
        radixSortByCode(keys);
        EXPECT_EQ(std::vector<MortonKey>(keys.begin(), keys.end()), expected) << n << " keys";
    }
}

TEST(AacReduction, HalvesDeltaAndGrowsAsThePaperSays) {
    // f(delta) = delta / 2 for the paper's presets (c was chosen for that).
    EXPECT_EQ(aacReduction(4, 4, 0.2), 2u);
    EXPECT_EQ(aacReduction(20, 20, 0.1), 10u);
    // f(n) = delta^(1/2 + eps) / 2 * n^(1/2 - eps), rounded down: AAC-HQ at one million.
    EXPECT_EQ(aacReduction(1000000, 20, 0.1), size_t(std::pow(20.0, 0.6) / 2.0 * std::pow(1e6, 0.4)));
    // Never below one cluster.
    EXPECT_EQ(aacReduction(1, 4, 0.2), 1u);
    EXPECT_LT(aacReduction(1000000, 4, 0.2), aacReduction(1000000, 20, 0.1));
}

TEST(AacConfig, RejectsParametersOutsideThePapersRange) {
    EXPECT_THROW(validateAacConfig(Config::withAac(0, 0.2)), std::exception);
    EXPECT_THROW(validateAacConfig(Config::withAac(4, 0.5)), std::exception);
    EXPECT_THROW(validateAacConfig(Config::withAac(4, -0.1)), std::exception);
    EXPECT_NO_THROW(validateAacConfig(Config::withAac(1, 0.0)));
}

}  // namespace
}  // namespace vkray::bvh
