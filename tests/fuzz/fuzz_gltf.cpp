// libFuzzer target: glTF 2.0 (.gltf and .glb) through load_gltf: tinygltf's parse, then
// Facet's own buffer, accessor, index, material and node checks and the image decoding.
// Input and checks: feed.h.
#include "feed.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    facet::fuzz::feed_gltf({data, size});
    return 0;
}
