#include <facet/ibl/procedural_sky.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include <facet/core/hash.h>
#include <facet/core/shared_constants.h>
#include <facet/graph/graph_run.h>
#include <facet/shader/program_cache.h>
#include "io/equirect.h"
#include "ibl/cube_texel_list.h"
#include "ibl/environment_cube.h"

namespace facet {

namespace {

// Mirrors the push-constant block of shaders/ibl/procedural_sky.glsl.
struct SkyParams {
    float sun_direction_cos_radius[4];
    float sun_radiance_glow[4];
    float zenith[4];
    float horizon[4];
    float ground[4];
};

SkyParams sky_params(const ProceduralSky& sky) {
    const auto dir = sky.sun_direction();
    const double to_rad = pi / 180.0;
    return {{dir[0], dir[1], dir[2], float(std::cos(sky.sun_angular_radius_deg * to_rad))},
            {sky.sun_radiance[0], sky.sun_radiance[1], sky.sun_radiance[2], sky.sun_glow},
            {sky.zenith_radiance[0], sky.zenith_radiance[1], sky.zenith_radiance[2], 0},
            {sky.horizon_radiance[0], sky.horizon_radiance[1], sky.horizon_radiance[2], 0},
            {sky.ground_radiance[0], sky.ground_radiance[1], sky.ground_radiance[2], 0}};
}

}  // namespace

ProceduralSky ProceduralSky::white() {
    ProceduralSky s;
    s.sun_radiance = s.zenith_radiance = s.horizon_radiance = s.ground_radiance = {1.0f, 1.0f, 1.0f};
    s.sun_glow = 0.0f;
    return s;
}

std::array<float, 3> ProceduralSky::sun_direction() const {
    const double to_rad = pi / 180.0;
    // Azimuth is the equirect longitude (0 along +X, 90 along +Z), elevation its latitude.
    const glm::dvec3 d = direction_at(sun_azimuth_deg * to_rad, sun_elevation_deg * to_rad);
    return {float(d.x), float(d.y), float(d.z)};
}

bool ProceduralSky::black() const {
    for (const auto& rgb : {sun_radiance, zenith_radiance, horizon_radiance, ground_radiance})
        if (luminance(rgb[0], rgb[1], rgb[2]) > 0) return false;
    return true;
}

std::string ProceduralSky::content_hash() const {
    Hash64 h;
    h.add("facet procedural sky v1");
    const float values[] = {sun_elevation_deg, sun_azimuth_deg, sun_angular_radius_deg, sun_radiance[0],
                            sun_radiance[1],   sun_radiance[2], sun_glow,               zenith_radiance[0],
                            zenith_radiance[1], zenith_radiance[2], horizon_radiance[0], horizon_radiance[1],
                            horizon_radiance[2], ground_radiance[0], ground_radiance[1], ground_radiance[2]};
    h.add(values, sizeof values);
    return h.hex();
}

Result<ImageHandle> add_procedural_sky_pass(RenderGraph& graph, ProgramCache& programs, const ProceduralSky& sky,
                                            ImageHandle target) {
    auto pipeline = programs.compute("ibl/procedural_sky.comp");
    if (!pipeline) return pipeline.error();
    const SkyParams params = sky_params(sky);
    ImageHandle written;
    graph.add_compute_pass("procedural sky", [&](PassBuilder& b) { written = b.write_storage(target, ImageRange::mip(0)); },
                           [p = pipeline.value(), params, target](PassContext& pc) {
                               const ImageDesc& d = pc.desc(target);
                               p->bind(pc.cmd());
                               const DescriptorWrite writes[] = {
                                   DescriptorWrite::storage_image(pc.view(target, ImageRange::mip(0)))};
                               p->push_descriptors(pc.cmd(), writes);
                               p->push_constants(pc.cmd(), params);
                               // Small groups over the whole image: lavapipe spreads groups over its threads.
                               const auto local = p->workgroup_size();
                               vkCmdDispatch(pc.cmd(), group_count(d.width, local[0]), group_count(d.height, local[1]), 1);
                           });
    return written;
}

Result<ImageHandle> add_procedural_sky_cube_pass(RenderGraph& graph, ProgramCache& programs, const ProceduralSky& sky,
                                                 ImageHandle cube, ImageHandle* mirror) {
    const bool with_mirror = mirror && mirror->valid();
    const ImageDesc desc = graph.resource(cube).image_desc;
    if (Status fits = check_cube_mirror(graph, cube, mirror, "procedural sky to cube"); !fits) return fits.error();
    // Every texel with 4 x 4 taps, then those near the sun again with 16 x 16.
    ImageHandle current = cube, mirror_current = with_mirror ? *mirror : ImageHandle{};
    for (const bool sun_texels : {false, true}) {
        const ShaderDefine mirror_define{"FACET_MIRROR", "1"}, sun_define{"FACET_SUN_TEXELS", "1"};
        const std::vector<ShaderDefine> defines =
            with_mirror ? (sun_texels ? std::vector{mirror_define, sun_define} : std::vector{mirror_define})
                        : (sun_texels ? std::vector{sun_define} : std::vector<ShaderDefine>{});
        auto pipeline = programs.compute("ibl/procedural_sky_cube.comp", defines);
        if (!pipeline) return pipeline.error();
        const ImageHandle cube_in = current, mirror_in = mirror_current;
        SkyParams params = sky_params(sky);
        // The sun pass's reach: the disk's radius plus two texels (at most 2 / n radians
        // across), as the cosine the texels' centres are compared with (the zenith's w).
        const double reach = sky.sun_angular_radius_deg * pi / 180.0 + 4.0 / desc.width;
        params.zenith[3] = float(std::cos(std::min(reach, pi)));
        graph.add_compute_pass(sun_texels ? "procedural sky to cube (sun)" : "procedural sky to cube", [&](PassBuilder& b) {
            current = b.write_storage(cube_in, ImageRange::mip(0));
            if (with_mirror) mirror_current = b.write_storage(mirror_in, ImageRange::mip(0));
        }, [p = pipeline.value(), params, cube, mirror_in, with_mirror, n = desc.width](PassContext& pc) {
            p->bind(pc.cmd());
            std::vector<DescriptorWrite> writes = {
                DescriptorWrite::storage_image(pc.view(cube, ImageRange::mip(0), VK_IMAGE_VIEW_TYPE_2D_ARRAY))};
            if (with_mirror)
                writes.push_back(
                    DescriptorWrite::storage_image(pc.view(mirror_in, ImageRange::mip(0), VK_IMAGE_VIEW_TYPE_2D_ARRAY)));
            p->push_descriptors(pc.cmd(), writes);
            p->push_constants(pc.cmd(), params);
            dispatch_cube(pc, *p, n);
        });
    }
    if (with_mirror) *mirror = mirror_current;
    return current;
}

}  // namespace facet
