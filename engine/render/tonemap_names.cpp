// Tone mapping operators by name, apart from the pass so that option parsing (and its
// fuzz target) needs no GPU code.
#include <facet/render/tonemap.h>

namespace facet {
namespace {
constexpr const char* kTonemapNames[] = {"none", "reinhard", "exposure", "aces", "neutral"};
}

const char* tonemap_name(Tonemap tonemap) { return kTonemapNames[uint32_t(tonemap)]; }

std::optional<Tonemap> parse_tonemap(const std::string& name) {
    for (uint32_t i = 0; i < 5; ++i)
        if (name == kTonemapNames[i]) return Tonemap(i);
    return std::nullopt;
}

}  // namespace facet
