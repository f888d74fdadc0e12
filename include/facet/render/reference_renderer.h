#pragma once
// Ground truth inside the engine (shaders/render/reference.comp): per pixel, the
// reflectance equation integrated by Monte Carlo over the whole environment with BRDF and
// environment importance sampling combined by multiple importance sampling; no split
// sum, no prefiltering. Batches of samples accumulate until the image's relative noise
// (standard error of the mean, RMS over covered pixels, relative to the RMS radiance)
// falls under a target, or a sample limit is reached.
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include <facet/core/result.h>
#include <facet/gpu/resources.h>
#include <facet/render/forward_renderer.h>

namespace facet {

class Context;
class ProgramCache;

struct ReferenceSettings {
    uint32_t batch_samples = 32;  // per pixel and batch, each one BRDF and one environment sample
    uint32_t min_samples = 64;
    uint32_t max_samples = 4096;
    double noise_target = 0.01;   // relative standard error of the image
};

// The surface seen by each pixel: single-sample views of the forward pass (normal,
// position, basecolor, metallic, roughness, f0, emissive), RGBA32F, SHADER_READ_ONLY.
struct ReferenceSurface {
    const Image* normal = nullptr;
    const Image* position = nullptr;
    const Image* basecolor = nullptr;
    const Image* metallic = nullptr;
    const Image* roughness = nullptr;
    const Image* f0 = nullptr;
    const Image* emissive = nullptr;
    const Image* clearcoat = nullptr;         // View::clearcoat: weight, roughness
    const Image* clearcoat_normal = nullptr;  // View::clearcoat_normal
    const Image* iridescence = nullptr;       // View::iridescence: weight, film ior, thickness (nm)
    const Image* anisotropy = nullptr;        // View::anisotropy: direction, strength
    const Image* sheen = nullptr;             // View::sheen: colour, roughness
    const Image* transmission = nullptr;      // View::transmission: weight, lobe roughness
};

struct ReferenceStats {
    uint32_t samples = 0;   // per pixel (each a BRDF and an environment sample)
    double noise = 0;       // relative standard error reached
    bool converged = false; // noise <= target
};

class ReferenceRenderer {
public:
    ReferenceRenderer(Context& context, ProgramCache& programs);
    ~ReferenceRenderer();

    // The environment as the reference sees it: texels (row 0 = top) and their sampling
    // distribution, uploaded once. Without one, only lights and emission are integrated.
    // An Error when the device fails (out of memory, device lost).
    Status set_environment(std::span<const float> rgba, uint32_t width, uint32_t height, float intensity);

    using Progress = std::function<void(const ReferenceStats&)>;
    // Accumulates until converged; then `accumulation()` holds the sums (rgb, a = count)
    // in GENERAL layout. A device failure is an Error (no exception leaves it).
    Result<ReferenceStats> accumulate(const ReferenceSurface& surface, const FrameSettings& frame,
                                      const ReferenceSettings& settings, const Progress& progress = {});
    Image& accumulation() { return *accumulation_; }

    // Adds the pass that turns the sums into radiance: `frame_out` (RGBA32F, alpha =
    // coverage); returns its new version. `accumulation` and `normal` are imported by the
    // caller (GENERAL and SHADER_READ_ONLY).
    Result<ImageHandle> add_resolve_pass(RenderGraph& graph, ImageHandle accumulation, ImageHandle normal,
                                         ImageHandle frame_out);

private:
    Context& context_;
    ProgramCache& programs_;
    std::unique_ptr<Buffer> radiance_, distribution_, lights_;
    uint32_t env_width_ = 0, env_height_ = 0;
    float env_intensity_ = 1.0f;
    std::unique_ptr<Image> accumulation_, moments_;
    Sampler nearest_;
};

}  // namespace facet
