#include "bake_files.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>

#include <facet/gpu/transfer.h>
#include "interrupt.h"
#include <facet/io/atomic_file.h>
#include <facet/io/image_io.h>
#include <facet/io/json_writer.h>
#include <facet/io/ktx2.h>
#include <facet/io/output_set.h>

namespace facet {

namespace {

namespace fs = std::filesystem;

std::vector<float> as_floats(const std::vector<std::byte>& bytes) {
    std::vector<float> f(bytes.size() / sizeof(float));
    std::memcpy(f.data(), bytes.data(), bytes.size());
    return f;
}

// RGBA32F levels -> a KTX2 image of RGBA16F (the Khronos glTF IBL sampler's format).
Ktx2Image to_ktx2(const ImageTexels& t, const BakeDescription& d) {
    Ktx2Image k;
    k.format = VK_FORMAT_R16G16B16A16_SFLOAT;
    k.width = t.desc.width;
    k.height = t.desc.height;
    k.faces = t.desc.cube ? 6 : 1;
    k.levels = t.desc.mip_levels;
    for (const auto& level : t.levels) {
        std::vector<float> f = as_floats(level);
        std::vector<std::byte> half(f.size() * 2);
        for (size_t i = 0; i < f.size(); ++i) {
            const uint16_t h = float_to_half(f[i]);
            std::memcpy(half.data() + i * 2, &h, 2);
        }
        k.level_data.push_back(std::move(half));
    }
    k.key_values = {{"KTXwriter", "facet-bake " + d.version}};
    return k;
}

size_t count_bad(const ImageTexels& t) {
    size_t bad = 0;
    for (const auto& level : t.levels)
        for (float v : as_floats(level)) bad += !std::isfinite(v) || v < 0;
    return bad;
}

double rounded(double ms) { return std::round(ms * 1e3) / 1e3; }

std::string bake_json(const BakeDescription& d, const BakeResults& r) {
    JsonWriter j;
    j.begin_object()
        .value("program", "facet-bake")
        .value("version", d.version)
        .value("device", d.device)
        .value("bake_key", d.bake_key)
        .begin_object("input")
        .value("name", d.input)
        .value("content_hash", d.content_hash)
        .value("width", r.environment.desc.width)
        .value("height", r.environment.desc.height)
        .value("source_width", d.source_width)
        .value("source_height", d.source_height)
        .value("max_env_width", d.max_env_width)
        .value("sanitized_texels", int64_t(d.sanitized_texels))
        .end_object();
    j.begin_array("warnings");
    for (const std::string& w : d.warnings) j.value({}, w);
    j.end_array();
    if (d.budget_target > 0) {
        j.begin_object("budget").value("target_rel_rmse", d.budget_target);
        j.begin_array("roughness_range").value({}, double(d.budget_roughness_min)).value({}, double(d.budget_roughness_max)).end_array();
        j.begin_array("choices");
        for (const auto& c : d.budget)
            j.begin_object().value("stage", c.stage).value("method", c.method).value("parameters", c.params)
                .value("predicted_rel_rmse", c.predicted_error).value("measured_time_ms", c.time_ms)
                .value("met", c.met).end_object();
        j.end_array().end_object();
    }
    j
        .begin_object("environment_cube")
        .value("size", d.cube_size)
        .value("filtering", "4x4 supersampled bilinear; mips by solid-angle-weighted 2x2 means")
        .end_object()
        .begin_object("specular")
        .value("file", "specular.ktx2")
        .value("size", d.cube_size)
        .value("format", "R16G16B16A16_SFLOAT")
        .value("method", specular_method_name(d.specular.method))
        .value("sample_count", d.specular.sample_count)
        .value("alpha", "roughness^2")
        .begin_array("levels");
    const std::vector<float> roughness = specular_level_roughness(d.specular.levels);
    for (uint32_t m = 0; m < d.specular.levels; ++m)
        j.begin_object()
            .value("level", m)
            .value("roughness", double(roughness[m]))
            .value("method", m == 0 ? "copy" : specular_method_name(specular_level_method(d.specular, roughness[m])))
            .value("size", std::max(1u, d.cube_size >> m))
            .end_object();
    j.end_array()
        .end_object()
        .begin_object("irradiance")
        .value("file", "irradiance.ktx2")
        .value("quantity", "E(n) / pi")
        .value("method", irradiance_method_name(d.irradiance.method))
        .value("size", d.irradiance.size)
        .value("source_size", d.irradiance.source_size)
        .value("riemann_step", double(d.irradiance.riemann_step))
        .value("blur_sigma", double(d.irradiance.blur_sigma))
        .end_object()
        .begin_object("brdf_lut")
        .value("file", "brdf_lut.ktx2")
        .value("size", d.lut.size)
        .value("samples", d.lut.sample_count)
        .value("visibility", d.lut.visibility == LutVisibility::height_correlated ? "smith height-correlated"
                                                                                : "smith schlick-ggx k = r^2/2")
        .value("channels", "R = A (scale), G = B (bias), B = E_avg (multiscatter)")
        .end_object()
        .value("preview_exposure", double(d.exposure))
        .begin_array("passes");
    double gpu = 0;
    for (const PassTiming& t : r.timings) {
        j.begin_object().value("name", t.name).value("gpu_time_ms", rounded(t.time_ms)).end_object();
        gpu += t.time_ms;
    }
    j.end_array().value("gpu_time_ms", rounded(gpu)).value("wall_time_ms", rounded(d.wall_time_ms)).end_object();
    return j.str();
}

}  // namespace

ImageTexels read_all(Context& context, const Image& image) {
    ImageTexels t;
    t.desc = image.desc();
    for (uint32_t m = 0; m < t.desc.mip_levels; ++m) {
        std::vector<std::byte> level;
        for (uint32_t layer = 0; layer < t.desc.array_layers; ++layer) {
            auto bytes = read_image(context, image, m, layer, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
            level.insert(level.end(), bytes.begin(), bytes.end());
        }
        t.levels.push_back(std::move(level));
    }
    return t;
}

const std::vector<const char*>& bake_output_names() {
    static const std::vector<const char*> names = {"specular.ktx2",   "irradiance.ktx2", "brdf_lut.ktx2",
                                                   "brdf_lut.png",    "environment.exr", "environment.hdr",
                                                   "environment.png", "bake.json"};
    return names;
}

Status stage_bake_files(OutputSet& outputs, const std::string& dir, const BakeDescription& d, const BakeResults& r) {
    for (const ImageTexels* t : {&r.environment, &r.irradiance, &r.specular, &r.lut})
        if (size_t bad = count_bad(*t))
            return Error{std::to_string(bad) + " baked values are NaN, Inf or negative; nothing was written"};
    for (const char* name : bake_output_names())
        if (fs::exists(fs::path(dir) / name))
            std::fprintf(stderr, "facet-bake: replacing %s\n", (fs::path(dir) / name).c_str());
    auto path = [&](const char* name) { return (fs::path(dir) / name).string(); };
    // Each file goes to its temporary; the previous bake stays whole until the commit.
    auto stage = [&](const char* name) {
        check_interrupt();
        return outputs.stage(path(name));
    };
    const ImageDesc& e = r.environment.desc;
    const std::vector<float> env = as_floats(r.environment.levels[0]);
    for (const char* name : {"environment.exr", "environment.hdr"})
        if (Status s = write_hdr_image(stage(name), e.width, e.height, env); !s) return s;
    std::vector<uint8_t> preview(r.preview.levels[0].size());
    std::memcpy(preview.data(), r.preview.levels[0].data(), preview.size());
    if (Status s = write_ldr_image(stage("environment.png"), e.width, e.height, preview); !s) return s;
    if (Status s = write_ktx2(stage("specular.ktx2"), to_ktx2(r.specular, d)); !s) return s;
    if (Status s = write_ktx2(stage("irradiance.ktx2"), to_ktx2(r.irradiance, d)); !s) return s;
    if (Status s = write_ktx2(stage("brdf_lut.ktx2"), to_ktx2(r.lut, d)); !s) return s;
    // LUT preview: A, B and E_avg lie in [0, 1]; shown linearly, roughness 0 on the top row.
    const std::vector<float> lut = as_floats(r.lut.levels[0]);
    std::vector<uint8_t> lut_png(lut.size());
    for (size_t i = 0; i < lut.size(); ++i)
        lut_png[i] = i % 4 == 3 ? 255 : static_cast<uint8_t>(std::lround(std::clamp(lut[i], 0.0f, 1.0f) * 255.0f));
    if (Status s = write_ldr_image(stage("brdf_lut.png"), r.lut.desc.width, r.lut.desc.height, lut_png); !s) return s;
    if (r.sh9.empty() && fs::exists(path("sh9.json"))) {
        std::fprintf(stderr, "facet-bake: removing %s (this bake does not use spherical harmonics)\n",
                     path("sh9.json").c_str());
        outputs.remove_with_commit(path("sh9.json"));
    }
    if (!r.sh9.empty()) {
        JsonWriter j;
        j.begin_object()
            .value("basis", "real SH, bands 0-2, order (0,0) (1,-1) (1,0) (1,1) (2,-2) (2,-1) (2,0) (2,1) (2,2); "
                            "Y_1,-1 = 0.4886 y, Y_10 = 0.4886 z, Y_11 = 0.4886 x")
            .value("quantity", "radiance projections L_i = integral L Y_i dw (before the cosine kernel)")
            .value("irradiance", "E(n)/pi = sum_i A_l w_l L_i Y_i(n) / pi, A = (pi, 2pi/3, pi/4)")
            .value("window_h", double(r.sh9[9 * 4]))
            .value("window", "w_l = (1 + cos(pi l / (2 h))) / 2; h = 0 means no window")
            .begin_array("coefficients");
        for (int i = 0; i < 9; ++i) {
            j.begin_array();
            for (int c = 0; c < 3; ++c) j.value("", double(r.sh9[i * 4 + c]));
            j.end_array();
        }
        j.end_array().end_object();
        if (Status s = write_text_file(stage("sh9.json"), j.str()); !s) return s;
    }
    // bake.json last: the set's marker, its presence with a bake key marks a complete bake.
    return write_text_file(stage("bake.json"), bake_json(d, r));
}

}  // namespace facet
