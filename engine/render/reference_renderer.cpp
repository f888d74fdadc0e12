#include <facet/render/reference_renderer.h>

#include <cmath>
#include <cstddef>
#include <cstring>

#include <facet/gpu/context.h>
#include <facet/gpu/pipeline.h>
#include <facet/gpu/transfer.h>
#include <facet/graph/compiled_graph.h>
#include <facet/graph/graph_run.h>
#include "render/environment_distribution.h"
#include "render/light_data.h"
#include <facet/shader/program_cache.h>
#include "core/guarded.h"

namespace facet {
namespace {

struct ReferenceParams {
    glm::vec4 camera_position;
    glm::uvec4 env;    // width, height, light count, flags
    glm::uvec4 batch;  // samples, first sample index
    glm::vec4 scale;   // environment intensity
};
static_assert(sizeof(ReferenceParams) == 64 && offsetof(ReferenceParams, env) == 16 &&
                  offsetof(ReferenceParams, batch) == 32 && offsetof(ReferenceParams, scale) == 48,
              "Params in shaders/render/reference.comp");

const ResourceState sampled{VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                            VK_ACCESS_2_SHADER_SAMPLED_READ_BIT};
const ResourceState storage_rw{VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                               VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT};

std::unique_ptr<Buffer> storage_buffer(Context& context, const void* data, size_t bytes, const char* name) {
    auto buffer = std::make_unique<Buffer>(or_throw(Buffer::create(context, std::max<size_t>(bytes, 16),
                                                                   VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                                                       VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                                                   MemoryUsage::gpu_only, name)));
    if (bytes)
        or_throw(upload_buffer(context, *buffer, std::as_bytes(std::span(static_cast<const std::byte*>(data), bytes))));
    return buffer;
}

std::vector<float> read_floats(Context& context, const Image& image) {
    auto bytes = or_throw(read_image(context, image, 0, 0, VK_IMAGE_LAYOUT_GENERAL));
    std::vector<float> values(bytes.size() / sizeof(float));
    std::memcpy(values.data(), bytes.data(), values.size() * sizeof(float));
    return values;
}

}  // namespace

// Makes nothing on the device: accumulate makes the sampler, and returns its failure.
ReferenceRenderer::ReferenceRenderer(Context& context, ProgramCache& programs) : context_(context), programs_(programs) {}

ReferenceRenderer::~ReferenceRenderer() = default;

Status ReferenceRenderer::set_environment(std::span<const float> rgba, uint32_t width, uint32_t height,
                                          float intensity) try {
    const EnvironmentDistribution d = build_environment_distribution(rgba, width, height);
    radiance_ = storage_buffer(context_, rgba.data(), rgba.size_bytes(), "reference environment radiance");
    distribution_ = storage_buffer(context_, d.values.data(), d.values.size() * sizeof(float),
                                   "reference environment distribution");
    env_width_ = width;
    env_height_ = height;
    env_intensity_ = intensity;
    return Ok{};
} catch (const VulkanError& e) {
    return Error{e.what(), e.result()};
}

Result<ReferenceStats> ReferenceRenderer::accumulate(const ReferenceSurface& surface, const FrameSettings& frame,
                                                     const ReferenceSettings& settings, const Progress& progress) try {
    if (!surface.normal || !surface.position || !surface.basecolor || !surface.metallic || !surface.roughness ||
        !surface.f0 || !surface.emissive || !surface.clearcoat || !surface.clearcoat_normal ||
        !surface.iridescence || !surface.anisotropy || !surface.sheen || !surface.transmission)
        return Error{"reference: every surface view is needed"};
    if (settings.batch_samples == 0 || settings.max_samples == 0)
        return Error{"reference: the sample counts must be at least 1"};
    auto pipeline = programs_.compute("render/reference.comp");
    if (!pipeline) return pipeline.error();

    std::vector<LightData> lights;
    for (const Light& l : frame.lights) lights.push_back(light_data(l));
    if (!nearest_) nearest_ = or_throw(Sampler::create(context_, VK_FILTER_NEAREST, false, false, "reference nearest"));
    lights_ = storage_buffer(context_, lights.data(), lights.size() * sizeof(LightData), "reference lights");
    if (!radiance_) {
        const float zero[4] = {};
        radiance_ = storage_buffer(context_, zero, sizeof zero, "reference environment radiance");
        distribution_ = storage_buffer(context_, zero, sizeof zero, "reference environment distribution");
    }

    ImageDesc desc = surface.normal->desc();
    desc.format = VK_FORMAT_R32G32B32A32_SFLOAT;
    const VkImageUsageFlags usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                                    VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    accumulation_ = std::make_unique<Image>(or_throw(Image::create(context_, desc, usage, "reference accumulation")));
    moments_ = std::make_unique<Image>(or_throw(Image::create(context_, desc, usage, "reference moments")));
    or_throw(context_.submit_and_wait([&](VkCommandBuffer cmd) {
        for (Image* image : {accumulation_.get(), moments_.get()}) {
            const VkImageSubresourceRange range = whole_range(image->desc());
            image_barrier(cmd, image->handle(), range, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                          VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_CLEAR_BIT,
                          VK_ACCESS_2_TRANSFER_WRITE_BIT);
            const VkClearColorValue zero{};
            vkCmdClearColorImage(cmd, image->handle(), VK_IMAGE_LAYOUT_GENERAL, &zero, 1, &range);
        }
        memory_barrier(cmd, VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                       VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    }));

    ReferenceStats stats;
    // Bindings 0-6, then 12-17 (render/reference.comp).
    const Image* views[] = {surface.normal,   surface.position, surface.basecolor, surface.metallic, surface.roughness,
                            surface.f0,       surface.emissive, surface.clearcoat, surface.clearcoat_normal,
                            surface.iridescence, surface.anisotropy, surface.sheen, surface.transmission};
    const char* view_names[] = {"normal", "position", "basecolor", "metallic", "roughness",
                                "f0",     "emissive", "clearcoat", "clearcoat normal",
                                "iridescence", "anisotropy", "sheen", "transmission"};
    constexpr int kViews = 13, kFirstViewsInOrder = 7;
    while (stats.samples < settings.max_samples) {
        const uint32_t count = std::min(settings.batch_samples, settings.max_samples - stats.samples);
        RenderGraph graph;
        std::vector<ImageHandle> inputs;
        for (int i = 0; i < kViews; ++i)
            inputs.push_back(graph.import_image(view_names[i], {views[i]->handle(), views[i]->desc(), sampled, sampled}));
        ImageHandle acc = graph.import_image("accumulation", {accumulation_->handle(), desc, storage_rw, storage_rw});
        ImageHandle mom = graph.import_image("moments", {moments_->handle(), desc, storage_rw, storage_rw});
        ReferenceParams params{glm::vec4(frame.camera.position, 1.0f),
                               glm::uvec4(env_width_, env_height_, uint32_t(lights.size()),
                                          frame.brdf == BrdfModel::thesis ? 1u : 0u),
                               glm::uvec4(count, stats.samples, 0u, 0u), glm::vec4(env_intensity_, 0.0f, 0.0f, 0.0f)};
        graph.add_compute_pass("reference batch", [&](PassBuilder& b) {
            for (ImageHandle h : inputs) b.sample(h);
            acc = b.read_write_storage(acc);
            mom = b.read_write_storage(mom);
        }, [&, p = *pipeline, params, inputs, acc, mom](PassContext& pc) {
            p->bind(pc.cmd());
            std::vector<DescriptorWrite> writes;
            for (int i = 0; i < kFirstViewsInOrder; ++i)
                writes.push_back(DescriptorWrite::sampled_image(pc.view(inputs[i]), nearest_.handle()));
            writes.push_back(DescriptorWrite::storage_buffer(radiance_->handle()));
            writes.push_back(DescriptorWrite::storage_buffer(distribution_->handle()));
            writes.push_back(DescriptorWrite::storage_buffer(lights_->handle()));
            writes.push_back(DescriptorWrite::storage_image(pc.view(acc)));
            writes.push_back(DescriptorWrite::storage_image(pc.view(mom)));
            for (int i = kFirstViewsInOrder; i < kViews; ++i)
                writes.push_back(DescriptorWrite::sampled_image(pc.view(inputs[i]), nearest_.handle()));
            p->push_descriptors(pc.cmd(), writes);
            p->push_constants(pc.cmd(), params);
            const auto local = p->workgroup_size();
            vkCmdDispatch(pc.cmd(), group_count(desc.width, local[0]), group_count(desc.height, local[1]), 1);
        });
        CompiledGraph compiled = graph.compile();
        GraphRun run(context_, compiled);
        or_throw(run.submit_and_wait());
        stats.samples += count;

        // Noise: spread of the batch means per pixel (equal batches only).
        const std::vector<float> m = read_floats(context_, *moments_);
        double se2 = 0, mean2 = 0;
        for (size_t i = 0; i + 3 < m.size(); i += 4) {
            const double n = m[i + 2];
            if (n < 2) continue;
            const double mean = m[i] / n, var = std::max(0.0, (m[i + 1] - m[i] * mean) / (n - 1));
            se2 += var / n;
            mean2 += mean * mean;
        }
        stats.noise = mean2 > 0 ? std::sqrt(se2 / mean2) : 0.0;
        stats.converged = stats.samples >= settings.min_samples && stats.samples >= 2 * settings.batch_samples &&
                          stats.noise <= settings.noise_target;
        if (progress) progress(stats);
        if (stats.converged) break;
    }
    return stats;
} catch (const VulkanError& e) {
    return Error{e.what(), e.result()};
}

Result<ImageHandle> ReferenceRenderer::add_resolve_pass(RenderGraph& graph, ImageHandle accumulation,
                                                        ImageHandle normal, ImageHandle frame_out) {
    auto pipeline = programs_.compute("render/reference_resolve.comp");
    if (!pipeline) return pipeline.error();
    ImageHandle written;
    graph.add_compute_pass("reference resolve", [&](PassBuilder& b) {
        b.read_storage(accumulation);
        b.sample(normal);
        written = b.write_storage(frame_out);
    }, [p = *pipeline, accumulation, normal, frame_out, sampler = nearest_.handle()](PassContext& pc) {
        const ImageDesc& d = pc.desc(frame_out);
        p->bind(pc.cmd());
        const DescriptorWrite writes[] = {DescriptorWrite::storage_image(pc.view(accumulation)),
                                          DescriptorWrite::sampled_image(pc.view(normal), sampler),
                                          DescriptorWrite::storage_image(pc.view(frame_out))};
        p->push_descriptors(pc.cmd(), writes);
        const auto local = p->workgroup_size();
        vkCmdDispatch(pc.cmd(), group_count(d.width, local[0]), group_count(d.height, local[1]), 1);
    });
    return written;
}

}  // namespace facet
