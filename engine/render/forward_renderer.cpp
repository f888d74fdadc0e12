// The programs' frame composed from the separate passes (forward, skybox, display
// transform, views), and the skybox pass.
#include <facet/render/forward_renderer.h>

#include <cstring>

#include <facet/gpu/context.h>
#include <facet/gpu/pipeline.h>
#include <facet/graph/graph_run.h>
#include <facet/render/gpu_scene.h>
#include <facet/shader/program_cache.h>
#include "render/forward_data.h"

namespace facet {
using namespace forward;

namespace {

constexpr VkFormat hdr_format = VK_FORMAT_R32G32B32A32_SFLOAT;
constexpr VkFormat depth_format = VK_FORMAT_D32_SFLOAT;

}  // namespace

Result<ImageHandle> ForwardRenderer::add_skybox_pass(RenderGraph& graph, ImageHandle hdr, const FrameSettings& s,
                                                     const CameraMatrices& camera, const IblInputs& ibl,
                                                     uint32_t frame) {
    slot(frame);
    const VkFormat format = graph.resource(hdr).image_desc.format;
    if (format != VK_FORMAT_R32G32B32A32_SFLOAT && format != VK_FORMAT_R16G16B16A16_SFLOAT)
        return Error{"the skybox composites into RGBA32F or RGBA16F images, not '" + graph.resource(hdr).name + "'"};
    // The disks as constants of the pipeline, as the forward pass's.
    auto disks = disk_light_defines(s.environment_lights, "the skybox");
    if (!disks) return disks.error();
    std::vector<ShaderDefine> defines = std::move(*disks);
    if (format == VK_FORMAT_R16G16B16A16_SFLOAT) defines.push_back({"FRAME_RGBA16F", "1"});
    auto sky = programs_.compute("render/skybox.comp", defines);
    if (!sky) return sky.error();
    glm::mat4 rotation = camera.view;
    rotation[3] = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
    const SkyConstants constants{glm::inverse(camera.projection * rotation), 0.0f, ibl.intensity};
    ImageHandle written;
    graph.add_compute_pass("skybox", [&](PassBuilder& b) {
        b.sample(ibl.cube);
        written = b.read_write_storage(hdr);
    }, [p = *sky, constants, hdr, cube = ibl.cube, sampler = ibl.cube_sampler](PassContext& pc) {
        const ImageDesc& d = pc.desc(hdr);
        p->bind(pc.cmd());
        const DescriptorWrite writes[] = {DescriptorWrite::sampled_image(pc.view(cube), sampler),
                                          DescriptorWrite::storage_image(pc.view(hdr, ImageRange::mip(0)))};
        p->push_descriptors(pc.cmd(), writes);
        p->push_constants(pc.cmd(), constants);
        const auto local = p->workgroup_size();
        vkCmdDispatch(pc.cmd(), group_count(d.width, local[0]), group_count(d.height, local[1]), 1);
    });
    return written;
}

Result<ImageHandle> ForwardRenderer::add_skybox_pass(RenderGraph& graph, ImageHandle hdr, const FrameSettings& s,
                                                     const IblInputs& ibl, uint32_t frame) {
    if (s.width == 0 || s.height == 0) return Error{"the image size must be at least 1x1"};
    return add_skybox_pass(graph, hdr, s, s.camera.matrices(float(s.width) / float(s.height)), ibl, frame);
}

Result<FrameImages> ForwardRenderer::add_passes(RenderGraph& graph, const GpuScene& gpu, const FrameSettings& s,
                                                const std::optional<IblInputs>& ibl, uint32_t frame) {
    if (s.width == 0 || s.height == 0) return Error{"the image size must be at least 1x1"};
    const VkSampleCountFlagBits samples = VkSampleCountFlagBits(s.samples);
    if (s.samples != 1 && s.samples != 2 && s.samples != 4 && s.samples != 8)
        return Error{"MSAA samples must be 1, 2, 4 or 8, not " + std::to_string(s.samples)};
    slot(frame);
    const CameraMatrices camera = s.camera.matrices(float(s.width) / float(s.height));

    // Every pipeline first, so that a compile error leaves the graph untouched.
    const Target target{hdr_format, depth_format, samples};
    auto final_pipelines = pipelines(gpu, View::final_color, target, ibl.has_value(), s);
    if (!final_pipelines) return final_pipelines.error();
    for (View v : s.views) {
        auto p = pipelines(gpu, v, Target{hdr_format, depth_format, VK_SAMPLE_COUNT_1_BIT}, ibl.has_value(), s);
        if (!p) return p.error();
    }

    FrameImages out;
    ImageDesc hdr_desc;
    hdr_desc.format = hdr_format;
    hdr_desc.width = s.width;
    hdr_desc.height = s.height;
    out.hdr = graph.create_image("hdr colour", hdr_desc);
    ImageDesc msaa_desc = hdr_desc;
    msaa_desc.samples = samples;
    ImageDesc depth_desc = msaa_desc;
    depth_desc.format = depth_format;
    ForwardTargets targets;
    targets.depth = graph.create_image("depth", depth_desc);
    targets.store_depth = false;
    if (samples == VK_SAMPLE_COUNT_1_BIT) {
        targets.color = out.hdr;
    } else {
        targets.color = graph.create_image("msaa colour", msaa_desc);
        targets.resolve = out.hdr;
    }
    auto background = add_transmission_background(graph, gpu, s, camera, s.width, s.height, ibl, frame);
    if (!background) return background.error();
    const ForwardOutputs drawn = add_draw_pass(graph, "forward", gpu, s, camera, targets, ibl,
                                               std::move(*final_pipelines), frame, *background);
    out.hdr = targets.resolve.valid() ? drawn.resolve : drawn.color;

    if (s.skybox && ibl) {
        auto composited = add_skybox_pass(graph, out.hdr, s, camera, *ibl, frame);
        if (!composited) return composited.error();
        out.hdr = *composited;
    }

    ImageDesc ldr_desc = hdr_desc;
    ldr_desc.format = VK_FORMAT_R8G8B8A8_UNORM;
    auto ldr = add_tonemap_pass(graph, programs_, nearest_, out.hdr, graph.create_image("display colour", ldr_desc),
                                s.display);
    if (!ldr) return ldr.error();
    out.ldr = *ldr;

    for (View v : s.views) {
        auto image = add_view_pass(graph, gpu, v, s, camera, ibl, frame);
        if (!image) return image.error();
        out.views.push_back({v, *image});
    }
    return out;
}

}  // namespace facet
