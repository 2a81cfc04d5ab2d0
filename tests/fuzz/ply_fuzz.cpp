// libFuzzer target of the PLY loader (ASCII and both binary byte orders): the input is the file.
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* bytes, size_t size) {
    vkray::fuzz::fuzzMeshFile(vkray::fuzz::asText(bytes, size), "m.ply", false);
    return 0;
}
