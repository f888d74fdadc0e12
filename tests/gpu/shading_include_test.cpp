// shaders/facet/shading.glsl as a host's own shader uses it: a compute shader of the
// test's own (its own bindings) includes "facet/shading.glsl" and calls it; the values are
// checked against formulas written here independently in double precision (the
// KHR_lights_punctual falloff, the thesis' BRDF, the bake's lod rule). The environment
// composition is covered by forward_render_test (white furnace, energy, both Smith terms).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "support/compute_probe.h"
#include "support/gpu_test.h"

namespace facet {
namespace {

constexpr double pi = 3.14159265358979323846;

struct V3 {
    double x, y, z;
};
V3 operator+(V3 a, V3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
V3 operator*(V3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
double dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
V3 normalize(V3 a) { return a * (1.0 / std::sqrt(dot(a, a))); }
V3 cross(V3 a, V3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }

std::string probe(const std::string& body) {
    return "#version 460\n#include \"facet/shading.glsl\"\nlayout(local_size_x = 1) in;\n"
           "layout(std430, binding = 0) writeonly buffer Out { float values[]; };\n"
           "void put(uint i, vec3 v) { values[i] = v.x; values[i + 1u] = v.y; values[i + 2u] = v.z; }\n"
           "void main() {\n" +
           body + "}\n";
}

class ShadingIncludeTest : public test::GpuTest {};

// KHR_lights_punctual: I / d^2 windowed by clamp(1 - (d / range)^4, 0, 1); spot cone
// clamp(cos * scale + offset, 0, 1)^2 with scale = 1 / (cos inner - cos outer).
TEST_F(ShadingIncludeTest, PunctualFalloffFollowsKhrLightsPunctual) {
    const double inner = 10 * pi / 180, outer = 30 * pi / 180, at = 20 * pi / 180;
    const double scale = 1 / (std::cos(inner) - std::cos(outer)), offset = -std::cos(outer) * scale;
    const std::string body = R"(
    vec3 l;
    FacetPunctualLight light;
    light.type = FACET_LIGHT_POINT;
    light.position = vec3(0.0, 0.0, 2.0);
    light.range_m = 3.0;
    light.direction = vec3(0.0);
    light.intensity = vec3(10.0, 20.0, 30.0);
    put(0u, facet_punctual_incidence(light, vec3(0.0), l));
    put(3u, l);
    light.range_m = 0.0;
    put(6u, facet_punctual_incidence(light, vec3(0.0), l));
    light.type = FACET_LIGHT_SPOT;
    light.position = vec3(0.0, 2.0, 0.0);
    light.direction = vec3(0.0, -3.0, 0.0);  // not unit: normalised by the function
    light.intensity = vec3(1.0);
    light.cone_scale = )" + std::to_string(scale) + R"(;
    light.cone_offset = )" + std::to_string(offset) + R"(;
    put(9u, facet_punctual_incidence(light, vec3(2.0 * tan()" + std::to_string(at) + R"(), 0.0, 0.0), l));
    put(12u, facet_punctual_incidence(light, vec3(3.0, 0.0, 0.0), l));
    light.type = FACET_LIGHT_DIRECTIONAL;
    light.direction = vec3(0.0, -2.0, 0.0);
    light.intensity = vec3(5.0);
    put(15u, facet_punctual_incidence(light, vec3(7.0), l));
    put(18u, l);
)";
    auto v = test::run_compute_probe(ctx(), "punctual_probe.comp", probe(body), 21);
    ASSERT_EQ(v.size(), 21u);
    const double window = 1 - std::pow(2.0 / 3.0, 4);
    EXPECT_NEAR(v[0], 10.0 / 4 * window, 1e-5);
    EXPECT_NEAR(v[2], 30.0 / 4 * window, 1e-5);
    EXPECT_NEAR(v[5], 1.0, 1e-6);  // l points at the light
    EXPECT_NEAR(v[6], 10.0 / 4, 1e-5);
    const double d2 = 4 + std::pow(2 * std::tan(at), 2);
    const double cone = std::clamp(std::cos(at) * scale + offset, 0.0, 1.0);
    EXPECT_NEAR(v[9], cone * cone / d2, 1e-5);
    EXPECT_EQ(v[12], 0.0f);  // 56 degrees off the axis: outside the outer cone
    EXPECT_NEAR(v[15], 5.0, 1e-6);
    EXPECT_NEAR(v[19], 1.0, 1e-6);  // towards the light: against its direction
}

struct Brdf {
    V3 diffuse, specular;
};

// The BRDF times n.l for unit incident radiance, written from the equations: glTF's
// (height-correlated visibility, diffuse weighted by 1 - F of the dielectric F0 0.04, the
// specular F mixed between F(0.04) and F(albedo)) or the thesis' (Schlick-GGX of factor k,
// kd = (1 - F)(1 - metallic) with F0 = mix(0.04, albedo, metallic)).
Brdf model_brdf(V3 n, V3 v, V3 l, V3 albedo, double metallic, double roughness, bool gltf, double k) {
    const bool height_correlated = gltf;
    const V3 h = normalize(v + l);
    const double nl = dot(n, l), nv = dot(n, v), nh = dot(n, h), vh = dot(v, h);
    const double alpha = roughness * roughness, a2 = alpha * alpha;
    const double t = nh * nh * (a2 - 1) + 1;
    const double D = a2 / (pi * t * t);
    double DG;  // D G / (4 n.l n.v)
    if (height_correlated) {
        DG = D * 0.5 / (nl * std::sqrt(nv * nv * (1 - a2) + a2) + nv * std::sqrt(nl * nl * (1 - a2) + a2));
    } else {
        const double G = nv / (nv * (1 - k) + k) * nl / (nl * (1 - k) + k);
        DG = D * G / (4 * nl * nv);
    }
    auto channel = [&](double a, double& d, double& s) {
        const double w = std::pow(1 - vh, 5);
        if (gltf) {
            const double Fd = 0.04 + 0.96 * w, Fm = a + (1 - a) * w;
            d = (1 - Fd) * (1 - metallic) * a / pi * nl;
            s = (Fd * (1 - metallic) + Fm * metallic) * DG * nl;
            return;
        }
        const double f0 = 0.04 * (1 - metallic) + a * metallic;
        const double F = f0 + (1 - f0) * w;
        d = (1 - F) * (1 - metallic) * a / pi * nl;
        s = F * DG * nl;
    };
    Brdf b;
    channel(albedo.x, b.diffuse.x, b.specular.x);
    channel(albedo.y, b.diffuse.y, b.specular.y);
    channel(albedo.z, b.diffuse.z, b.specular.z);
    return b;
}

TEST_F(ShadingIncludeTest, ReflectLightIsTheModelsBrdf) {
    const std::string body = R"(
    FacetSurface s = facet_surface(FACET_BRDF_THESIS, vec3(0.0, 0.0, 1.0), vec3(0.8, 0.5, 0.2), 0.3, 0.5, 0.04, 1.0, 1.0);
    vec3 v = normalize(vec3(0.3, 0.1, 1.0)), l = normalize(vec3(-0.5, 0.2, 0.8));
    float NdotV = clamp(dot(s.n, v), 0.0, 1.0);
    vec3 d, sp;
    facet_reflect_light(s, v, NdotV, l, vec3(2.0), true, d, sp);
    put(0u, d); put(3u, sp);
    s.brdf = FACET_BRDF_GLTF;
    facet_reflect_light(s, v, NdotV, l, vec3(2.0), true, d, sp);
    put(6u, d); put(9u, sp);
    facet_reflect_light(s, v, NdotV, vec3(0.0, 0.6, -0.8), vec3(2.0), true, d, sp);
    put(12u, d + sp);
)";
    auto v = test::run_compute_probe(ctx(), "reflect_probe.comp", probe(body), 15);
    ASSERT_EQ(v.size(), 15u);
    const V3 n{0, 0, 1}, view = normalize({0.3, 0.1, 1.0}), l = normalize({-0.5, 0.2, 0.8}), albedo{0.8, 0.5, 0.2};
    const double k = (0.5 + 1) * (0.5 + 1) / 8;
    for (bool correlated : {false, true}) {
        const Brdf b = model_brdf(n, view, l, albedo, 0.3, 0.5, correlated, k);
        const size_t o = correlated ? 6 : 0;
        const double d[3] = {b.diffuse.x, b.diffuse.y, b.diffuse.z}, s[3] = {b.specular.x, b.specular.y, b.specular.z};
        for (int c = 0; c < 3; ++c) {
            const std::string what = std::to_string(c) + (correlated ? " glTF" : " thesis");
            EXPECT_NEAR(v[o + c], 2 * d[c], 1e-5 * std::max(1.0, d[c])) << "diffuse " << what;
            EXPECT_NEAR(v[o + 3 + c], 2 * s[c], 1e-5 * std::max(1.0, s[c])) << "specular " << what;
        }
    }
    for (int c = 12; c < 15; ++c) EXPECT_EQ(v[c], 0.0f);  // light from below the surface
}

// lod = roughness x (levels - 1); a disk's specular fades in across the level below the
// first one baked without the extracted lights.
TEST_F(ShadingIncludeTest, SpecularLodAndDiskWeightFollowTheBakeLevels) {
    const std::string body = R"(
    values[0] = facet_specular_lod(0.5, 9.0);
    values[1] = facet_specular_lod(1.0, 9.0);
    values[2] = facet_disk_specular_weight(0.5, 9.0, 4.0);
    values[3] = facet_disk_specular_weight(0.4, 9.0, 4.0);
    values[4] = facet_disk_specular_weight(0.3, 9.0, 4.0);
    values[5] = facet_disk_specular_weight(0.0, 9.0, 0.0);
)";
    auto v = test::run_compute_probe(ctx(), "lod_probe.comp", probe(body), 6);
    ASSERT_EQ(v.size(), 6u);
    EXPECT_FLOAT_EQ(v[0], 4.0f);
    EXPECT_FLOAT_EQ(v[1], 8.0f);
    EXPECT_FLOAT_EQ(v[2], 1.0f);
    EXPECT_NEAR(v[3], 0.2, 1e-6);
    EXPECT_FLOAT_EQ(v[4], 0.0f);
    EXPECT_FLOAT_EQ(v[5], 1.0f);  // no split level: every level is without the lights
}

// A small disk on a rough surface is a point source of intensity L x solid angle; on a
// mirror-like surface whose reflection hits it, the mirror image L F (G = 1).
TEST_F(ShadingIncludeTest, DiskLightLimits) {
    const double theta = 0.02;
    const std::string body = R"(
    FacetDiskLight disk = facet_make_disk_light(normalize(vec3(-0.5, 0.2, 0.8)), 0.02, vec3(1000.0));
    FacetSurface s = facet_surface(FACET_BRDF_THESIS, vec3(0.0, 0.0, 1.0), vec3(0.8, 0.5, 0.2), 0.3, 0.9, 0.04, 1.0, 1.0);
    vec3 v = normalize(vec3(0.3, 0.1, 1.0));
    float NdotV = clamp(dot(s.n, v), 0.0, 1.0);
    vec3 d, sp;
    facet_disk_light(s, v, NdotV, disk, d, sp);
    put(0u, d); put(3u, sp);
    FacetSurface mirror = facet_surface(FACET_BRDF_THESIS, vec3(0.0, 0.0, 1.0), vec3(1.0, 0.5, 0.25), 1.0, 0.01, 0.04, 1.0, 1.0);
    vec3 r = reflect(-disk.direction, mirror.n);  // v such that R hits the disk's centre
    facet_disk_light(mirror, r, clamp(dot(mirror.n, r), 0.0, 1.0), disk, d, sp);
    put(6u, d); put(9u, sp);
)";
    auto v = test::run_compute_probe(ctx(), "disk_probe.comp", probe(body), 12);
    ASSERT_EQ(v.size(), 12u);
    const double omega = 2 * pi * (1 - std::cos(theta));
    const Brdf b = model_brdf({0, 0, 1}, normalize({0.3, 0.1, 1.0}), normalize({-0.5, 0.2, 0.8}), {0.8, 0.5, 0.2}, 0.3,
                               0.9, false, 0.9 * 0.9 / 2);
    EXPECT_NEAR(v[0], 1000 * omega * b.diffuse.x, 0.01 * 1000 * omega * b.diffuse.x);
    EXPECT_NEAR(v[2], 1000 * omega * b.diffuse.z, 0.01 * 1000 * omega * b.diffuse.z);
    EXPECT_NEAR(v[3], 1000 * omega * b.specular.x, 0.01 * 1000 * omega * b.specular.x);
    EXPECT_NEAR(v[5], 1000 * omega * b.specular.z, 0.01 * 1000 * omega * b.specular.z);
    // Metal: no diffuse; the mirror reflects L F(n.v), F0 = albedo.
    EXPECT_EQ(v[6], 0.0f);
    const double w = std::pow(1 - dot({0, 0, 1}, normalize({-0.5, 0.2, 0.8})), 5);
    const double albedo[3] = {1.0, 0.5, 0.25};
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(v[9 + c], 1000 * (albedo[c] + (1 - albedo[c]) * w), 0.005 * 1000 * albedo[c]);
}

// A cap of angular radius theta with R `offset` radians from its centre (rotated about R by
// `azimuth`), seen at n.v, on a surface of the model's BRDF.
struct DiskCase {
    double theta, roughness, metallic, nv, offset, azimuth;
    bool gltf;
};

struct DiskResult {
    double specular, sum_specular, diffuse, sum_diffuse;  // the green channel
};

// facet_disk_light (`point`: as a point, facet_disk_point_lobe) against a sum of the
// model's BRDF over 20000 directions spread evenly over the cap, per case.
std::vector<DiskResult> disk_against_sums(Context& context, const std::vector<DiskCase>& cases, bool point) {
    std::string body;
    std::vector<V3> normals, views, centres;
    for (size_t i = 0; i < cases.size(); ++i) {
        const DiskCase& c = cases[i];
        const V3 n{0, 0, 1}, view{std::sqrt(1 - c.nv * c.nv), 0, c.nv};
        const V3 R{-view.x, -view.y, view.z};
        // Rotate R by `offset` about an axis perpendicular to it, at `azimuth` around R.
        const V3 t1 = normalize(cross(R, {0, 1, 0})), t2 = cross(R, t1);
        const V3 axis{t1.x * std::cos(c.azimuth) + t2.x * std::sin(c.azimuth), t1.y * std::cos(c.azimuth) + t2.y * std::sin(c.azimuth),
                      t1.z * std::cos(c.azimuth) + t2.z * std::sin(c.azimuth)};
        const V3 centre = normalize({R.x * std::cos(c.offset) + axis.x * std::sin(c.offset),
                                     R.y * std::cos(c.offset) + axis.y * std::sin(c.offset),
                                     R.z * std::cos(c.offset) + axis.z * std::sin(c.offset)});
        normals.push_back(n), views.push_back(view), centres.push_back(centre);
        char line[512];
        std::snprintf(line, sizeof line,
                      "{ FacetSurface s = facet_surface(%s, vec3(0.0, 0.0, 1.0), vec3(0.9, 0.6, 0.3), %.3f, %.3f, 0.04, 1.0, 1.0);"
                      " vec3 v = vec3(%.9f, 0.0, %.9f); vec3 d, sp;"
                      " facet_disk_light(s, v, %.9f, facet_make_disk_light(vec3(%.9f, %.9f, %.9f), %.3f, vec3(100.0)), %s, d, sp);"
                      " put(%zuu, d); put(%zuu, sp); }\n",
                      c.gltf ? "FACET_BRDF_GLTF" : "FACET_BRDF_THESIS", c.metallic, c.roughness, view.x, view.z, c.nv,
                      centre.x, centre.y, centre.z, c.theta, point ? "true" : "false", 6 * i, 6 * i + 3);
        body += line;
    }
    auto v = test::run_compute_probe(context, "disk_sum_probe.comp", probe(body), 6 * cases.size());
    std::vector<DiskResult> results;
    if (v.size() != 6 * cases.size()) return results;
    for (size_t i = 0; i < cases.size(); ++i) {
        const DiskCase& c = cases[i];
        const V3 cc = centres[i];
        const V3 t1 = normalize(cross(cc, std::abs(cc.y) < 0.9 ? V3{0, 1, 0} : V3{1, 0, 0})), t2 = cross(cc, t1);
        const int samples = 20000;
        const double omega = 2 * pi * (1 - std::cos(c.theta));
        double diffuse = 0, specular = 0;
        for (int k = 0; k < samples; ++k) {
            const double z = 1 - (k + 0.5) / samples * (1 - std::cos(c.theta)), r = std::sqrt(1 - z * z), phi = k * 2.39996323;
            const V3 l{t1.x * r * std::cos(phi) + t2.x * r * std::sin(phi) + cc.x * z,
                       t1.y * r * std::cos(phi) + t2.y * r * std::sin(phi) + cc.y * z,
                       t1.z * r * std::cos(phi) + t2.z * r * std::sin(phi) + cc.z * z};
            if (l.z <= 0) continue;
            const Brdf b = model_brdf(normals[i], views[i], l, {0.9, 0.6, 0.3}, c.metallic, c.roughness, c.gltf,
                                      c.roughness * c.roughness / 2);
            diffuse += b.diffuse.y, specular += b.specular.y;
        }
        diffuse *= 100 * omega / samples, specular *= 100 * omega / samples;
        const DiskResult r{v[6 * i + 4], specular, v[6 * i + 1], diffuse};
        std::printf("%-6s theta %.2f roughness %.2f n.v %.1f R %.2f rad from the centre: specular %.4g sum %.4g (%+.1f%%), "
                    "diffuse %.4g sum %.4g\n",
                    c.gltf ? "glTF" : "thesis", c.theta, c.roughness, c.nv, c.offset, r.specular, r.sum_specular,
                    100 * (r.specular - r.sum_specular) / std::max(r.sum_specular, 1e-30), r.diffuse, r.sum_diffuse);
        results.push_back(r);
    }
    return results;
}

// Wide caps (3 and 11 degrees) on smooth to rough surfaces, R inside, at the edge, just
// outside and far from the cap, the horizon cutting some: the closed form against a sum
// of the model's BRDF over the cap (both models).
TEST_F(ShadingIncludeTest, DiskLightMatchesTheSumOverTheCap) {
    std::vector<DiskCase> cases;
    for (bool gltf : {true, false})
        for (double theta : {0.05, 0.2})
            for (double roughness : {0.3, 0.6})
                for (double nv : {0.4, 0.9})
                    for (double offset : {0.0, 1.0, 1.5, 6.0}) cases.push_back({theta, roughness, gltf ? 1.0 : 0.0, nv,
                                                                              offset * theta, 0.7, gltf});
    cases.push_back({0.2, 0.5, 1.0, 0.6, 1.3, 1.57, true});  // the cap's centre 0.1 rad below the horizon
    const std::vector<DiskResult> r = disk_against_sums(ctx(), cases, false);
    ASSERT_EQ(r.size(), cases.size());
    double near_error = 0, near_truth = 0;
    for (size_t i = 0; i < cases.size(); ++i) {
        const DiskCase& c = cases[i];
        const double error = std::abs(r[i].specular - r[i].sum_specular) / std::max(r[i].sum_specular, 1e-3);
        EXPECT_NEAR(r[i].diffuse, r[i].sum_diffuse, 0.03 * r[i].sum_diffuse + 1e-4) << "case " << i;
        const bool tail = c.offset > 2 * c.theta;
        if (!tail) near_error += std::abs(r[i].specular - r[i].sum_specular), near_truth += r[i].sum_specular;
        // Seen from above (n.v 0.9) within 4%, the tails (R six radii away, a value that
        // small) within 25%. At grazing view the cap's image in slope space is an ellipse
        // 1 / (v.h) times longer than wide, which the disk of the same area stands in for:
        // within 8% inside the cap, but the edge of an 11-degree cap on roughness 0.3 at
        // n.v 0.4 lies 0.1 radian off, -41% for R just outside it: the bound is 45% there.
        EXPECT_LT(error, tail ? 0.25 : c.nv > 0.8 ? 0.04 : 0.45) << "case " << i;
    }
    // Where R is in or near the cap (what a highlight shows), 6% overall.
    EXPECT_LT(near_error / near_truth, 0.06);
}

// A cap as a point where the lobe is wider than kPointCapLobeRatio (3) x its radius
// (render/lobe_disks.h): 3- and 11-degree caps on lobes 3 to 12 times wider, R inside, at
// the edge, just outside and far from the cap, grazing and from above, the horizon cutting
// some, and at the rim, against the sum over the cap (both models), next to the closed form's error.
TEST_F(ShadingIncludeTest, DiskLightAsAPointMatchesTheSumWhereTheLobeIsWide) {
    std::vector<DiskCase> cases;
    for (bool gltf : {true, false})
        for (double theta : {0.05, 0.2})
            for (double lobe : {3.0, 5.0, 12.0}) {  // alpha / theta
                const double roughness = std::sqrt(lobe * theta);
                if (roughness > 1.0) continue;
                for (double nv : {0.4, 0.9})
                    for (double offset : {0.0, 1.0, 1.5, 6.0})
                        cases.push_back({theta, roughness, gltf ? 1.0 : 0.0, nv, offset * theta, 0.7, gltf});
            }
    cases.push_back({0.05, 0.6, 1.0, 0.6, 1.3, 1.57, true});  // the cap's centre 0.1 rad below the horizon
    cases.push_back({0.2, 0.9, 0.0, 0.3, 1.25, 1.57, false});
    const size_t rim = cases.size();  // then a view at the rim (n.v 0.15), R along the horizon
    for (double theta : {0.05, 0.2})
        for (double offset : {0.0, 1.0, 2.0, 4.0})
            for (double azimuth : {0.0, 1.57, 3.14})
                cases.push_back({theta, theta > 0.1 ? 0.8 : 0.5, 1.0, 0.15, offset * theta, azimuth, true});
    const std::vector<DiskResult> point = disk_against_sums(ctx(), cases, true);
    const std::vector<DiskResult> closed = disk_against_sums(ctx(), cases, false);
    ASSERT_EQ(point.size(), cases.size());
    ASSERT_EQ(closed.size(), cases.size());
    double near_point = 0, near_closed = 0, near_truth = 0, rim_point = 0, rim_closed = 0, rim_truth = 0;
    for (size_t i = 0; i < cases.size(); ++i) {
        const DiskCase& c = cases[i];
        const DiskResult& r = point[i];
        const double error = std::abs(r.specular - r.sum_specular) / std::max(r.sum_specular, 1e-3);
        EXPECT_NEAR(r.diffuse, r.sum_diffuse, 0.03 * r.sum_diffuse + 1e-4) << "case " << i;
        if (i >= rim) {
            rim_point += std::abs(r.specular - r.sum_specular), rim_truth += r.sum_specular;
            rim_closed += std::abs(closed[i].specular - closed[i].sum_specular);
            continue;
        }
        const bool tail = c.offset > 2 * c.theta;
        if (!tail) {
            near_point += std::abs(r.specular - r.sum_specular), near_truth += r.sum_specular;
            near_closed += std::abs(closed[i].specular - closed[i].sum_specular);
        }
        // As the closed form: seen from above within 4%, the tails within 25%; at grazing view,
        // where the horizon cuts an 11-degree cap next to R, within 20% (the closed form 17%).
        EXPECT_LT(error, tail ? 0.25 : c.nv > 0.8 ? 0.04 : 0.2) << "case " << i;
    }
    // Where R is in or near the cap, 3% overall, and no further off than the closed form.
    std::printf("R in or near the cap: as a point %.2f%% off overall, the closed form %.2f%%\n", 100 * near_point / near_truth,
                100 * near_closed / near_truth);
    EXPECT_LT(near_point / near_truth, 0.03);
    EXPECT_LE(near_point, near_closed);
    // At the rim both are coarse (the cap's image in slope space is far from a disk there;
    // issue 13's measure leaves out n.v under 0.3): the point no further off than the closed form.
    std::printf("at the rim (n.v 0.15): as a point %.2f%% off overall, the closed form %.2f%%\n", 100 * rim_point / rim_truth,
                100 * rim_closed / rim_truth);
    EXPECT_LE(rim_point, rim_closed);
}

// Turquin 2019: a light's specular scaled by 1 + F0 (1 / E - 1), E = A + B.
TEST_F(ShadingIncludeTest, MultiscatterLightEnergy) {
    auto v = test::run_compute_probe(ctx(), "energy_probe.comp",
                                     probe("put(0u, facet_multiscatter_light_energy(vec3(1.0, 0.5, 0.0), "
                                           "vec4(0.6, 0.2, 0.0, 0.0)));\n"),
                                     3);
    ASSERT_EQ(v.size(), 3u);
    EXPECT_NEAR(v[0], 1 + 1.0 * (1 / 0.8 - 1), 1e-6);
    EXPECT_NEAR(v[1], 1 + 0.5 * (1 / 0.8 - 1), 1e-6);
    EXPECT_NEAR(v[2], 1.0, 1e-6);
}

}  // namespace
}  // namespace facet
