#include "core/hash64.h"

#include <new>

#include <xxhash.h>

namespace vkray {

Hash64::Hash64(uint64_t seed) : state_(XXH64_createState()) {
    if (!state_) throw std::bad_alloc();
    XXH64_reset(state_, seed);
}

Hash64::~Hash64() { XXH64_freeState(state_); }

void Hash64::update(const void* data, size_t size) {
    if (size > 0) XXH64_update(state_, data, size);
}

uint64_t Hash64::digest() const { return XXH64_digest(state_); }

uint64_t hash64(const void* data, size_t size, uint64_t seed) { return XXH64(data, size, seed); }

}  // namespace vkray
