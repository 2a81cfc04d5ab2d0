// libFuzzer target of the glTF 2.0 loader. An input that starts with the GLB magic "glTF" is a .glb,
// taken whole; any other is a .gltf (JSON) followed by "#@ NAME" sections for the buffers it names
// by URI (fuzz_common.h).
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* bytes, size_t size) {
    const std::string_view data = vkray::fuzz::asText(bytes, size);
    if (data.starts_with("glTF"))
        vkray::fuzz::fuzzMeshFile(data, "m.glb", false);
    else
        vkray::fuzz::fuzzMeshFile(data, "m.gltf", true);
    return 0;
}
