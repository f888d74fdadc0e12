#include <facet/ibl/method_domain.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include <facet/core/shared_constants.h>
#include <facet/ibl/light_extraction.h>

namespace facet {

EnvironmentStats environment_stats(std::span<const float> rgba, uint32_t width, uint32_t height, bool content) {
    EnvironmentStats stats;
    stats.width = width;
    stats.height = height;
    const size_t n = size_t(width) * height;
    if (n == 0) return stats;
    if (!content) {
        stats.black = true;
        for (size_t i = 0; i < n && stats.black; ++i)
            stats.black = !(luminance(rgba[i * 4], rgba[i * 4 + 1], rgba[i * 4 + 2]) > 0);
        return stats;
    }
    std::vector<double> lum(n);
    double peak = 0;
    for (size_t i = 0; i < n; ++i) {
        lum[i] = std::max(0.0, luminance(rgba[i * 4], rgba[i * 4 + 1], rgba[i * 4 + 2]));
        peak = std::max(peak, lum[i]);
    }
    std::nth_element(lum.begin(), lum.begin() + long(n / 2), lum.end());
    const double median = lum[n / 2];
    stats.black = peak <= 0;
    stats.peak_over_median = median > 0 ? peak / median : (peak > 0 ? std::numeric_limits<double>::infinity() : 1);
    // Compact lights as light extraction would find them (any size, any number).
    LightExtractionSettings find;
    find.max_lights = 64;
    find.max_solid_angle = 0.05;
    find.min_power_fraction = 0.005;
    find.max_residual_range = 0;  // compact regions only
    const LightExtraction lights = extract_lights(rgba, width, height, find);
    stats.compact_light_power = lights.extracted_power_fraction;
    for (const DiskLight& l : lights.lights) stats.widest_light_radius = std::max(stats.widest_light_radius, l.angular_radius);
    return stats;
}

std::string documented_bound(IrradianceMethod method) {
    return method == IrradianceMethod::convolve ? "within 2% everywhere"
                                                : "within 5% on skies without compact lights";
}

std::string documented_bound(SpecularMethod method, uint32_t sample_count) {
    switch (method) {
    case SpecularMethod::automatic:
    case SpecularMethod::hybrid:
    case SpecularMethod::convolve: return "within 5% everywhere";
    case SpecularMethod::filtered:
        return sample_count >= 1024 ? "within 5% everywhere" : "within 5% without very bright lights";
    case SpecularMethod::importance: return "within 10% without lights far brighter than their surroundings";
    case SpecularMethod::mips: return "none: a box filter, not a GGX lobe";
    }
    return "";
}

bool method_warnings_read_content(const IblSettings& settings) {
    const SpecularSettings& sp = settings.specular;
    return (settings.want_irradiance && settings.irradiance.method != IrradianceMethod::convolve) ||
           (settings.want_specular &&
            (sp.method == SpecularMethod::mips || sp.method == SpecularMethod::importance ||
             (sp.method == SpecularMethod::filtered && sp.sample_count < 1024)));
}

std::vector<std::string> method_warnings(const EnvironmentStats& s, const IblSettings& settings) {
    std::vector<std::string> warnings;
    if (s.black) return warnings;
    if (s.height < 16 || s.width < 32)
        warnings.push_back("input of " + std::to_string(s.width) + "x" + std::to_string(s.height) +
                           ": its texels span more than 11 degrees, so every result depends on how they are "
                           "interpolated (bilinearly here); against a piecewise-constant reading expect errors "
                           "above 10%");
    const bool lights = s.compact_light_power > 0.05;
    const std::string power = std::to_string(int(std::lround(100 * s.compact_light_power))) + "%";
    if (settings.want_irradiance) {
        const IrradianceSettings& i = settings.irradiance;
        switch (i.method) {
        case IrradianceMethod::convolve: break;
        case IrradianceMethod::riemann:
            if (lights || i.riemann_step > 0.025f)
                warnings.push_back("irradiance riemann: compact lights hold " + power +
                                   " of the power and a step of " + std::to_string(i.riemann_step) +
                                   " rad samples them unevenly; expect errors above 5% (convolve is exact)");
            break;
        case IrradianceMethod::sh9:
            if (lights)
                warnings.push_back("irradiance sh9: compact lights hold " + power +
                                   " of the power; nine coefficients cannot hold them, expect errors above 5%" +
                                   (i.sh9_windowing ? "" : " and negative irradiance (ringing)"));
            break;
        case IrradianceMethod::blur:
        case IrradianceMethod::lowmip:
            if (lights || s.peak_over_median > 100)
                warnings.push_back(std::string("irradiance ") + irradiance_method_name(i.method) +
                                   ": a high dynamic range input (peak " + std::to_string(int(s.peak_over_median)) +
                                   "x the median) is not a cosine convolution of a small level; expect errors "
                                   "well above 5%");
            break;
        }
    }
    if (settings.want_specular) {
        const SpecularSettings& sp = settings.specular;
        if (sp.method == SpecularMethod::mips && s.peak_over_median > 1.5)
            warnings.push_back("specular mips: the environment's box-filtered mips are not GGX lobes; expect errors "
                               "of tens of percent on rough levels");
        if (sp.method == SpecularMethod::importance && (lights || s.peak_over_median > 100))
            warnings.push_back("specular importance: " + std::to_string(sp.sample_count) +
                               " samples per texel over a light " + std::to_string(int(s.peak_over_median)) +
                               "x the median give fireflies; use filtered, convolve or automatic");
        if (sp.method == SpecularMethod::filtered && sp.sample_count < 1024 && (lights || s.peak_over_median > 100))
            warnings.push_back("specular filtered: " + std::to_string(sp.sample_count) +
                               " samples are too few for this dynamic range; expect errors above 5%");
    }
    return warnings;
}

}  // namespace facet
