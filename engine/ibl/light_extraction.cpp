#include <facet/ibl/light_extraction.h>

#include <algorithm>
#include <cmath>

#include <facet/core/shared_constants.h>
#include "io/equirect.h"

namespace facet {
namespace {

double luminance(const float* t) { return facet::luminance(t[0], t[1], t[2]); }

struct Region {
    std::vector<uint32_t> texels;
    double power = 0, solid_angle = 0;  // of the luminance given
};

// Connected regions of texels above `threshold` (8-neighbours, u wraps around); `label`
// gets each texel's region or -1.
std::vector<Region> connected_regions(const std::vector<double>& lum, double threshold, uint32_t w, uint32_t h,
                                      std::vector<int32_t>& label) {
    const size_t n = size_t(w) * h;
    label.assign(n, -1);
    std::vector<Region> regions;
    for (size_t start = 0; start < n; ++start) {
        if (label[start] >= 0 || lum[start] <= threshold) continue;
        Region r;
        std::vector<uint32_t> stack{uint32_t(start)};
        label[start] = int32_t(regions.size());
        while (!stack.empty()) {
            const uint32_t i = stack.back();
            stack.pop_back();
            r.texels.push_back(i);
            const uint32_t x = i % w, y = i / w;
            const double omega = equirect_texel_solid_angle(y, w, h);
            r.power += lum[i] * omega;
            r.solid_angle += omega;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int yy = int(y) + dy;
                    if (yy < 0 || yy >= int(h)) continue;
                    const uint32_t xx = uint32_t((int(x) + dx + int(w)) % int(w));
                    const size_t j = size_t(yy) * w + xx;
                    if (label[j] < 0 && lum[j] > threshold) {
                        label[j] = int32_t(regions.size());
                        stack.push_back(uint32_t(j));
                    }
                }
        }
        regions.push_back(std::move(r));
    }
    return regions;
}

// Splits a region's texels into `pieces` compact parts by k-means on their directions
// (weighted by the power above the fill plus their solid angle, so that every texel
// belongs somewhere), started from texels spread by farthest-point selection.
std::vector<std::vector<uint32_t>> split_region(const std::vector<uint32_t>& texels, std::span<const float> rgba,
                                                const glm::dvec3& fill, uint32_t w, uint32_t h, uint32_t pieces) {
    if (pieces <= 1 || texels.size() <= pieces) return {texels};
    std::vector<glm::dvec3> dir(texels.size());
    std::vector<double> weight(texels.size());
    for (size_t t = 0; t < texels.size(); ++t) {
        const uint32_t i = texels[t];
        dir[t] = equirect_texel_direction(i % w, i / w, w, h);
        const glm::dvec3 excess = glm::max(glm::dvec3(rgba[i * 4], rgba[i * 4 + 1], rgba[i * 4 + 2]) - fill, 0.0);
        const double omega = equirect_texel_solid_angle(i / w, w, h);
        weight[t] = (facet::luminance(excess.x, excess.y, excess.z) + 1e-6) * omega;
    }
    std::vector<glm::dvec3> centre{dir[size_t(std::max_element(weight.begin(), weight.end()) - weight.begin())]};
    while (centre.size() < pieces) {
        size_t farthest = 0;
        double far_dot = 2;
        for (size_t t = 0; t < dir.size(); ++t) {
            double nearest = -2;
            for (const glm::dvec3& c : centre) nearest = std::max(nearest, glm::dot(dir[t], c));
            if (nearest < far_dot) far_dot = nearest, farthest = t;
        }
        centre.push_back(dir[farthest]);
    }
    std::vector<uint32_t> owner(texels.size(), 0);
    for (int iteration = 0; iteration < 12; ++iteration) {
        for (size_t t = 0; t < dir.size(); ++t) {
            double best = -2;
            for (uint32_t c = 0; c < pieces; ++c)
                if (glm::dot(dir[t], centre[c]) > best) best = glm::dot(dir[t], centre[c]), owner[t] = c;
        }
        std::vector<glm::dvec3> sum(pieces, glm::dvec3(0.0));
        for (size_t t = 0; t < dir.size(); ++t) sum[owner[t]] += weight[t] * dir[t];
        for (uint32_t c = 0; c < pieces; ++c)
            if (glm::length(sum[c]) > 0) centre[c] = glm::normalize(sum[c]);
    }
    std::vector<std::vector<uint32_t>> out(pieces);
    for (size_t t = 0; t < texels.size(); ++t) out[owner[t]].push_back(texels[t]);
    return out;
}

// The residual's luminance above `level` as the lights still free: its connected regions of
// at least min_power_fraction of the whole (a softbox and its halo; scattered bright texels
// stay in the map: one light for them all would sit between them), each split by direction
// into pieces. A piece is a cap around its power-weighted centroid whose radius gives the
// same mean 1 - cos(angle to the centre) as the piece's power (a uniform cap of radius theta
// has (1 - cos theta) / 2): the lobe sees the piece's power, centre and spread. Its texels
// keep their colour, scaled to `level`.
void extract_excess(LightExtraction& out, uint32_t w, uint32_t h, double level, double total_power,
                    const LightExtractionSettings& settings) {
    std::vector<float>& map = out.residual;
    const size_t n = size_t(w) * h;
    std::vector<double> lum(n);
    for (size_t i = 0; i < n; ++i) lum[i] = luminance(&map[i * 4]);
    std::vector<int32_t> label;
    std::vector<Region> regions = connected_regions(lum, level, w, h, label);
    for (Region& r : regions) {  // the power above the level
        r.power = 0;
        for (uint32_t i : r.texels) r.power += (lum[i] - level) * equirect_texel_solid_angle(i / w, w, h);
    }
    std::sort(regions.begin(), regions.end(), [](const Region& a, const Region& b) { return a.power > b.power; });
    // The regions that get lights, one each at first; the rest of the free lights go one
    // at a time to the region with the most power per light (while it has room: pieces of
    // at least max_solid_angle).
    const uint32_t free = settings.max_lights - uint32_t(out.lights.size());
    size_t count = 0;
    while (count < regions.size() && count < free && regions[count].power >= settings.min_power_fraction * total_power)
        ++count;
    regions.resize(count);
    std::vector<uint32_t> pieces(count, 1);
    for (uint32_t spare = free - uint32_t(count); spare > 0; --spare) {
        size_t best = count;
        for (size_t k = 0; k < count; ++k)
            if (pieces[k] < uint32_t(std::ceil(regions[k].solid_angle / settings.max_solid_angle - 1e-9)) &&
                (best == count || regions[k].power / pieces[k] > regions[best].power / pieces[best]))
                best = k;
        if (best == count) break;
        ++pieces[best];
    }
    std::vector<float> excess(map.size(), 0.0f);  // split_region weighs texels by it (fill 0)
    for (size_t k = 0; k < count; ++k) {
        const Region& r = regions[k];
        for (uint32_t i : r.texels) {
            const float keep = float(level / lum[i]);
            for (size_t c = 0; c < 3; ++c) {
                excess[i * 4 + c] = map[i * 4 + c] * (1.0f - keep);
                map[i * 4 + c] *= keep;
            }
        }
        for (const std::vector<uint32_t>& piece : split_region(r.texels, excess, glm::dvec3(0.0), w, h, pieces[k])) {
            glm::dvec3 power(0.0), centroid(0.0);
            for (uint32_t i : piece) {
                const double omega = equirect_texel_solid_angle(i / w, w, h);
                const glm::dvec3 e(excess[size_t(i) * 4], excess[size_t(i) * 4 + 1], excess[size_t(i) * 4 + 2]);
                power += e * omega;
                centroid += facet::luminance(e.x, e.y, e.z) * omega * equirect_texel_direction(i % w, i / w, w, h);
            }
            const double piece_power = facet::luminance(power.x, power.y, power.z);
            if (piece.empty() || piece_power <= 0 || glm::length(centroid) <= 0) continue;
            const glm::dvec3 centre = glm::normalize(centroid);
            double spread = 0;  // power-weighted mean of 1 - cos(angle to the centre)
            for (uint32_t i : piece) {
                const float* e = &excess[size_t(i) * 4];
                spread += luminance(e) * equirect_texel_solid_angle(i / w, w, h) *
                          (1.0 - glm::dot(equirect_texel_direction(i % w, i / w, w, h), centre));
            }
            spread /= piece_power;
            // At least one texel's cap: a piece of one texel is not a point.
            const double cap = std::max(2.0 * spread, equirect_texel_solid_angle(h / 2, w, h) / (2 * pi));
            DiskLight light;
            light.direction = glm::vec3(centre);
            light.solid_angle = float(2 * pi * cap);
            light.angular_radius = float(std::acos(std::clamp(1.0 - cap, -1.0, 1.0)));
            light.radiance = glm::vec3(power / (2 * pi * cap));
            light.texels = uint32_t(piece.size());
            light.power_fraction = piece_power / total_power;
            out.extracted_power_fraction += light.power_fraction;
            out.lights.push_back(light);
        }
    }
}

}  // namespace

LightExtraction extract_lights(std::span<const float> rgba, uint32_t w, uint32_t h,
                               const LightExtractionSettings& settings) {
    LightExtraction out;
    out.residual.assign(rgba.begin(), rgba.end());
    const size_t n = size_t(w) * h;
    if (n == 0 || rgba.size() < n * 4) return out;
    std::vector<double> lum(n);
    double total_power = 0, peak = 0;
    for (size_t i = 0; i < n; ++i) {
        lum[i] = std::max(0.0, luminance(&rgba[i * 4]));
        total_power += lum[i] * equirect_texel_solid_angle(uint32_t(i / w), w, h);
        peak = std::max(peak, lum[i]);
    }
    std::vector<double> sorted = lum;
    std::nth_element(sorted.begin(), sorted.begin() + long(n / 2), sorted.end());
    const double median = sorted[n / 2];
    const double threshold = std::max(settings.min_ratio_to_median * median, settings.min_ratio_to_peak * peak);
    if (peak <= 0 || total_power <= 0) return out;

    std::vector<int32_t> label;
    const std::vector<Region> regions = connected_regions(lum, threshold, w, h, label);
    std::vector<size_t> order(regions.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return regions[a].power > regions[b].power; });

    for (size_t k : order) {
        const Region& r = regions[k];
        const double fraction = r.power / total_power;
        if (fraction < settings.min_power_fraction) break;  // sorted: the rest are smaller
        if (r.solid_angle > settings.max_region_solid_angle) {
            out.notes.push_back("a bright region of " + std::to_string(r.solid_angle) +
                                " sr is too wide to be a light; it stays in the map");
            continue;
        }
        // Regions wider than one light (a softbox, a window, a low sun's glow) become
        // several disks, one per piece of at most max_solid_angle.
        const uint32_t pieces = uint32_t(std::ceil(r.solid_angle / settings.max_solid_angle - 1e-9));
        if (out.lights.size() + pieces > settings.max_lights) {
            out.notes.push_back("a bright region of " + std::to_string(r.solid_angle) + " sr needs " +
                                std::to_string(pieces) + " lights, over the limit of " +
                                std::to_string(settings.max_lights) + "; it stays in the map");
            continue;
        }
        // The fill: the mean of the texels just outside the region (the surrounding sky).
        glm::dvec3 fill(0.0);
        double ring_weight = 0;
        for (uint32_t i : r.texels) {
            const uint32_t x = i % w, y = i / w;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int yy = int(y) + dy;
                    if (yy < 0 || yy >= int(h)) continue;
                    const size_t j = size_t(yy) * w + uint32_t((int(x) + dx + int(w)) % int(w));
                    if (label[j] == int32_t(k)) continue;
                    fill += glm::dvec3(rgba[j * 4], rgba[j * 4 + 1], rgba[j * 4 + 2]);
                    ring_weight += 1;
                }
        }
        if (ring_weight > 0) fill /= ring_weight;
        for (const std::vector<uint32_t>& piece : split_region(r.texels, rgba, fill, w, h, pieces)) {
            // Power above the fill, its direction (power-weighted) and solid angle.
            glm::dvec3 power(0.0), centroid(0.0);
            double solid_angle = 0;
            for (uint32_t i : piece) {
                const double omega = equirect_texel_solid_angle(i / w, w, h);
                const glm::dvec3 excess = glm::max(glm::dvec3(rgba[i * 4], rgba[i * 4 + 1], rgba[i * 4 + 2]) - fill, 0.0);
                power += excess * omega;
                solid_angle += omega;
                centroid += (facet::luminance(excess.x, excess.y, excess.z) + 1e-12) * omega *
                            equirect_texel_direction(i % w, i / w, w, h);
                for (int c = 0; c < 3; ++c) out.residual[i * 4 + size_t(c)] = float(fill[c]);
            }
            if (piece.empty() || glm::length(centroid) <= 0) continue;
            const double piece_fraction = facet::luminance(power.x, power.y, power.z) / total_power;
            DiskLight light;
            light.direction = glm::vec3(glm::normalize(centroid));
            light.solid_angle = float(solid_angle);
            light.angular_radius = float(std::acos(std::clamp(1.0 - solid_angle / (2 * pi), -1.0, 1.0)));
            light.radiance = glm::vec3(power / solid_angle);
            light.texels = uint32_t(piece.size());
            light.power_fraction = pieces == 1 ? fraction : piece_fraction;
            out.extracted_power_fraction += light.power_fraction;
            out.lights.push_back(light);
        }
    }
    if (settings.max_residual_range > 0 && out.lights.size() < settings.max_lights && median > 0) {
        double residual_peak = 0;
        for (size_t i = 0; i < n; ++i) residual_peak = std::max(residual_peak, luminance(&out.residual[i * 4]));
        if (residual_peak > settings.max_residual_range * median)
            extract_excess(out, w, h, settings.max_residual_range * median, total_power, settings);
    }
    return out;
}

}  // namespace facet
