// XXH64 (Yann Collet's xxHash, 64-bit variant, from Debian's libxxhash), streamed. Not
// cryptographic: it tells that bytes changed, at several GB/s on one core, so that checking a
// multi-GB structure file or a 16M-triangle scene costs little next to reading or loading it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>

struct XXH64_state_s;

namespace vkray {

class Hash64 {
public:
    explicit Hash64(uint64_t seed = 0);
    ~Hash64();
    Hash64(const Hash64&) = delete;
    Hash64& operator=(const Hash64&) = delete;

    // Appends `size` bytes; the digest is the same however the bytes are split across calls.
    void update(const void* data, size_t size);
    // The hash of everything appended so far (update() may go on after it).
    uint64_t digest() const;

private:
    XXH64_state_s* state_;
};

uint64_t hash64(const void* data, size_t size, uint64_t seed = 0);

}  // namespace vkray
