// facet-bench: speed measurements (never pass/fail). `bake` runs facet-bake on each
// environment several times (--force, fresh process each time) and reports the median
// GPU time of every pass (timestamp queries, from bake.json) and of the whole bake, and
// the median wall time, as a table on stdout and optionally CSV. `render` measures
// frames of the forward renderer (apps/bench_render.h). `accuracy` measures the final
// image against the exact integral of its BRDF model (apps/bench_accuracy.h).
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <regex>
#include <string>
#include <vector>

#include "bench_accuracy.h"
#include "bench_render.h"
#include "bench_sweep.h"
#include "cli.h"
#include "facet_bench_options.h"
#include <facet/io/atomic_file.h>

namespace {

namespace fs = std::filesystem;
constexpr const char* program = "facet-bench";

double median(std::vector<double> v) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::string quote(const std::string& s) {
    std::string out = "'";
    for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

struct Run {
    std::vector<std::pair<std::string, double>> passes;  // name, GPU ms, in order
    double gpu_ms = 0, wall_ms = 0;
};

// Reads the fields facet-bake's bake.json writes (its format is ours; no JSON library).
bool parse_bake_json(const std::string& text, Run& run) {
    static const std::regex pass(R"re(\{\s*"name": "([^"]*)",\s*"gpu_time_ms": ([0-9.eE+-]+)\s*\})re");
    static const std::regex gpu(R"re("gpu_time_ms": ([0-9.eE+-]+),\s*"wall_time_ms": ([0-9.eE+-]+))re");
    for (auto it = std::sregex_iterator(text.begin(), text.end(), pass); it != std::sregex_iterator(); ++it)
        run.passes.emplace_back((*it)[1].str(), std::stod((*it)[2].str()));
    std::smatch m;
    if (!std::regex_search(text, m, gpu)) return false;
    run.gpu_ms = std::stod(m[1].str());
    run.wall_ms = std::stod(m[2].str());
    return !run.passes.empty();
}

}  // namespace

int main(int argc, char** argv) {
    // accuracy takes facet-render's options (its own parser).
    if (argc > 1 && std::string(argv[1]) == "accuracy") return facet::run_accuracy(argc, argv);
    std::optional<facet::BenchOptions> options;
    try {
        options = facet::parse_bench_options(argc, argv);
        if (!options) return 0;
    } catch (const std::invalid_argument& e) {
        std::fprintf(stderr, "%s: error: %s\n", program, e.what());
        return 2;
    }
    const facet::cli::Parsed& a = options->args;
    const int runs = options->runs;
    if (a.positional[0] == "render") return facet::run_render_bench(a);
    if (a.positional[0] == "sweep") return facet::run_sweep(a);
    std::vector<std::string> envs(a.positional.begin() + 1, a.positional.end());
    if (envs.empty()) envs = {"builtin:sky"};
    const std::string bake =
        a.has("--bake") ? a.get("--bake") : (fs::canonical("/proc/self/exe").parent_path() / "facet-bake").string();
    std::error_code missing;  // the throwing overload would abort on a name too long
    if (!fs::exists(bake, missing)) {
        std::fprintf(stderr, "%s: error: %s: no such program (use --bake PATH)\n", program, bake.c_str());
        return 1;
    }
    const fs::path work = fs::temp_directory_path() / ("facet-bench-" + std::to_string(::getpid()));
    std::string csv = "environment,pass,median_gpu_ms,runs\n";
    int status = 0;
    for (const std::string& env : envs) {
        std::vector<Run> results;
        for (int r = 0; r < runs; ++r) {
            std::fprintf(stderr, "%s: %s, run %d/%d\n", program, env.c_str(), r + 1, runs);
            // facet-bake uses the shader cache facet-bench was given (or none).
            const std::string shader_cache = options->shader_cache.empty()
                                                 ? std::string("--no-shader-cache")
                                                 : "--shader-cache " + quote(options->shader_cache);
            const std::string command = quote(bake) + " " + quote(env) + " --force --out " + quote(work.string()) +
                                        " " + shader_cache + " " + a.get("--bake-args") + " > /dev/null 2> " +
                                        quote((work.string() + ".log"));
            const int raw = std::system(command.c_str());
            std::ifstream in(work / "bake.json");
            std::string text((std::istreambuf_iterator<char>(in)), {});
            Run run;
            if (raw != 0 || !parse_bake_json(text, run)) {
                std::ifstream log(work.string() + ".log");
                std::string reason((std::istreambuf_iterator<char>(log)), {});
                std::fprintf(stderr, "%s: %s: the bake failed:\n%s", program, env.c_str(), reason.c_str());
                status = 1;
                break;
            }
            results.push_back(std::move(run));
        }
        if (results.empty()) continue;
        std::printf("\n%s: %zu runs, medians\n", env.c_str(), results.size());
        std::map<std::string, std::vector<double>> per_pass;
        for (const Run& run : results)
            for (const auto& [name, ms] : run.passes) per_pass[name].push_back(ms);
        for (const auto& [name, ms] : results.front().passes) {
            const double m = median(per_pass[name]);
            std::printf("  %-42s %9.2f ms GPU\n", name.c_str(), m);
            csv += "\"" + env + "\",\"" + name + "\"," + std::to_string(m) + "," + std::to_string(results.size()) + "\n";
        }
        std::vector<double> gpu, wall;
        for (const Run& run : results) {
            gpu.push_back(run.gpu_ms);
            wall.push_back(run.wall_ms);
        }
        std::printf("  %-42s %9.2f ms GPU\n  %-42s %9.2f ms wall (load, bake, read back, write)\n", "whole bake",
                    median(gpu), "whole bake", median(wall));
        csv += "\"" + env + "\",\"whole bake (GPU)\"," + std::to_string(median(gpu)) + "," + std::to_string(results.size()) + "\n";
        csv += "\"" + env + "\",\"whole bake (wall)\"," + std::to_string(median(wall)) + "," + std::to_string(results.size()) + "\n";
    }
    std::error_code ec;
    fs::remove_all(work, ec);
    fs::remove(work.string() + ".log", ec);
    if (a.has("--csv"))
        if (facet::Status s = facet::write_text_file(a.get("--csv"), csv); !s) {
            std::fprintf(stderr, "%s: error: %s\n", program, s.error().message.c_str());
            return 1;
        }
    return status;
}
