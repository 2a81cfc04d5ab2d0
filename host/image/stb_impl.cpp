// The one translation unit that compiles the stb image reader and writer (single-header libraries:
// exactly one .cpp of the program may define the *_IMPLEMENTATION macros). Anyone else who needs
// stb_image just includes the header without the macros. Every declaration in the headers has a
// definition; the PNG writer compresses with zlib (below) instead of stb's own deflate.
#include <climits>
#include <cstdlib>

#include <zlib.h>

namespace {

// stb_image_write's hook for a zlib-style compressor (STBIW_ZLIB_COMPRESS): the deflate stream of
// `data` in a malloc'd buffer stb frees, or null. stb's own deflate is a simple one, most of a PNG
// write; zlib at its default level is faster and its files smaller (docs/performance.md, "Kept
// changes and what they measured").
unsigned char* zlibCompress(unsigned char* data, int size, int* outSize, int /*stb's quality*/) {
    uLongf bound = compressBound(uLong(size));
    auto* out = static_cast<unsigned char*>(std::malloc(bound));
    if (!out) return nullptr;
    if (compress2(out, &bound, data, uLong(size), Z_DEFAULT_COMPRESSION) != Z_OK || bound > uLongf(INT_MAX)) {
        std::free(out);
        return nullptr;
    }
    *outSize = int(bound);
    return out;
}

}  // namespace

#define STBIW_ZLIB_COMPRESS zlibCompress
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image.h>
#include <stb_image_write.h>
