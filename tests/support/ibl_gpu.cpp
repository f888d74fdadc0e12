#include "support/ibl_gpu.h"

#include <gtest/gtest.h>

#include <cstring>
#include <optional>

#include <facet/gpu/context.h>
#include <facet/gpu/transfer.h>
#include <facet/graph/compiled_graph.h>
#include <facet/graph/graph_run.h>
#include <facet/graph/transfer_passes.h>
#include "ibl/environment_cube.h"
#include <facet/shader/program_cache.h>
#include "support/gpu_test.h"

namespace facet::test {

namespace {
const Sampler* current_equirect_sampler = nullptr;
}

const Sampler* run_ibl_equirect_sampler() { return current_equirect_sampler; }

CubeLevels run_ibl(Context& context, const Equirect& e, const AddPasses& passes) {
    // The shared context's pipelines (built by the first call that needs each); a context
    // of the test's own gets its own, gone with this call.
    std::optional<ShaderCompiler> own_compiler;
    std::optional<ProgramCache> own_programs;
    ProgramCache* shared = shared_programs_for(context);
    if (!shared) {
        own_compiler.emplace();
        own_programs.emplace(context, *own_compiler);
    }
    ProgramCache& programs = shared ? *shared : *own_programs;
    Sampler equirect_sampler = must(Sampler::create(context, VK_FILTER_LINEAR, false, true, "equirect"));
    Sampler cube_sampler = must(Sampler::create(context, VK_FILTER_LINEAR, true, false, "cube"));
    Buffer staging = must(
        Buffer::create(context, e.rgba.size() * 4, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUsage::upload, "staging"));
    std::memcpy(staging.mapped(), e.rgba.data(), e.rgba.size() * 4);
    must(staging.flush());
    RenderGraph g;
    ImageDesc ed;
    ed.width = e.w;
    ed.height = e.h;
    auto equirect = g.create_image("equirect", ed);
    auto texels = g.import_buffer(
        "texels", {staging.handle(), staging.size(), {VK_IMAGE_LAYOUT_UNDEFINED, VK_PIPELINE_STAGE_2_HOST_BIT,
                                                     VK_ACCESS_2_HOST_WRITE_BIT}, {}});
    equirect = add_upload_pass(g, "upload", texels, equirect);
    const uint32_t size = cube_size_for(e.h);
    auto cube = g.create_image("environment cube", environment_cube_desc(size, full_mip_count(size)));
    auto cube_out = add_environment_cube_passes(g, programs, equirect_sampler, equirect, cube);
    EXPECT_TRUE(cube_out) << (cube_out ? "" : cube_out.error().message);
    current_equirect_sampler = &equirect_sampler;
    ImageHandle result = passes ? passes(g, programs, cube_sampler, *cube_out, equirect) : *cube_out;
    current_equirect_sampler = nullptr;
    g.export_image(result, {VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                            VK_ACCESS_2_TRANSFER_READ_BIT});
    CompiledGraph compiled = g.compile();
    auto run = must(run_graph(context, compiled));
    Image& image = *run->transient_image(result);
    CubeLevels out;
    out.size = image.desc().width;
    for (uint32_t m = 0; m < image.desc().mip_levels; ++m) {
        std::vector<float> level;
        for (uint32_t f = 0; f < image.desc().array_layers; ++f) {
            auto bytes = must(read_image(context, image, m, f, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL));
            const size_t old = level.size();
            level.resize(old + bytes.size() / 4);
            std::memcpy(level.data() + old, bytes.data(), bytes.size());
        }
        out.levels.push_back(std::move(level));
    }
    return out;
}

}  // namespace facet::test
