// XXH64 (Yann Collet's xxHash, 64-bit variant; the reference's test vectors hold: tests/accel/
// accel_file_test.cpp), streamed. Not cryptographic: it tells that bytes changed, at several GB/s
// on one core, so that checking a multi-GB structure file or a 16M-triangle scene costs little
// next to reading or loading it.
#pragma once

#include <cstddef>
#include <cstdint>

namespace vkray {

class Hash64 {
public:
    explicit Hash64(uint64_t seed = 0);

    // Appends `size` bytes; the digest is the same however the bytes are split across calls.
    void update(const void* data, size_t size);
    // The hash of everything appended so far (update() may go on after it).
    uint64_t digest() const;

private:
    uint64_t seed_;
    uint64_t acc_[4];
    unsigned char pending_[32];  // the start of a stripe not yet complete
    size_t pendingBytes_ = 0;
    uint64_t totalBytes_ = 0;
};

inline uint64_t hash64(const void* data, size_t size, uint64_t seed = 0) {
    Hash64 h(seed);
    h.update(data, size);
    return h.digest();
}

}  // namespace vkray
