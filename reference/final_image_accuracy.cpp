#include <facet/reference/final_image_accuracy.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <thread>
#include <vector>

namespace facet::test {
namespace {

Vec3 unit(const Vec3& a) {
    const double l = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    return l > 0 ? Vec3{a[0] / l, a[1] / l, a[2] / l} : Vec3{0, 0, 0};
}

struct Pixel {
    size_t index;  // y * width + x
    Vec3 n, v;
    TruthMaterial material;
    int group;
};

int group_of(double roughness, double metallic) {
    const int band = roughness < 0.4 ? 0 : roughness < 0.6 ? 1 : roughness < 0.8 ? 2 : 3;
    return 2 * band + (metallic >= 0.5 ? 1 : 0);
}

}  // namespace

FinalImageTruth final_image_truth(const FinalImageViews& in, const Vec3& eye, const TexelLights& env, BrdfModel model,
                                  const AccuracySettings& s) {
    const size_t count = size_t(in.width) * in.height;
    for (std::span<const float> image : {in.hdr, in.normal, in.position, in.basecolor, in.metallic, in.roughness})
        if (image.size() != count * 4)
            throw std::invalid_argument("final_image_accuracy: an image is not " + std::to_string(in.width) + " x " +
                                        std::to_string(in.height) + " RGBA");
    const bool coated = !in.clearcoat.empty(), filmed = !in.iridescence.empty(), stretched = !in.anisotropy.empty(),
               sheen = !in.sheen.empty(), through = !in.transmission.empty();
    // The extensions' views are optional: empty, or of the frame's size.
    const std::pair<const char*, std::span<const float>> optional[] = {
        {"sheen", in.sheen},         {"anisotropy", in.anisotropy},     {"iridescence", in.iridescence},
        {"clear coat", in.clearcoat}, {"clear coat normal", in.clearcoat_normal}, {"transmission", in.transmission}};
    for (const auto& [name, image] : optional)
        if (!image.empty() && image.size() != count * 4)
            throw std::invalid_argument(std::string("final_image_accuracy: the ") + name + " image is not " +
                                        std::to_string(in.width) + " x " + std::to_string(in.height) + " RGBA");
    if (coated && in.clearcoat_normal.size() != count * 4)
        throw std::invalid_argument("final_image_accuracy: the clear coat's normal image is missing");
    // Eligible pixels: covered (the views' alpha and the resolved colour's coverage both
    // 1, so MSAA edges are left out), facing the eye and rough enough.
    std::vector<Pixel> eligible;
    for (size_t i = 0; i < count; ++i) {
        if (in.position[i * 4 + 3] < 1.0f || in.normal[i * 4 + 3] < 1.0f || in.hdr[i * 4 + 3] < 1.0f) continue;
        const double roughness = in.roughness[i * 4], metallic = in.metallic[i * 4];
        if (!(roughness >= s.min_roughness)) continue;
        const Vec3 n = unit({in.normal[i * 4], in.normal[i * 4 + 1], in.normal[i * 4 + 2]});
        const Vec3 v = unit({eye[0] - in.position[i * 4], eye[1] - in.position[i * 4 + 1], eye[2] - in.position[i * 4 + 2]});
        if (!(n[0] * v[0] + n[1] * v[1] + n[2] * v[2] > s.min_n_v)) continue;
        TruthMaterial m;
        m.albedo = {in.basecolor[i * 4], in.basecolor[i * 4 + 1], in.basecolor[i * 4 + 2]};
        m.metallic = metallic;
        m.roughness = roughness;
        m.dielectric_f0 = s.dielectric_f0;
        m.specular_weight = s.specular_weight;
        m.specular_color = s.specular_color;
        if (coated && in.clearcoat[i * 4] > 0) {
            m.clearcoat = in.clearcoat[i * 4];
            m.clearcoat_roughness = in.clearcoat[i * 4 + 1];
            m.clearcoat_normal = unit({in.clearcoat_normal[i * 4], in.clearcoat_normal[i * 4 + 1],
                                       in.clearcoat_normal[i * 4 + 2]});
        }
        if (filmed && in.iridescence[i * 4] > 0) {
            m.iridescence = in.iridescence[i * 4];
            m.iridescence_ior = in.iridescence[i * 4 + 1];
            m.iridescence_thickness = in.iridescence[i * 4 + 2];
        }
        if (stretched && in.anisotropy[i * 4 + 3] > 0) {
            m.anisotropy = in.anisotropy[i * 4 + 3];
            m.anisotropy_t = {in.anisotropy[i * 4], in.anisotropy[i * 4 + 1], in.anisotropy[i * 4 + 2]};
        }
        if (sheen) {
            m.sheen_color = {in.sheen[i * 4], in.sheen[i * 4 + 1], in.sheen[i * 4 + 2]};
            m.sheen_roughness = in.sheen[i * 4 + 3];
        }
        if (through) m.transmission = in.transmission[i * 4];
        eligible.push_back({i, n, v, m, group_of(roughness, metallic)});
    }
    // An even stride through the eligible pixels (scan order) down to the budget.
    std::vector<Pixel> pixels;
    if (eligible.size() <= s.max_pixels) pixels = std::move(eligible);
    else
        for (size_t k = 0; k < s.max_pixels; ++k) pixels.push_back(eligible[k * eligible.size() / s.max_pixels]);

    const auto start = std::chrono::steady_clock::now();
    std::vector<Vec3> truth(pixels.size());
    const unsigned threads = std::max(1u, s.threads ? s.threads : std::thread::hardware_concurrency());
    auto work = [&](size_t first) {
        for (size_t k = first; k < pixels.size(); k += threads) {
            const Pixel& p = pixels[k];
            truth[k] = environment_truth(env, model, p.material, p.n, p.v);
            for (double& c : truth[k]) c *= s.intensity;
        }
    };
    std::vector<std::thread> pool;
    for (unsigned t = 1; t < threads; ++t) pool.emplace_back(work, t);
    work(0);
    for (std::thread& t : pool) t.join();

    FinalImageTruth out;
    out.width = in.width;
    out.height = in.height;
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    for (size_t k = 0; k < pixels.size(); ++k) {
        out.index.push_back(pixels[k].index);
        out.group.push_back(pixels[k].group);
        out.luminance.push_back(luminance(truth[k]));
    }
    return out;
}

FinalImageAccuracy final_image_accuracy(const FinalImageTruth& truth, std::span<const float> hdr) {
    if (hdr.size() != size_t(truth.width) * truth.height * 4)
        throw std::invalid_argument("final_image_accuracy: the render is not " + std::to_string(truth.width) + " x " +
                                    std::to_string(truth.height) + " RGBA");
    FinalImageAccuracy out;
    out.truth_seconds = truth.seconds;
    for (int g = 0; g < 8; ++g) out.groups[size_t(g)] = measure_group(g);
    for (size_t k = 0; k < truth.index.size(); ++k) {
        const double t = truth.luminance[k];
        if (!(t > 0)) continue;  // a black environment has no relative error to measure
        const double r = luminance(&hdr[truth.index[k] * 4]);
        const double signed_rel = (r - t) / t;
        GroupError& g = out.groups[size_t(truth.group[k])];
        ++g.pixels;
        g.mean_rel += std::abs(signed_rel);
        g.mean_signed += signed_rel;
        // NaN or Inf in the render must show, not vanish in max().
        g.max_rel = std::isfinite(signed_rel) ? std::max(g.max_rel, std::abs(signed_rel)) : signed_rel;
        ++out.pixels;
    }
    for (int g = 0; g < 8; ++g) {
        GroupError& e = out.groups[size_t(g)];
        if (e.pixels == 0) continue;
        e.mean_rel /= double(e.pixels);
        e.mean_signed /= double(e.pixels);
        if (out.worst < 0 || !(e.mean_rel <= out.worst_mean_rel)) {
            out.worst = g;
            out.worst_mean_rel = e.mean_rel;
        }
    }
    return out;
}

FinalImageAccuracy final_image_accuracy(const FinalImageViews& views, const Vec3& eye, const TexelLights& env,
                                        BrdfModel model, const AccuracySettings& settings) {
    return final_image_accuracy(final_image_truth(views, eye, env, model, settings), views.hdr);
}

FinalImageAccuracy final_image_accuracy(const FinalImageViews& views, const Vec3& eye, const Equirect& env,
                                        BrdfModel model, const AccuracySettings& settings) {
    return final_image_accuracy(views, eye, texel_lights(env), model, settings);
}

GroupError measure_group(int g) {
    GroupError e;
    e.roughness_min = 0.2 + 0.2 * (g / 2);
    e.roughness_max = g / 2 == 3 ? 1.0 : 0.4 + 0.2 * (g / 2);
    e.metal = g % 2 == 1;
    return e;
}

std::string group_name(const GroupError& g) {
    char text[64];
    std::snprintf(text, sizeof text, "roughness [%.1f,%.1f%c %s", g.roughness_min, g.roughness_max,
                  g.roughness_max >= 1.0 ? ']' : ')', g.metal ? "metal" : "dielectric");
    return text;
}

std::string format_accuracy_table(const FinalImageAccuracy& a) {
    std::string out;
    char line[160];
    std::snprintf(line, sizeof line, "  %-32s %7s %10s %9s %10s\n", "group", "pixels", "mean err%", "max err%",
                  "signed%");
    out += line;
    for (const GroupError& g : a.groups) {
        std::snprintf(line, sizeof line, "  %-32s %7zu %10.2f %9.2f %+10.2f\n", group_name(g).c_str(), g.pixels,
                      100 * g.mean_rel, 100 * g.max_rel, 100 * g.mean_signed);
        out += line;
    }
    if (a.worst >= 0)
        std::snprintf(line, sizeof line, "  worst: %s, mean %.2f%%\n", group_name(a.groups[size_t(a.worst)]).c_str(),
                      100 * a.worst_mean_rel);
    else
        std::snprintf(line, sizeof line, "  worst: none (no pixel measured)\n");
    out += line;
    return out;
}

}  // namespace facet::test
