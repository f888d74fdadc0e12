// libFuzzer target: the command lines of facet-bake, facet-render, facet-viewer and
// facet-bench, and the --light and --aov value parsers. Input and checks: feed.h.
#include <cstdio>

#include "feed.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    // --help and --version print to stdout; libFuzzer reports on stderr.
    if (!std::freopen("/dev/null", "w", stdout)) return 1;
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    facet::fuzz::feed_cli({data, size});
    return 0;
}
