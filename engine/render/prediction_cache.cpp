#include "render/prediction_cache.h"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>

#include <facet/cache/directory_cache.h>
#include <facet/core/hash.h>
#include <facet/render/specular_lobes.h>
#include "render/lobe_disks.h"
#include "render/shading_choice.h"
#include "shader/embedded_shaders.h"

namespace facet {
namespace {

// Bumped with every change to the probe or the measure that the key cannot see.
constexpr const char* prediction_revision = "prediction-2";
constexpr const char* file_name = "prediction.txt";

std::string cache_key(const RenderSession::State& s, std::span<const ShadingMethod> methods,
                      const PredictionSettings& settings) {
    Hash64 h;
    char text[256];
    std::snprintf(text, sizeof text, "%s|%s|%s|%d|%u|%u,%u,%u,%u|%.17g|%d|", prediction_revision,
                  s.baked->metadata().bake_key.c_str(), brdf_model_name(s.frame.brdf), int(s.frame.multiscatter),
                  s.frame.samples, settings.width, settings.height, settings.truth_env_width, settings.pixels,
                  settings.stop_within, int(settings.two_lookups));
    h.add(text);
    for (ShadingMethod m : methods) h.add(shading_method_name(m)).add("|");
    for (const Material& m : probe_scene(s.scene).materials) {
        std::snprintf(text, sizeof text, "%.9g,%.9g;", double(m.roughness), double(m.metallic));
        h.add(text);
    }
    for (std::size_t i = 0; i < embedded::shader_count; ++i)
        h.add(embedded::shaders[i].name).add("|").add(embedded::shaders[i].text, embedded::shaders[i].size);
    // The rules that pick a material's disks are the library's too (render/lobe_disks.h).
    std::snprintf(text, sizeof text, "%.9g,%.9g,%.9g;", double(kMergedCapLobeFraction), double(kMergedCapMaxRadius),
                  double(kPointCapLobeRatio));
    h.add(text);
    // The fitted lookups' table is data of the library, not of the shaders.
    const std::vector<float> lobes = specular_lobe_table_texels();
    h.add(lobes.data(), lobes.size() * sizeof(float));
    return "prediction-" + h.hex();
}

// One line of groups, then one line per method: name, worst, worst group, 8 group errors, the
// 8 groups' errors with two lookups.
std::string serialize(const ShadingPrediction& p) {
    std::ostringstream out;
    for (bool g : p.groups) out << (g ? 1 : 0) << ' ';
    out << '\n';
    char number[40];
    for (const MethodPrediction& m : p.methods) {
        out << shading_method_name(m.method);
        std::snprintf(number, sizeof number, " %.17g %d", m.worst, m.worst_group);
        out << number;
        for (const auto* errors : {&m.group_error, &m.two_lookup_error})
            for (double e : *errors) {
                std::snprintf(number, sizeof number, " %.17g", e);
                out << number;
            }
        out << '\n';
    }
    return out.str();
}

std::optional<ShadingPrediction> parse(const std::string& text) {
    std::istringstream in(text);
    ShadingPrediction p;
    std::string line;
    if (!std::getline(in, line)) return std::nullopt;
    std::istringstream groups(line);
    for (bool& g : p.groups) {
        int v = 0;
        if (!(groups >> v)) return std::nullopt;
        g = v != 0;
    }
    while (std::getline(in, line)) {
        std::istringstream fields(line);
        std::string name, value;
        MethodPrediction m;
        if (!(fields >> name)) return std::nullopt;
        const auto method = parse_shading_method(name);
        if (!method) return std::nullopt;
        m.method = *method;
        // strtod reads "nan" and "inf" as printf writes them.
        if (!(fields >> value)) return std::nullopt;
        m.worst = std::strtod(value.c_str(), nullptr);
        if (!(fields >> m.worst_group)) return std::nullopt;
        for (auto* errors : {&m.group_error, &m.two_lookup_error})
            for (double& e : *errors) {
                if (!(fields >> value)) return std::nullopt;
                e = std::strtod(value.c_str(), nullptr);
            }
        p.methods.push_back(m);
    }
    if (p.methods.empty()) return std::nullopt;
    return p;
}

}  // namespace

Result<ShadingPrediction> predict_or_reuse(RenderSession::State& s, std::span<const ShadingMethod> methods,
                                           const PredictionSettings& settings, bool& from_cache) {
    from_cache = false;
    const RenderJob& job = s.job;
    if (job.bake_cache_dir.empty() || !job.shader_dir.empty()) return predict_shading_errors(s, methods, settings);
    const std::string key = cache_key(s, methods, settings);
    DirectoryCache cache({job.bake_cache_dir, job.bake_cache_max_bytes, true});
    std::optional<ShadingPrediction> fresh;
    bool predict_failed = false;
    auto entry = cache.get_or_fill(key, [&](const std::string& dir) -> Status {
        auto predicted = predict_shading_errors(s, methods, settings);
        if (!predicted) {
            predict_failed = true;
            return predicted.error();
        }
        std::ofstream out(dir + "/" + file_name, std::ios::binary);
        out << serialize(*predicted);
        if (!out.flush()) return Error{dir + "/" + file_name + ": cannot write"};
        fresh = std::move(predicted).value();
        return Ok{};
    });
    if (!entry) {
        if (predict_failed) return entry.error();
        return predict_shading_errors(s, methods, settings);  // the cache failed: predict without it
    }
    if (fresh) return std::move(*fresh);
    std::ifstream in(entry->path + "/" + file_name, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    if (auto cached = parse(text.str())) {
        from_cache = true;
        return std::move(*cached);
    }
    return predict_shading_errors(s, methods, settings);  // unreadable: predict again
}

}  // namespace facet
