// BakedEnvironment::save / stage: facet-bake's files (design.md), written through an
// OutputSet so that they appear together, bake.json last (the set's marker). bake.json
// records everything load() needs to read the images back and check them.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
#include <future>

#include <facet/gpu/transfer.h>
#include <facet/ibl/baked_environment.h>
#include <facet/io/atomic_file.h>
#include <facet/io/image_io.h>
#include <facet/io/json_writer.h>
#include <facet/io/ktx2.h>
#include <facet/io/output_set.h>
#include "ibl/bake_cancel.h"
#include "ibl/baked_outputs.h"
#include "core/vulkan_error.h"

namespace facet {

namespace {

namespace fs = std::filesystem;

Ktx2Image to_ktx2(const Image& image, Levels levels, const std::string& version) {
    Ktx2Image k;
    k.format = image.desc().format;
    k.width = image.desc().width;
    k.height = image.desc().height;
    k.faces = image.desc().cube ? 6 : 1;
    k.levels = image.desc().mip_levels;
    k.level_data = std::move(levels);
    k.key_values = {{"KTXwriter", "facet-bake " + version}};
    return k;
}

double rounded(double ms) { return std::round(ms * 1e3) / 1e3; }

void write_image_entry(JsonWriter& j, const char* file, const Image& image) {
    j.value("file", file).value("size", image.desc().width).value("mip_levels", image.desc().mip_levels)
        .value("format", format_name(image.desc().format));
}

std::string bake_json(const BakedEnvironment& b) {
    const BakeMetadata& d = b.metadata();
    const IblSettings& s = d.settings;
    JsonWriter j;
    j.begin_object()
        .value("program", "facet-bake")
        .value("version", d.version)
        .value("device", d.device)
        .value("bake_key", d.bake_key)
        .begin_object("input")
        .value("name", d.input)
        .value("content_hash", d.content_hash)
        .value("width", d.width)
        .value("height", d.height)
        .value("source_width", d.source_width)
        .value("source_height", d.source_height)
        .value("max_env_width", d.max_env_width)
        .value("sanitized_texels", int64_t(d.sanitized_texels))
        .end_object();
    j.begin_array("warnings");
    for (const std::string& w : d.warnings) j.value({}, w);
    j.end_array();
    j.begin_array("format_notes");
    for (const std::string& w : d.format_notes) j.value({}, w);
    j.end_array();
    if (d.budget) {
        j.begin_object("budget").value("target_rel_rmse", d.budget->target);
        j.begin_array("roughness_range")
            .value({}, double(d.budget->roughness_min))
            .value({}, double(d.budget->roughness_max))
            .end_array();
        j.begin_array("choices");
        for (const auto& c : d.budget->choices)
            j.begin_object().value("stage", c.stage).value("method", c.method).value("parameters", c.params)
                .value("predicted_rel_rmse", c.predicted_error).value("measured_time_ms", c.time_ms)
                .value("met", c.met).end_object();
        j.end_array().end_object();
    }
    j.begin_object("environment").value("file", "environment.exr").value("width", d.width)
        .value("height", d.height).value("format", format_name(b.environment().desc().format)).end_object();
    j.begin_object("environment_cube");
    write_image_entry(j, "environment.ktx2", b.cube());
    j.value("filtering", "4x4 supersampled bilinear; mips by solid-angle-weighted 2x2 means").end_object();
    if (const Image* spec = b.specular()) {
        j.begin_object("specular");
        write_image_entry(j, "specular.ktx2", *spec);
        j.value("method", specular_method_name(s.specular.method))
            .value("sample_count", s.specular.sample_count)
            .value("automatic_convolve_from", double(s.specular.automatic_convolve_from))
            .value("hybrid_sample_count", s.specular.hybrid_sample_count)
            .value("excess_factor", double(s.specular.excess_factor))
            .value("hybrid_half_size_residual", s.specular.hybrid_half_size_residual)
            .value("min_roughness", double(s.specular.min_roughness))
            .value("first_level", d.first_specular_level)
            .value("alpha", "roughness^2")
            .value("lookup", "lod = roughness x (levels - 1)")
            .begin_array("levels");
        for (uint32_t m = 0; m < spec->desc().mip_levels; ++m)
            j.begin_object()
                .value("level", m)
                .value("roughness", double(d.roughness[m]))
                .value("method", m == 0 ? "copy" : specular_method_name(specular_level_method(s.specular, d.roughness[m])))
                .value("size", std::max(1u, spec->desc().width >> m))
                .value("residual_at_half_size",
                       m > 0 && specular_level_method(s.specular, d.roughness[m]) == SpecularMethod::hybrid &&
                           hybrid_residual_at_half_size(s.specular, d.roughness[m], std::max(1u, spec->desc().width >> m)))
                .end_object();
        j.end_array().end_object();
    }
    if (const Image* irr = b.irradiance()) {
        j.begin_object("irradiance");
        write_image_entry(j, "irradiance.ktx2", *irr);
        j.value("quantity", "E(n) / pi")
            .value("method", irradiance_method_name(s.irradiance.method))
            .value("source_size", s.irradiance.source_size)
            .value("riemann_step", double(s.irradiance.riemann_step))
            .value("blur_sigma", double(s.irradiance.blur_sigma))
            .value("lowmip_size", s.irradiance.lowmip_size)
            .value("sh9_windowing", s.irradiance.sh9_windowing)
            .end_object();
    }
    if (const Image* lut = b.lut()) {
        j.begin_object("brdf_lut");
        write_image_entry(j, "brdf_lut.ktx2", *lut);
        j.value("samples", s.lut.sample_count)
            .value("brdf", brdf_model_name(s.lut.brdf))
            .value("visibility", s.lut.brdf == BrdfModel::gltf ? "smith height-correlated" : "smith schlick-ggx k = r^2/2")
            .value("channels", "R = A (scale), G = B (bias), B = E_avg (multiscatter), A = mean (1 - v.h)^5 (diffuse)")
            .end_object();
    }
    j.begin_object("lights")
        .value("split_level", d.light_split_level)
        .value("irradiance", "the whole environment (the disks' diffuse is in the irradiance cube)")
        .value("extracted_power_fraction", d.extracted_power_fraction)
        .begin_array("disks");
    for (const DiskLight& l : b.lights()) {
        j.begin_object().begin_array("direction");
        for (int c = 0; c < 3; ++c) j.value({}, double(l.direction[c]));
        j.end_array().value("angular_radius", double(l.angular_radius)).begin_array("radiance");
        for (int c = 0; c < 3; ++c) j.value({}, double(l.radiance[c]));
        j.end_array()
            .value("solid_angle", double(l.solid_angle))
            .value("texels", l.texels)
            .value("power_fraction", l.power_fraction)
            .end_object();
    }
    j.end_array().end_object();
    j.value("preview_exposure", double(d.preview_exposure)).begin_array("passes");
    double gpu = 0;
    for (const PassTiming& t : d.timings) {
        j.begin_object().value("name", t.name).value("gpu_time_ms", rounded(t.time_ms)).end_object();
        gpu += t.time_ms;
    }
    j.end_array().value("gpu_time_ms", rounded(gpu)).value("wall_time_ms", rounded(d.wall_time_ms)).end_object();
    return j.str();
}

std::string sh9_json(const std::vector<float>& sh9) {
    JsonWriter j;
    j.begin_object()
        .value("basis", "real SH, bands 0-2, order (0,0) (1,-1) (1,0) (1,1) (2,-2) (2,-1) (2,0) (2,1) (2,2); "
                        "Y_1,-1 = 0.4886 y, Y_10 = 0.4886 z, Y_11 = 0.4886 x")
        .value("quantity", "radiance projections L_i = integral L Y_i dw (before the cosine kernel)")
        .value("irradiance", "E(n)/pi = sum_i A_l w_l L_i Y_i(n) / pi, A = (pi, 2pi/3, pi/4)")
        .value("window_h", double(sh9[9 * 4]))
        .value("window", "w_l = (1 + cos(pi l / (2 h))) / 2; h = 0 means no window")
        .begin_array("coefficients");
    for (int i = 0; i < 9; ++i) {
        j.begin_array();
        for (int c = 0; c < 3; ++c) j.value("", double(sh9[size_t(i) * 4 + size_t(c)]));
        j.end_array();
    }
    j.end_array().end_object();
    return j.str();
}

}  // namespace

const std::vector<const char*>& baked_environment_files() {
    static const std::vector<const char*> names = {
        "specular.ktx2",   "irradiance.ktx2", "brdf_lut.ktx2",   "brdf_lut.png", "environment.ktx2",
        "environment.exr", "environment.hdr", "environment.png", "bake.json"};
    return names;
}

Status BakedEnvironment::stage(OutputSet& outputs, const std::string& dir, const BakeStopFn& stop,
                               std::vector<std::string>* notes, const BakeSaveOptions& options) const try {
    if (!environment_ || !cube_) return Error{dir + ": an empty BakedEnvironment cannot be saved"};
    Context& context = *context_;
    auto path = [&](const char* name) { return (fs::path(dir) / name).string(); };
    auto is_preview = [](const std::string& name) {
        return name == "environment.png" || name == "environment.hdr" || name == "brdf_lut.png";
    };
    for (const char* name : baked_environment_files())
        if (notes && fs::exists(path(name)) && (options.previews || !is_preview(name)))
            notes->push_back("replacing " + path(name));
    // Each file goes to its temporary; the previous bake stays whole until the commit.
    auto staged = [&](const char* name) {
        bake_safe_point(stop, "file");
        return outputs.stage(path(name));
    };
    auto remove_old = [&](const char* name, const char* why) {
        if (!fs::exists(path(name))) return;
        if (notes) notes->push_back("removing " + path(name) + " (" + why + ")");
        outputs.remove_with_commit(path(name));
    };
    const ImageDesc e = environment_.desc();
    const char* no_previews = "previews are not written here";
    // Files are encoded and written on second threads once their texels are on the host
    // (the EXR's compression was most of a save). Staging (the OutputSet) and GPU reads stay
    // on this thread; every return below waits for the others (the futures' destructors)
    // before the staged files go.
    std::vector<std::future<Status>> writing;
    auto in_background = [&](std::function<Status()> work) {
        writing.push_back(std::async(std::launch::async, std::move(work)));
    };
    // Every image needed, read back in one submission; the files are then written from the
    // mapped readback buffer on second threads.
    // Files encoded ahead are used when they are of the texels baked (waits for an encoder
    // still at work: it had the whole bake's idle cores).
    const std::shared_ptr<const EncodedEnvironmentFiles> encoded = encoded_.get();
    const bool environment_encoded = encoded && encoded->content_hash == metadata_.content_hash &&
                                     encoded->width == environment_.desc().width &&
                                     encoded->height == environment_.desc().height &&
                                     encoded->previews == options.previews;
    const Image* preview_image = options.previews && preview_ ? &preview_ : nullptr;
    struct Ktx2Output {
        const char* name;
        const Image* image;
        const char* why_absent;
    };
    const Ktx2Output ktx2_outputs[] = {{"environment.ktx2", &cube_, ""},
                                       {"specular.ktx2", specular(), "this bake has no specular cube"},
                                       {"irradiance.ktx2", irradiance(), "this bake has no irradiance"},
                                       {"brdf_lut.ktx2", lut(), "this bake has no BRDF LUT"}};
    std::vector<const Image*> images;
    for (const Ktx2Output& k : ktx2_outputs) images.push_back(k.image);
    images.push_back(environment_encoded ? nullptr : &environment_);  // [4]
    images.push_back(preview_image);                                   // [5]
    const ReadBack read = read_back(context, images, kBakedLayout);

    const std::string exr_path = staged("environment.exr");
    std::string hdr_path;
    if (!options.previews) remove_old("environment.hdr", no_previews);
    else hdr_path = staged("environment.hdr");
    if (environment_encoded) {
        // Encoded ahead (BakeSettings::encoded_environment): only the bytes to write.
        in_background([exr_path, hdr_path, encoded]() -> Status {
            if (Status s = write_binary_file(exr_path, encoded->exr); !s) return s;
            if (!hdr_path.empty()) return write_binary_file(hdr_path, encoded->hdr);
            return Ok{};
        });
    } else {
        // Each file on a thread of its own (the EXR's compression on every core).
        for (const std::string& to : {exr_path, hdr_path})
            if (!to.empty())
                in_background([to, e, read]() -> Status {
                    const std::span<const std::byte> level = read.levels[4][0];
                    return write_hdr_image(to, e.width, e.height,
                                           {reinterpret_cast<const float*>(level.data()), level.size() / sizeof(float)});
                });
    }
    if (!options.previews) {
        remove_old("environment.png", no_previews);
    } else if (preview_image) {
        in_background([png_path = staged("environment.png"), e, read] {
            const std::span<const std::byte> level = read.levels[5][0];
            return write_ldr_image(png_path, e.width, e.height,
                                   {reinterpret_cast<const uint8_t*>(level.data()), level.size()});
        });
    }
    for (size_t i = 0; i < std::size(ktx2_outputs); ++i) {
        const Ktx2Output& k = ktx2_outputs[i];
        if (!k.image) {
            remove_old(k.name, k.why_absent);
            continue;
        }
        in_background([to = staged(k.name), file = to_ktx2(*k.image, {}, metadata_.version), read, i] {
            return write_ktx2(to, file, read.levels[i]);
        });
    }
    if (!options.previews) {
        remove_old("brdf_lut.png", no_previews);
    } else if (lut_) {
        // LUT preview: A, B and E_avg lie in [0, 1]; shown linearly, roughness 0 on the top row.
        in_background([to = staged("brdf_lut.png"), desc = lut_.desc(), read] {
            const std::span<const std::byte> level = read.levels[3][0];
            const bool half = desc.format == VK_FORMAT_R16G16B16A16_SFLOAT;
            const size_t n = size_t(desc.width) * desc.height * 4;
            std::vector<uint8_t> png(n);
            for (size_t i = 0; i < n; ++i) {
                float v;
                if (half) {
                    uint16_t h;
                    std::memcpy(&h, level.data() + i * 2, 2);
                    v = half_to_float(h);
                } else {
                    std::memcpy(&v, level.data() + i * 4, 4);
                }
                png[i] = i % 4 == 3 ? 255 : static_cast<uint8_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
            }
            return write_ldr_image(to, desc.width, desc.height, png);
        });
    } else {
        remove_old("brdf_lut.png", "this bake has no BRDF LUT");
    }
    if (sh9_.empty()) remove_old("sh9.json", "this bake does not use spherical harmonics");
    else if (Status s = write_text_file(staged("sh9.json"), sh9_json(sh9_)); !s) return s;
    for (std::future<Status>& w : writing)
        if (Status s = w.get(); !s) return s;
    // bake.json last: the set's marker, its presence with a bake key marks a complete bake.
    return write_text_file(staged("bake.json"), bake_json(*this));
} catch (const BakeCancelled&) {
    return Error{kBakeCancelled};
} catch (const VulkanError& error) {
    return Error{dir + ": reading the baked images back: " + error.what(), error.result()};
}

Result<EncodedEnvironmentFiles> encode_environment_files(const EnvironmentSource& source,
                                                         const BakeSaveOptions& options) {
    if (source.sky || source.image.rgba.empty())
        return Error{source.name + ": a built-in environment's texels are made on the device; nothing to encode ahead"};
    EncodedEnvironmentFiles files;
    files.content_hash = source.content_hash;
    files.width = source.width;
    files.height = source.height;
    files.previews = options.previews;
    // On this thread only: encoding ahead runs beside other work (the device's start).
    auto exr = encode_hdr_image("environment.exr", source.width, source.height, source.image.rgba, 1);
    if (!exr) return exr.error();
    files.exr = std::move(*exr);
    if (options.previews) {
        auto hdr = encode_hdr_image("environment.hdr", source.width, source.height, source.image.rgba);
        if (!hdr) return hdr.error();
        files.hdr = std::move(*hdr);
    }
    return files;
}

EncodedEnvironment::EncodedEnvironment(std::shared_ptr<const EncodedEnvironmentFiles> ready) {
    if (!ready) return;
    std::promise<std::shared_ptr<const EncodedEnvironmentFiles>> made;
    made.set_value(std::move(ready));
    pending_ = made.get_future().share();
}

EncodedEnvironment encode_environment_files_in_background(
    std::shared_future<std::shared_ptr<const EnvironmentSource>> source, const BakeSaveOptions& options) {
    auto work = [source = std::move(source), options]() -> std::shared_ptr<const EncodedEnvironmentFiles> {
        std::shared_ptr<const EnvironmentSource> texels;
        try {
            texels = source.get();
        } catch (const std::future_error&) {  // the caller gave up before it had them
            return nullptr;
        }
        if (!texels) return nullptr;
        auto files = encode_environment_files(*texels, options);
        if (!files) return nullptr;
        return std::make_shared<const EncodedEnvironmentFiles>(std::move(*files));
    };
    return EncodedEnvironment(std::async(std::launch::async, std::move(work)).share());
}

Status BakedEnvironment::save(const std::string& dir, const BakeSaveOptions& options) const {
    if (Status s = ensure_directory(dir); !s) return s;
    OutputSet outputs;
    if (Status s = stage(outputs, dir, {}, nullptr, options); !s) return s;
    return outputs.commit();
}

}  // namespace facet
