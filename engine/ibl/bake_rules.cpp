#include <facet/ibl/bake_rules.h>

#include <algorithm>

#include <facet/core/hash.h>
#include <facet/ibl/method_domain.h>
#include <facet/render/specular_lobes.h>

namespace facet {

IblSettings ibl_settings_for_scene(IblSettings requested, const SceneNeeds& needs, bool multiscatter) {
    requested.want_irradiance = requested.want_irradiance && (needs.diffuse || multiscatter);
    // The fitted lookups read kernels narrower than the surface's (render/specular_lobes.h).
    requested.specular.min_roughness =
        std::max(requested.specular.min_roughness, lowest_lookup_roughness(needs.min_roughness));
    return requested;
}

uint32_t light_split_level(std::span<const DiskLight> lights, uint32_t /*specular_levels*/) {
    return lights.empty() ? 0 : 1;
}

std::vector<std::string> bake_warnings(const EnvironmentSource& analysed, const IblSettings& resolved) {
    const bool content = method_warnings_read_content(resolved);
    if (analysed.sky && !content) {
        // All the warnings read is the size and whether there is any light at all, which
        // a sky's parameters say without rendering it.
        EnvironmentStats stats;
        stats.width = analysed.width;
        stats.height = analysed.height;
        stats.black = analysed.sky->black();
        return method_warnings(stats, resolved);
    }
    if (analysed.sky || analysed.image.rgba.empty()) return {};
    return method_warnings(environment_stats(analysed.image.rgba, analysed.width, analysed.height, content), resolved);
}

// What a bake makes of the same input and settings: bumped with every change to the
// passes or their rules (the LUT's channels, light extraction, the split level), so that
// a bake cache never hands out an entry made by older code of the same version number.
constexpr const char* kBakeRevision = "bake revision 9: a procedural sky's cube made from the sky itself";

std::string bake_key(const EnvironmentSource& s, const BakeSettings& b) {
    const IblSettings& o = b.ibl;
    Hash64 h;
    h.add(FACET_VERSION).add(kBakeRevision).add(s.content_hash);
    const double values[] = {double(s.width), double(s.height), double(o.cube_size), double(o.specular.levels),
                             double(b.preview_exposure), double(int(o.irradiance.method)), double(o.irradiance.size),
                             double(o.irradiance.source_size), o.irradiance.riemann_step, o.irradiance.blur_sigma,
                             double(o.irradiance.lowmip_size), double(o.irradiance.sh9_windowing),
                             double(int(o.specular.method)), double(o.specular.sample_count),
                             o.specular.automatic_convolve_from, double(o.specular.min_roughness),
                             double(o.specular.hybrid_sample_count), o.specular.excess_factor,
                             double(o.specular.hybrid_half_size_residual),
                             double(o.lut.size), double(o.lut.sample_count), double(int(o.lut.brdf)),
                             b.target_error, double(b.roughness_min), double(b.roughness_max),
                             double(o.want_irradiance), double(o.want_specular), double(o.want_lut),
                             double(b.format), double(b.extract_lights),
                             b.extraction.min_ratio_to_median, b.extraction.min_ratio_to_peak,
                             b.extraction.max_solid_angle, b.extraction.min_power_fraction,
                             double(b.extraction.max_lights), b.extraction.max_region_solid_angle};
    h.add(values, sizeof values);
    return h.hex();
}

}  // namespace facet
