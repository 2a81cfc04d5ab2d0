#include "core/hash64.h"

#include <algorithm>
#include <bit>
#include <cstring>

namespace vkray {
namespace {

constexpr uint64_t kP1 = 0x9E3779B185EBCA87ull;
constexpr uint64_t kP2 = 0xC2B2AE3D27D4EB4Full;
constexpr uint64_t kP3 = 0x165667B19E3779F9ull;
constexpr uint64_t kP4 = 0x85EBCA77C2B2AE63ull;
constexpr uint64_t kP5 = 0x27D4EB2F165667C5ull;

// Little-endian reads, as the reference defines the hash (and as vkray's files are written).
static_assert(std::endian::native == std::endian::little, "vkray assumes a little-endian host");

uint64_t read64(const unsigned char* p) {
    uint64_t v;
    std::memcpy(&v, p, 8);
    return v;
}

uint32_t read32(const unsigned char* p) {
    uint32_t v;
    std::memcpy(&v, p, 4);
    return v;
}

uint64_t round64(uint64_t acc, uint64_t lane) {
    acc += lane * kP2;
    return std::rotl(acc, 31) * kP1;
}

uint64_t mergeRound(uint64_t h, uint64_t acc) {
    h ^= round64(0, acc);
    return h * kP1 + kP4;
}

// Four independent lanes over 32-byte stripes: the multiplies of one stripe overlap.
void consumeStripes(uint64_t acc[4], const unsigned char* p, size_t stripes) {
    uint64_t a0 = acc[0], a1 = acc[1], a2 = acc[2], a3 = acc[3];
    for (size_t s = 0; s < stripes; ++s, p += 32) {
        a0 = round64(a0, read64(p));
        a1 = round64(a1, read64(p + 8));
        a2 = round64(a2, read64(p + 16));
        a3 = round64(a3, read64(p + 24));
    }
    acc[0] = a0, acc[1] = a1, acc[2] = a2, acc[3] = a3;
}

}  // namespace

Hash64::Hash64(uint64_t seed) : seed_(seed), acc_{seed + kP1 + kP2, seed + kP2, seed, seed - kP1} {}

void Hash64::update(const void* data, size_t size) {
    const auto* p = static_cast<const unsigned char*>(data);
    totalBytes_ += size;
    if (pendingBytes_ > 0) {
        const size_t take = std::min(size, 32 - pendingBytes_);
        std::memcpy(pending_ + pendingBytes_, p, take);
        pendingBytes_ += take, p += take, size -= take;
        if (pendingBytes_ < 32) return;
        consumeStripes(acc_, pending_, 1);
        pendingBytes_ = 0;
    }
    consumeStripes(acc_, p, size / 32);
    p += size / 32 * 32;
    pendingBytes_ = size % 32;
    std::memcpy(pending_, p, pendingBytes_);
}

uint64_t Hash64::digest() const {
    uint64_t h;
    if (totalBytes_ >= 32) {
        h = std::rotl(acc_[0], 1) + std::rotl(acc_[1], 7) + std::rotl(acc_[2], 12) + std::rotl(acc_[3], 18);
        for (uint64_t a : acc_) h = mergeRound(h, a);
    } else {
        h = seed_ + kP5;
    }
    h += totalBytes_;
    const unsigned char* p = pending_;
    size_t left = pendingBytes_;
    for (; left >= 8; left -= 8, p += 8) h = std::rotl(h ^ round64(0, read64(p)), 27) * kP1 + kP4;
    if (left >= 4) {
        h = std::rotl(h ^ (uint64_t(read32(p)) * kP1), 23) * kP2 + kP3;
        left -= 4, p += 4;
    }
    for (; left > 0; --left, ++p) h = std::rotl(h ^ (uint64_t(*p) * kP5), 11) * kP1;
    h ^= h >> 33;
    h *= kP2;
    h ^= h >> 29;
    h *= kP3;
    h ^= h >> 32;
    return h;
}

}  // namespace vkray
