#pragma once
// The display transform as a compute pass: exposure, a tone mapping operator, gamma.
#include <optional>
#include <string>

#include <facet/core/result.h>
#include <facet/graph/render_graph.h>

namespace facet {

class ProgramCache;
class Sampler;

// Numbers match shaders/render/tonemap.comp.
enum class Tonemap : uint32_t { none = 0, reinhard = 1, exposure = 2, aces = 3, neutral = 4 };

const char* tonemap_name(Tonemap tonemap);
std::optional<Tonemap> parse_tonemap(const std::string& name);

struct DisplaySettings {
    float exposure = 1.0f;
    Tonemap tonemap = Tonemap::reinhard;
    float gamma = 0.0f;  // 0: the sRGB transfer function; else x^(1/gamma)
};

// Reads `hdr` (mip 0, sampled) and writes `ldr` (RGBA8 UNORM, same size, already
// encoded); returns the new version of `ldr`. `nearest` is a nearest-filter sampler.
Result<ImageHandle> add_tonemap_pass(RenderGraph& graph, ProgramCache& programs, const Sampler& nearest,
                                     ImageHandle hdr, ImageHandle ldr, const DisplaySettings& display);

}  // namespace facet
