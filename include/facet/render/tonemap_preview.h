#pragma once
// An 8-bit sRGB preview of a linear HDR image: exposure, then Reinhard (the thesis'
// operator), then the sRGB transfer function. A compute pass of the render graph.
#include <facet/core/result.h>
#include <facet/graph/render_graph.h>

namespace facet {

class ProgramCache;

// Reads `hdr` (RGBA32F, mip 0) and writes `ldr` (RGBA8 UNORM, same size); returns the
// new version of `ldr`.
Result<ImageHandle> add_tonemap_preview_pass(RenderGraph& graph, ProgramCache& programs, ImageHandle hdr,
                                             ImageHandle ldr, float exposure);

}  // namespace facet
