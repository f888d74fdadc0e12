#include "bench_sweep.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <sstream>

#include <facet/gpu/context.h>
#include <facet/gpu/transfer.h>
#include <facet/graph/compiled_graph.h>
#include <facet/graph/graph_run.h>
#include <facet/ibl/ibl_bake.h>
#include <facet/io/atomic_file.h>
#include <facet/io/image_io.h>
#include <facet/io/json_writer.h>
#include "bench_sweep_image.h"
#include "facet_bench_options.h"
#include <facet/render/render_job.h>
#include "shader_cache.h"
#include "start_vulkan.h"
#include <facet/shader/program_cache.h>
#include <facet/ibl/ibl_measure.h>
#include <facet/reference/ibl_reference.h>

namespace facet {
namespace {

namespace fs = std::filesystem;

using Row = SweepRow;

void finish(const ErrorStats& stats, Row& row, double bound) {
    row.rel_rmse = stats.rel_rmse();
    row.max_rel = stats.max_rel;
    row.psnr = stats.psnr();
    if (stats.bad) row.failed = true, row.failure = "NaN, Inf or negative values";
    else if (!std::isfinite(row.rel_rmse) || row.rel_rmse > bound)
        row.failed = true, row.failure = "error above the bound of " + std::to_string(int(std::lround(bound * 100))) + "%";
}

Result<test::Equirect> texels_of(Context& context, ProgramCache& programs, EnvironmentSource& env) {
    if (Status s = materialize_environment(context, programs, env); !s) return s.error();
    // The sweep measures the bake of these texels against their truth, the cube included.
    env.sky_model.reset();
    return test::Equirect{env.width, env.height, env.image.rgba};
}

// Box-downsamples a file environment to `width` (power-of-two factors), so that the sweep
// and its truth stay fast; the truth uses the same texels.
void downsample_to(EnvironmentSource& env, uint32_t width) {
    if (env.sky || env.width <= width) return;
    test::Equirect e{env.width, env.height, env.image.rgba};
    const uint32_t factor = env.width / width;
    if (factor < 2) return;
    e = test::downsample(e, factor);
    env.image.rgba = e.rgba;
    env.width = env.image.width = e.w;
    env.height = env.image.height = e.h;
}

// Group columns: issue 13's roughness bands x dielectric/metal, in FinalImageAccuracy's order.
std::string group_column(size_t g) {
    static const char* bands[] = {"0.2-0.4", "0.4-0.6", "0.6-0.8", "0.8-1.0"};
    return std::string("r") + bands[g / 2] + (g % 2 ? " metal" : " dielectric");
}

std::string csv_of(const std::vector<Row>& rows) {
    std::string csv = "environment,stage,method,parameters,gpu_ms,rel_rmse,max_rel,psnr_db,failed,failure,brdf,"
                      "samples_per_pixel,auto_choice,worst_group_mean_rel,worst_group";
    for (size_t g = 0; g < 8; ++g) csv += ",\"" + group_column(g) + "\"";
    csv += "\n";
    for (const Row& r : rows) {
        std::ostringstream line;
        line << '"' << r.env << "\"," << r.stage << ",\"" << r.method << "\",\"" << r.params << "\"," << r.gpu_ms << ','
             << r.rel_rmse << ',' << r.max_rel << ',' << r.psnr << ',' << (r.failed ? 1 : 0) << ",\"" << r.failure
             << "\"," << r.brdf << ',' << r.samples_per_pixel << ',' << r.auto_choice << ',';
        if (r.accuracy) {
            const test::FinalImageAccuracy& a = *r.accuracy;
            line << a.worst_mean_rel << ",\"" << (a.worst >= 0 ? test::group_name(a.groups[size_t(a.worst)]) : "") << '"';
            for (const test::GroupError& g : a.groups) line << ',' << g.mean_rel;
        } else {
            line << ',' << std::string(8, ',');
        }
        csv += line.str() + "\n";
    }
    return csv;
}

std::string json_of(const std::vector<Row>& rows, const std::string& device, const SweepOptions& o) {
    JsonWriter j;
    j.begin_object().value("program", "facet-bench sweep").value("version", FACET_VERSION).value("device", device);
    j.value("environment_width", o.env_width).value("runs", o.runs);
    j.value("image_width", o.image_width).value("image_height", o.image_height).value("truth_pixels", o.max_pixels);
    j.value("time", "wall time of each setting's passes, each pass its own submission (median of the runs); "
                    "stage image: the frame's passes except the views, or the whole reference-mode call");
    j.value("image_error", "per roughness x metalness group: mean of |lum(render) - lum(truth)| / lum(truth) "
                           "against the exact sum over every texel (issue 13); worst_group_mean_rel: the worst group");
    j.begin_array("rows");
    for (const Row& r : rows) {
        j.begin_object().value("environment", r.env).value("stage", r.stage).value("method", r.method);
        j.value("parameters", r.params).value("gpu_ms", r.gpu_ms).value("rel_rmse", r.rel_rmse);
        j.value("max_rel", r.max_rel).value("psnr_db", r.psnr).value("failed", r.failed).value("failure", r.failure);
        if (r.accuracy) {
            const test::FinalImageAccuracy& a = *r.accuracy;
            j.value("brdf", r.brdf).value("samples_per_pixel", r.samples_per_pixel);
            if (!r.auto_choice.empty()) j.value("auto_choice", r.auto_choice).value("auto_reason", r.auto_reason);
            j.value("worst_group_mean_rel", a.worst_mean_rel);
            j.value("worst_group", a.worst >= 0 ? test::group_name(a.groups[size_t(a.worst)]) : std::string("none"));
            j.value("pixels", uint32_t(a.pixels)).value("truth_seconds", a.truth_seconds);
            j.begin_array("groups");
            for (const test::GroupError& g : a.groups) {
                j.begin_object().value("group", test::group_name(g)).value("metal", g.metal);
                j.value("roughness_min", g.roughness_min).value("roughness_max", g.roughness_max);
                j.value("pixels", uint32_t(g.pixels)).value("mean_rel", g.mean_rel).value("max_rel", g.max_rel);
                j.value("mean_signed", g.mean_signed).end_object();
            }
            j.end_array();
        }
        j.end_object();
    }
    j.end_array().end_object();
    return j.str();
}

}  // namespace

int run_sweep(const cli::Parsed& a) {
    SweepOptions options;
    try {
        options = parse_sweep_options(a);
    } catch (const std::invalid_argument& e) {
        std::fprintf(stderr, "facet-bench: error: %s\n", e.what());
        return 2;
    }
    const std::vector<std::string>& envs = options.envs;
    const uint32_t width = options.env_width;
    const int runs = options.runs;
    const std::string& stages = options.stages;
    const std::string& out_dir = options.out_dir;
    auto created = create_program_context();
    if (!created) {
        std::fprintf(stderr, "facet-bench: error: cannot start Vulkan: %s\n", created.error().message.c_str());
        return 1;
    }
    Context& context = *created.value();
    IblMeasure sweep(context, runs, ShaderCompilerOptions{shader_dir_from_environment(), options.shader_cache});
    std::vector<Row> rows;
    auto fail = [](const std::string& message) {
        std::fprintf(stderr, "facet-bench: error: %s\n", message.c_str());
        return 1;
    };
    auto has_stage = [&](const char* s) { return stages.find(s) != std::string::npos; };
    for (const std::string& name : envs) {
        auto resolved = resolve_environment(name, width);
        if (!resolved) return fail(resolved.error().message);
        EnvironmentSource env = std::move(resolved).value();
        auto texels = texels_of(context, sweep.programs(), env);
        if (!texels) return fail(texels.error().message);
        downsample_to(env, width);
        const test::Equirect e{env.width, env.height, env.image.rgba};
        const std::string label = fs::path(name).stem().string();
        std::fprintf(stderr, "facet-bench: sweep %s (%ux%u)\n", label.c_str(), e.w, e.h);
        auto record = [&](Row row, const ErrorStats& stats, double bound) {
            row.env = label;
            finish(stats, row, bound);
            std::fprintf(stderr, "facet-bench:   %-10s %-10s %-22s %8.2f ms  relRMSE %.4f%s\n", row.stage.c_str(),
                         row.method.c_str(), row.params.c_str(), row.gpu_ms, row.rel_rmse,
                         row.failed ? ("  FAILED: " + row.failure).c_str() : "");
            rows.push_back(row);
        };

        if (has_stage("irradiance")) {
            struct Config {
                const char* method;
                std::string params;
                std::function<void(IrradianceSettings&)> set;
            };
            std::vector<Config> configs;
            for (uint32_t src : {4u, 8u, 16u, 32u})
                configs.push_back({"convolve", "source " + std::to_string(src),
                                   [src](IrradianceSettings& s) { s.method = IrradianceMethod::convolve; s.source_size = src; }});
            for (float step : {0.1f, 0.05f, 0.025f})
                configs.push_back({"riemann", "step " + std::to_string(step).substr(0, 5),
                                   [step](IrradianceSettings& s) { s.method = IrradianceMethod::riemann; s.riemann_step = step; }});
            configs.push_back({"sh9", "windowed", [](IrradianceSettings& s) { s.method = IrradianceMethod::sh9; }});
            configs.push_back({"sh9-raw", "no window", [](IrradianceSettings& s) {
                                   s.method = IrradianceMethod::sh9;
                                   s.sh9_windowing = false;
                               }});
            for (float sigma : {0.25f, 0.5f})
                configs.push_back({"blur", "sigma " + std::to_string(sigma).substr(0, 4),
                                   [sigma](IrradianceSettings& s) { s.method = IrradianceMethod::blur; s.blur_sigma = sigma; }});
            for (uint32_t size : {1u, 2u, 4u})
                configs.push_back({"lowmip", "face " + std::to_string(size),
                                   [size](IrradianceSettings& s) { s.method = IrradianceMethod::lowmip; s.lowmip_size = size; }});
            for (const Config& c : configs) {
                IblSettings settings;
                c.set(settings.irradiance);
                auto baked = sweep.bake(env, settings, "irradiance");
                if (!baked) return fail(label + ": irradiance " + c.method + ": " + baked.error().message);
                ErrorStats stats;
                compare_cube(*baked, 0, [&](const test::Vec3& n) { return test::irradiance_over_pi(e, n); }, stats);
                record({"", "irradiance", c.method, c.params, baked->gpu_ms}, stats, 0.05);
            }
        }
        if (has_stage("specular")) {
            struct Config {
                const char* method;
                std::string params;
                SpecularSettings settings;
                uint32_t cube_size = 0;  // 0: the input's height / 2
            };
            std::vector<Config> configs;
            for (uint32_t n : {64u, 256u, 1024u, 4096u}) {
                SpecularSettings s;
                s.sample_count = n;
                s.method = SpecularMethod::importance;
                configs.push_back({"importance", std::to_string(n) + " samples", s});
                s.method = SpecularMethod::filtered;
                configs.push_back({"filtered", std::to_string(n) + " samples", s});
            }
            SpecularSettings s;
            s.method = SpecularMethod::convolve;
            configs.push_back({"convolve", "texel blocks", s});
            s.method = SpecularMethod::mips;
            configs.push_back({"mips", "environment mips", s});
            for (uint32_t n : {16u, 64u, 256u}) {
                s.method = SpecularMethod::hybrid;
                s.hybrid_sample_count = n;
                configs.push_back({"hybrid", std::to_string(n) + " samples", s});
            }
            s = SpecularSettings{};
            configs.push_back({"automatic", "defaults", s});
            // Sizes: the same methods on a cube half as large (faster, coarser levels).
            const uint32_t half = std::max(1u, e.h / 4);
            s.method = SpecularMethod::automatic;
            s.sample_count = 1024;
            configs.push_back({"automatic", "defaults, cube " + std::to_string(half), s, half});
            s.method = SpecularMethod::filtered;
            configs.push_back({"filtered", "1024 samples, cube " + std::to_string(half), s, half});
            const test::TexelTable table(e);
            for (const Config& c : configs) {
                IblSettings settings;
                settings.specular = c.settings;
                settings.cube_size = c.cube_size;
                auto baked = sweep.bake(env, settings, "specular");
                if (!baked) return fail(label + ": specular " + c.method + ": " + baked.error().message);
                ErrorStats stats;
                for (uint32_t m = 1; m < baked->levels; ++m) {
                    const double roughness = double(m) / (baked->levels - 1);
                    compare_cube(*baked, m, [&](const test::Vec3& n) { return test::prefiltered(table, n, roughness); },
                                 stats);
                }
                record({"", "specular", c.method, c.params, baked->gpu_ms}, stats, 0.1);
            }
        }
        if (has_stage("lut") && name == envs.front()) {
            // The LUT does not depend on the environment: once, under the first one.
            for (uint32_t size : {32u, 64u, 128u})
                for (uint32_t samples : {128u, 512u, 2048u}) {
                    IblSettings settings;
                    settings.lut.size = size;
                    settings.lut.sample_count = samples;
                    auto baked = sweep.bake(env, settings, "lut");
                    if (!baked) return fail("lut: " + baked.error().message);
                    const ErrorStats stats = lut_error(*baked, settings.lut.brdf == BrdfModel::gltf);
                    Row row{"", "lut", "lut " + std::to_string(size), std::to_string(samples) + " samples", baked->gpu_ms};
                    row.env = "any";
                    finish(stats, row, 0.05);
                    rows.push_back(row);
                    std::fprintf(stderr, "facet-bench:   lut %3u^2 %5u samples %8.2f ms  relRMSE %.5f\n", size, samples,
                                 row.gpu_ms, row.rel_rmse);
                }
        }
        if (has_stage("image"))
            if (Status st = sweep_final_image(context, e, label, options, [&](SweepRow row) {
                    const test::FinalImageAccuracy& a = *row.accuracy;
                    std::fprintf(stderr, "facet-bench:   image %-6s %-16s %-22s %9.2f ms  worst group %6.2f%% (%s)%s\n",
                                 row.brdf.c_str(), row.method.c_str(), row.params.c_str(), row.gpu_ms,
                                 100 * a.worst_mean_rel,
                                 a.worst >= 0 ? test::group_name(a.groups[size_t(a.worst)]).c_str() : "none",
                                 row.failed ? ("  FAILED: " + row.failure).c_str() : "");
                    rows.push_back(std::move(row));
                });
                !st)
                return fail(st.error().message);
    }
    std::error_code ec;
    fs::create_directories(out_dir, ec);
    if (Status s = write_text_file((fs::path(out_dir) / "sweep.csv").string(), csv_of(rows)); !s)
        return fail(s.error().message);
    if (Status s = write_text_file((fs::path(out_dir) / "sweep.json").string(),
                                   json_of(rows, context.device_name(), options));
        !s)
        return fail(s.error().message);
    std::printf("wrote %s/sweep.csv and sweep.json (%zu rows); charts: /usr/bin/python3 scripts/chart.py %s\n",
                out_dir.c_str(), rows.size(), out_dir.c_str());
    return 0;
}

}  // namespace facet
