// libFuzzer target of the OFF loader: the input is the file.
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* bytes, size_t size) {
    vkray::fuzz::fuzzMeshFile(vkray::fuzz::asText(bytes, size), "m.off", false);
    return 0;
}
