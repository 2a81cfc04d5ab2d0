// libFuzzer target of the .scene parser and, through `geo`, of every mesh loader at once: the input
// is a scene followed by the files it names (fuzz_common.h), so every .scene file is a seed as it is.
#include "fuzz_common.h"
#include "scene/scene_parser.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* bytes, size_t size) {
    using namespace vkray;
    const fuzz::FuzzFiles in = fuzz::splitFiles(fuzz::asText(bytes, size));
    ParseOptions options;
    options.maxTriangles = fuzz::kMaxTriangles;
    options.readFile = fuzz::memoryReader(in, "");
    fuzz::expectOnlyErrors([&] { fuzz::checkScene(parseSceneText(in.main, "fuzz.scene", "fuzz", options)); });
    return 0;
}
