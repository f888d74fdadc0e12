#pragma once
// The smallest complete piece of work Facet does: bake a built-in sky and render the
// built-in spheres with it, at sizes lavapipe gets through in a fraction of a second.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <memory>
#include <string>

#include <facet/gpu/context.h>
#include <facet/render/render_job.h>
#include "support/gpu_test.h"

namespace facet::test {

// A context of the test's own (not the shared one), so that its teardown, where the
// validation layer reports objects left behind, happens inside the test.
inline std::unique_ptr<Context> own_context(bool validation = true) {
    ContextOptions options = context_options();
    options.validation = validation;
    options.sync_validation = validation;
    auto created = create_context(options);
    if (!created) {
        ADD_FAILURE() << created.error().message;
        return nullptr;
    }
    return std::move(created).value();
}

// One sphere: the 49 of builtin:spheres are 9 MiB of mesh built and uploaded every
// session, a fifth of a tiny session's time, with nothing more to exercise.
inline RenderJob tiny_job() {
    RenderJob job;
    job.model = "builtin:sphere";
    job.env = "builtin:sky";
    job.env_width = 64;
    job.ibl.cube_size = 16;
    job.ibl.irradiance.size = 8;
    job.ibl.irradiance.source_size = 8;
    job.ibl.specular.levels = 4;
    job.ibl.specular.sample_count = 64;
    job.ibl.lut.size = 16;
    job.ibl.lut.sample_count = 64;
    job.frame.width = 32;
    job.frame.height = 32;
    return job;
}

struct TinyResult {
    std::string error;        // empty on success
    VkResult vk_result = VK_SUCCESS;
    double mean_radiance = 0;  // of the rendered HDR image
};

// Bake + render + teardown of everything but the context. Errors come back as a Result
// (no exception crosses the public API: one that did would fail the calling test).
inline TinyResult run_tiny_session(Context& context, const RenderJob& job = tiny_job()) {
    TinyResult out;
    auto session = RenderSession::create(context, job);
    if (!session) return {session.error().message, session.error().vk_result};
    auto images = (*session)->render_frame();
    if (!images) return {images.error().message, images.error().vk_result};
    double sum = 0;
    for (size_t i = 0; i < images->hdr.size(); i += 4) sum += images->hdr[i] + images->hdr[i + 1] + images->hdr[i + 2];
    out.mean_radiance = sum / (3.0 * images->hdr.size() / 4);
    if (!std::isfinite(out.mean_radiance)) out.error = "non-finite image";
    return out;
}

// A single-sample size x size frame of the origin seen head-on from (0, 0, 3) (the small
// glTF files' quads at z = 0 facing +Z), under `env` baked from 64 texels, no skybox.
inline RenderJob head_on_job(const std::string& env, uint32_t size) {
    RenderJob job;
    job.env = env;
    job.env_width = 64;
    job.frame.width = size;
    job.frame.height = size;
    job.frame.samples = 1;
    job.frame.skybox = false;
    job.ibl.specular.sample_count = 64;
    job.ibl.lut.size = 32;
    job.ibl.lut.sample_count = 256;
    job.orbit = std::array<float, 3>{0.0f, 0.0f, 3.0f};
    job.target = glm::vec3(0.0f);
    return job;
}

}  // namespace facet::test
