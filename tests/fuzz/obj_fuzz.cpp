// libFuzzer target of the OBJ loader and the MTL files an OBJ names: the input is the OBJ, followed
// by "#@ NAME" sections for its `mtllib` files (fuzz_common.h).
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* bytes, size_t size) {
    vkray::fuzz::fuzzMeshFile(vkray::fuzz::asText(bytes, size), "m.obj", true);
    return 0;
}
