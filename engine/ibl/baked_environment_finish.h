#pragma once
// The end of bake_environment, on the GPU: every output is checked (no NaN, Inf or
// negative value) and measured (its largest value) by a pass of the bake's own graph, the
// specular levels no lookup reads are cleared, and after the run the outputs that fit
// RGBA16F are converted into it by a blit. Nothing of an output passes through the host;
// only two numbers per output are read back.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <facet/core/result.h>
#include <facet/gpu/resources.h>
#include <facet/graph/render_graph.h>

namespace facet {

class Buffer;
class Context;
class Pipeline;
class ProgramCache;

// One output of the bake's graph to check: the levels from `first_level` on count.
struct CheckedOutput {
    ImageHandle image;  // RGBA32F; replaced by its version after the check
    uint32_t first_level = 0;
};

// Clears levels [0, level_count) of `image` to zero (levels nothing computed), so that
// the saved files are the same from run to run; returns the image's new version.
ImageHandle add_clear_levels_pass(RenderGraph& graph, ImageHandle image, uint32_t level_count);

// A pass per output and level accumulating its largest value and its count of unsound
// values into the returned buffer (2 uints an output, in the order given), which the
// caller exports and reads with read_output_ranges after the run.
Result<BufferHandle> add_output_range_passes(RenderGraph& graph, ProgramCache& programs,
                                             std::vector<CheckedOutput>& outputs);

struct OutputRange {
    float peak = 0;    // the largest sound value
    uint64_t bad = 0;  // NaN, Inf or negative values
};
std::vector<OutputRange> read_output_ranges(Context& context, const Buffer& ranges, size_t count);

// The pipeline convert_to_half runs (a bake asks for it with its passes' batch).
Result<const Pipeline*> half_conversion_program(ProgramCache& programs);

// Copies of `rgba32f`'s images (every level and layer, in `layout`, made with storage use)
// in RGBA16F, made by compute passes in one submission (ibl/to_half.comp: each value
// rounded to a half by the store), left in kBakedLayout and named `names`; the originals are
// left in `layout` and may be dropped afterwards.
std::vector<Image> convert_to_half(ProgramCache& programs, std::span<Image* const> rgba32f, VkImageLayout layout,
                                   std::span<const std::string> names);

}  // namespace facet
