// The fitted lookups' table (render/specular_lobes.h, fitted by scripts/fit_specular_lobes.py)
// against the true specular lobe, recomputed here from the reference BRDFs (final_image_truth.h,
// written from the equations): at table nodes, the three kernels of the prefiltered cube the
// shader reads (the bake's GGX kernel D(h) (d.l) about each lookup's axis, normalised) must
// follow the normalised lobe f (n.l) of a white metal (F = 1) much closer than the split sum's
// one kernel along R at the surface's roughness, in L1 over the sphere.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

#include <facet/reference/final_image_truth.h>
#include <facet/render/specular_lobes.h>
#include "render/specular_lobes_table.h"

namespace facet::test {
namespace {

constexpr double pi = 3.14159265358979323846;

struct Grid {
    std::vector<Vec3> dir;
    std::vector<double> solid_angle;
};

// Texel centres of a 512 x 256 equirect grid: roughness 0.3's lobe spans many texels.
const Grid& grid() {
    static const Grid g = [] {
        Grid out;
        const int w = 512, h = 256;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const double lat = (0.5 - (y + 0.5) / h) * pi, lon = ((x + 0.5) / w - 0.5) * 2 * pi;
                out.dir.push_back({std::cos(lat) * std::cos(lon), std::sin(lat), std::cos(lat) * std::sin(lon)});
                out.solid_angle.push_back((2 * pi / w) * (pi / h) * std::cos(lat));
            }
        return out;
    }();
    return g;
}

double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// The bake's prefilter kernel about axis d at a roughness, normalised over the grid.
std::vector<double> kernel(const Vec3& d, double roughness) {
    const double a2 = std::pow(std::max(roughness * roughness, 1e-4), 2);
    std::vector<double> k(grid().dir.size());
    double sum = 0;
    for (size_t i = 0; i < k.size(); ++i) {
        const double c = dot(d, grid().dir[i]);
        if (c <= 0) continue;
        const double nh2 = (1 + c) / 2, t = nh2 * (a2 - 1) + 1;
        k[i] = a2 / (pi * t * t) * c * grid().solid_angle[i];
        sum += k[i];
    }
    for (double& x : k) x /= sum;
    return k;
}

double l1(const std::vector<double>& a, const std::vector<double>& b) {
    double s = 0;
    for (size_t i = 0; i < a.size(); ++i) s += std::abs(a[i] - b[i]);
    return s;
}

struct Lookup {
    double t, roughness, weight;  // axis normalize(mix(n, R, t)), as the shader reads it
};

// L1 over the sphere from the normalised lobe of a white metal (F = 1) at a table node to
// the lookups' kernels (`fitted`) and to one kernel along R at the surface's roughness.
struct NodeL1 {
    double fitted, mirror;
};
NodeL1 node_l1(BrdfModel model, int row, int column, const std::vector<Lookup>& lookups) {
    const double roughness = 0.2 + 0.1 * row, nv = 0.1 + 0.1 * column;
    const Vec3 n{1, 0, 0}, v{nv, 0, std::sqrt(1 - nv * nv)};
    const Vec3 R{2 * nv * n[0] - v[0], 2 * nv * n[1] - v[1], 2 * nv * n[2] - v[2]};
    TruthMaterial white;
    white.metallic = 1;
    white.roughness = roughness;
    std::vector<double> lobe(grid().dir.size());
    double sum = 0;
    for (size_t i = 0; i < lobe.size(); ++i) {
        lobe[i] = brdf_cos(model, white, n, v, grid().dir[i])[0] * grid().solid_angle[i];
        sum += lobe[i];
    }
    for (double& x : lobe) x /= sum;
    std::vector<double> fitted(lobe.size(), 0.0);
    for (const Lookup& k : lookups) {
        const Vec3 d{(1 - k.t) * n[0] + k.t * R[0], (1 - k.t) * n[1] + k.t * R[1], (1 - k.t) * n[2] + k.t * R[2]};
        const double len = std::sqrt(dot(d, d));
        const std::vector<double> kk = kernel({d[0] / len, d[1] / len, d[2] / len}, k.roughness);
        for (size_t i = 0; i < fitted.size(); ++i) fitted[i] += k.weight * kk[i];
    }
    return {l1(lobe, fitted), l1(lobe, kernel(R, roughness))};
}

TEST(SpecularLobes, FittedLookupsFollowTheTrueLobeBetterThanOneAlongR) {
    const std::vector<float> table = specular_lobe_table_texels();
    ASSERT_EQ(table.size(), size_t(kSpecularLobeTableWidth) * kSpecularLobeTableHeight * 4);
    for (BrdfModel model : {BrdfModel::gltf, BrdfModel::thesis})
        for (int row : {1, 3, 5, 8})          // roughness 0.3, 0.5, 0.7, 1.0
            for (int column : {1, 4, 7}) {    // n.v 0.2, 0.5, 0.8
                const size_t y = size_t(model == BrdfModel::gltf ? 0 : 9) + size_t(row);
                const float* directions = &table[(y * kSpecularLobeTableWidth + size_t(column)) * 4];
                const float* widths = &table[(y * kSpecularLobeTableWidth + 9 + size_t(column)) * 4];
                std::vector<Lookup> lookups;
                double weights = 0;
                for (int k = 0; k < 3; ++k) {
                    const double w = k == 0 ? directions[3] : k == 1 ? widths[3] : 1.0 - directions[3] - widths[3];
                    EXPECT_GE(w, 0.0);
                    EXPECT_GT(widths[k], 0.0f);
                    EXPECT_LE(widths[k], 1.0f);
                    weights += w;
                    lookups.push_back({directions[k], widths[k], w});
                }
                EXPECT_NEAR(weights, 1.0, 1e-3);
                const NodeL1 d = node_l1(model, row, column, lookups);
                std::printf("%-6s roughness %.1f n.v %.1f: L1 to the lobe %.3f fitted, %.3f one lookup along R\n",
                            brdf_model_name(model), 0.2 + 0.1 * row, 0.1 + 0.1 * column, d.fitted, d.mirror);
                // Fitted on a coarser grid (1.4 degrees, 0.7 below roughness 0.35): the fit
                // measured 2-10x closer; half is the bound.
                EXPECT_LT(d.fitted, 0.5 * d.mirror) << brdf_model_name(model) << " row " << row << " column " << column;
            }
}

// The groups that read two lookups by default: the measure's bands from kTwoLookupsRoughness,
// both classes (index 2 x band + metal).
TEST(SpecularLobes, TwoLookupsByDefaultFromTheRoughBands) {
    const std::array<bool, 8> expected = {false, false, false, false, true, true, true, true};
    EXPECT_EQ(kDefaultTwoLookupGroups, expected);
}

// The two lookups of equal weight (the table's third block), used from kTwoLookupsRoughness
// up: closer to the lobe than one along R by 2.2-9x at these nodes (0.45 of it at roughness
// 0.6, n.v 0.8, the least), and at most 2.3x the three lookups' L1 (the image's cost of them
// is measured in AccuracyTargets; docs/accuracy.md).
TEST(SpecularLobes, TwoLookupsFollowTheRoughLobesBetterThanOneAlongR) {
    const std::vector<float> table = specular_lobe_table_texels();
    const int first_row = int(std::lround((kTwoLookupsRoughness - 0.2f) * 10.0f));
    EXPECT_EQ(first_row, 4);
    for (BrdfModel model : {BrdfModel::gltf, BrdfModel::thesis})
        for (int row : {first_row, 5, 6, 8})  // roughness 0.6, 0.7, 0.8, 1.0
            for (int column : {1, 4, 7}) {    // n.v 0.2, 0.5, 0.8
                const size_t y = size_t(model == BrdfModel::gltf ? 0 : 9) + size_t(row);
                const float* two = &table[(y * kSpecularLobeTableWidth + 18 + size_t(column)) * 4];
                const float* directions = &table[(y * kSpecularLobeTableWidth + size_t(column)) * 4];
                const float* widths = &table[(y * kSpecularLobeTableWidth + 9 + size_t(column)) * 4];
                for (int k = 0; k < 2; ++k) {
                    EXPECT_GT(two[2 + k], 0.0f);
                    EXPECT_LE(two[2 + k], 1.0f);
                }
                const NodeL1 d = node_l1(model, row, column, {{two[0], two[2], 0.5}, {two[1], two[3], 0.5}});
                const NodeL1 three = node_l1(model, row, column,
                                             {{directions[0], widths[0], directions[3]},
                                              {directions[1], widths[1], widths[3]},
                                              {directions[2], widths[2], 1.0 - directions[3] - widths[3]}});
                std::printf("%-6s roughness %.1f n.v %.1f: L1 to the lobe %.3f two lookups, %.3f three, %.3f one along R\n",
                            brdf_model_name(model), 0.2 + 0.1 * row, 0.1 + 0.1 * column, d.fitted, three.fitted,
                            d.mirror);
                EXPECT_LT(d.fitted, 0.55 * d.mirror) << brdf_model_name(model) << " row " << row << " column " << column;
                EXPECT_LT(d.fitted, 2.5 * three.fitted) << brdf_model_name(model) << " row " << row << " column " << column;
            }
}

// The table stores two weights per entry and the shader takes the third as 1 - w0 - w1:
// valid only because the fit's three weights sum to 1.
TEST(SpecularLobes, FittedWeightsSumToOne) {
    for (int entry = 0; entry < kSpecularLobeModels * kSpecularLobeRows * kSpecularLobeColumns; ++entry) {
        const double sum = double(kSpecularLobeEntries[entry * 3][2]) + kSpecularLobeEntries[entry * 3 + 1][2] +
                           kSpecularLobeEntries[entry * 3 + 2][2];
        EXPECT_NEAR(sum, 1.0, 1e-4) << "entry " << entry;
    }
}

}  // namespace
}  // namespace facet::test
