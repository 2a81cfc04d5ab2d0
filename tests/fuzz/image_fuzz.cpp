// libFuzzer target of the image readers of `vkray compare`, `convert` and `assemble` (readImage:
// PNG and BMP through stb_image, PFM, EXR through OpenEXR), recognised by their magic bytes.
#include "fuzz_common.h"
#include "image/image_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* bytes, size_t size) {
    using namespace vkray;
    const std::vector<unsigned char> data(bytes, bytes + size);
    fuzz::expectOnlyErrors([&] {
        ImageMeta meta;
        const Image image = decodeImage("fuzz.img", data, &meta);
        // What compare and assemble rely on: the pixels the size promises, a display window.
        if (image.data.size() != size_t(image.width) * size_t(image.height) * size_t(image.channels)) __builtin_trap();
        if (image.channels != 1 && image.channels != 3) __builtin_trap();
        if (meta.x0 < -(1 << 30) || meta.displayWidth <= 0 || meta.displayHeight <= 0) __builtin_trap();
    });
    return 0;
}
