#pragma once
// Runs Facet's IBL passes on a CPU-made equirect and reads the results back, for tests.
#include <algorithm>
#include <functional>
#include <vector>

#include <facet/graph/render_graph.h>
#include <facet/reference/ibl_reference.h>

namespace facet {
class Context;
class ProgramCache;
class Sampler;
}  // namespace facet

namespace facet::test {

struct CubeLevels {
    uint32_t size = 0;
    std::vector<std::vector<float>> levels;  // [mip] -> faces x rows x texels x 4
    const float* texel(uint32_t mip, uint32_t face, uint32_t x, uint32_t y) const {
        const uint32_t n = std::max(1u, size >> mip);
        return &levels[mip][((size_t(face) * n + y) * n + x) * 4];
    }
};

// What a test adds after the environment cube exists: returns the cube image to read.
using AddPasses = std::function<ImageHandle(RenderGraph&, ProgramCache&, const Sampler& cube_sampler,
                                            ImageHandle environment_cube, ImageHandle equirect)>;

// Uploads `e`, builds the environment cube (face size h / 2, full mips), adds `passes`
// (nullptr: read the environment cube itself), runs, and reads every level of the result.
// On the shared context the pipelines are gpu_programs()' (support/gpu_test.h).
CubeLevels run_ibl(Context& context, const Equirect& e, const AddPasses& passes = nullptr);
// The sampler run_ibl built the cube with (linear, repeat in u): valid inside AddPasses.
const Sampler* run_ibl_equirect_sampler();

}  // namespace facet::test
