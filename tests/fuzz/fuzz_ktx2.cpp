// libFuzzer target: KTX 2 files through read_ktx2, and every file that reads through
// write_ktx2 and back. Input and checks: feed.h.
#include "feed.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    facet::fuzz::feed_ktx2({data, size});
    return 0;
}
