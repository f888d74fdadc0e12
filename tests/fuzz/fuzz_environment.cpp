// libFuzzer target: environment images (.hdr, .exr, .png, ...) through load_environment:
// OpenImageIO's readers, then Facet's texel checks, with sanitising off and on.
// Input and checks: feed.h.
#include "feed.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    facet::fuzz::feed_environment({data, size});
    return 0;
}
