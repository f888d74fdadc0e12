#include "bench_render.h"

#include <algorithm>
#include <cstdio>
#include <map>

#include <facet/gpu/context.h>
#include <facet/io/atomic_file.h>
#include "facet_bench_options.h"
#include <facet/render/render_job.h>
#include "start_vulkan.h"

namespace facet {
namespace {

double median(std::vector<double> v) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

int run_render_bench(const cli::Parsed& a) {
    RenderBenchOptions options;
    try {
        options = parse_render_bench_options(a);
    } catch (const std::invalid_argument& e) {
        std::fprintf(stderr, "facet-bench: error: %s\n", e.what());
        return 2;
    }
    const RenderJob& job = options.job;
    const int frames = options.frames;
    auto created = create_program_context();
    if (!created) {
        std::fprintf(stderr, "facet-bench: error: cannot start Vulkan: %s\n", created.error().message.c_str());
        return 1;
    }
    Context& context = *created.value();
    auto session = RenderSession::create(context, job, [](const std::string& line) {
        std::fprintf(stderr, "facet-bench: %s\n", line.c_str());
    });
    if (!session) {
        std::fprintf(stderr, "facet-bench: error: %s\n", session.error().message.c_str());
        return 1;
    }
    std::map<std::string, std::vector<double>> per_pass, per_pass_wall;
    std::vector<std::string> order;
    std::vector<double> gpu, wall;
    for (int f = -1; f < frames; ++f) {
        auto images = (*session)->render_frame(true);
        if (!images) {
            std::fprintf(stderr, "facet-bench: error: %s\n", images.error().message.c_str());
            return 1;
        }
        if (f < 0) continue;  // warm-up: first use of every pipeline and allocation
        double sum = 0;
        for (const PassTiming& t : images->timings) {
            if (!per_pass.count(t.name)) order.push_back(t.name);
            per_pass[t.name].push_back(t.time_ms);
            sum += t.time_ms;
        }
        for (const PassTiming& t : images->pass_wall) per_pass_wall[t.name].push_back(t.time_ms);
        gpu.push_back(sum);
        wall.push_back(images->wall_ms);
        std::fprintf(stderr, "facet-bench: frame %d/%d: %.1f ms GPU\n", f + 1, frames, sum);
    }
    std::printf("\n%s under %s, %ux%u, %ux MSAA, %s, %zu light(s), %d frames on %s, medians\n", job.model.c_str(),
                job.env.c_str(), job.frame.width, job.frame.height, job.frame.samples,
                job.frame.flat_floor ? "the floor (flat colour)"
                                     : ("shading " + std::string(shading_method_name((*session)->shading().method))).c_str(),
                (*session)->frame().lights.size(), frames, context.device_name().c_str());
    // Wall time per pass (each its own submission, waited for) beside the timestamps:
    // lavapipe defers rasterisation and runs compute asynchronously, so its timestamps
    // can credit one pass with another's work.
    std::string csv = "pass,median_gpu_ms,median_wall_ms,frames\n";
    for (const std::string& name : order) {
        std::printf("  %-24s %9.2f ms GPU %9.2f ms wall\n", name.c_str(), median(per_pass[name]),
                    median(per_pass_wall[name]));
        csv += "\"" + name + "\"," + std::to_string(median(per_pass[name])) + "," +
               std::to_string(median(per_pass_wall[name])) + "," + std::to_string(frames) + "\n";
    }
    std::printf("  %-24s %9.2f ms GPU\n  %-24s %9.2f ms wall (graph, transients, readback)\n", "frame", median(gpu),
                "frame", median(wall));
    double bake = 0;
    for (const PassTiming& t : (*session)->bake_timings()) bake += t.time_ms;
    std::printf("  %-24s %9.2f ms GPU (once)\n", "IBL bake", bake);
    csv += "\"frame\"," + std::to_string(median(gpu)) + "," + std::to_string(median(wall)) + "," +
           std::to_string(frames) + "\n";
    if (a.has("--csv"))
        if (Status s = write_text_file(a.get("--csv"), csv); !s) {
            std::fprintf(stderr, "facet-bench: error: %s\n", s.error().message.c_str());
            return 1;
        }
    return 0;
}

}  // namespace facet
