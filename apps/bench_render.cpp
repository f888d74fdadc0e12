#include "bench_render.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

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

// One shading method's session and what its frames measured.
struct Measured {
    std::unique_ptr<RenderSession> session;
    std::map<std::string, std::vector<double>> per_pass, per_pass_wall;
    std::vector<std::string> order;
    std::vector<double> gpu, wall;

    // Renders one frame; a measured one (not the warm-up) is recorded.
    Status frame(bool measured) {
        auto images = session->render_frame(true);
        if (!images) return images.error();
        if (!measured) return Ok{};  // warm-up: first use of every pipeline and allocation
        double sum = 0;
        for (const PassTiming& t : images->timings) {
            if (!per_pass.count(t.name)) order.push_back(t.name);
            per_pass[t.name].push_back(t.time_ms);
            sum += t.time_ms;
        }
        for (const PassTiming& t : images->pass_wall) per_pass_wall[t.name].push_back(t.time_ms);
        gpu.push_back(sum);
        wall.push_back(images->wall_ms);
        return Ok{};
    }

    // The table of medians; its CSV rows appended to `csv`.
    void print(const RenderJob& job, int frames, const Context& context, std::string& csv) {
        std::printf("\n%s under %s, %ux%u, %ux MSAA, %s, %zu light(s), %d frames on %s, medians\n", job.model.c_str(),
                    job.env.c_str(), job.frame.width, job.frame.height, job.frame.samples,
                    job.frame.flat_floor ? "the floor (flat colour)"
                                         : ("shading " + std::string(shading_method_name(session->shading().method))).c_str(),
                    session->frame().lights.size(), frames, context.device_name().c_str());
        // Wall time per pass (each its own submission, waited for) beside the timestamps:
        // lavapipe defers rasterisation and runs compute asynchronously, so its timestamps
        // can credit one pass with another's work.
        for (const std::string& name : order) {
            std::printf("  %-24s %9.2f ms GPU %9.2f ms wall\n", name.c_str(), median(per_pass[name]),
                        median(per_pass_wall[name]));
            csv += "\"" + name + "\"," + std::to_string(median(per_pass[name])) + "," +
                   std::to_string(median(per_pass_wall[name])) + "," + std::to_string(frames) + "\n";
        }
        std::printf("  %-24s %9.2f ms GPU\n  %-24s %9.2f ms wall (graph, transients, readback)\n", "frame", median(gpu),
                    "frame", median(wall));
        double bake = 0;
        for (const PassTiming& t : session->bake_timings()) bake += t.time_ms;
        std::printf("  %-24s %9.2f ms GPU (once)\n", "IBL bake", bake);
        csv += "\"frame\"," + std::to_string(median(gpu)) + "," + std::to_string(median(wall)) + "," +
               std::to_string(frames) + "\n";
    }
};

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
    auto say = [](const std::string& line) { std::fprintf(stderr, "facet-bench: %s\n", line.c_str()); };
    // The job's method, and --compare's in a session of its own (its own bake: a method that
    // extracts lights bakes another map).
    std::vector<RenderJob> jobs{job};
    if (options.compare) {
        jobs.push_back(job);
        jobs.back().shading = *options.compare;
    }
    std::vector<Measured> runs(jobs.size());
    for (size_t i = 0; i < jobs.size(); ++i) {
        auto session = RenderSession::create(context, jobs[i], say);
        if (!session) {
            std::fprintf(stderr, "facet-bench: error: %s\n", session.error().message.c_str());
            return 1;
        }
        runs[i].session = std::move(*session);
    }
    // Frame by frame, the methods in turn.
    for (int f = -1; f < frames; ++f)
        for (Measured& r : runs) {
            if (Status s = r.frame(f >= 0); !s) {
                std::fprintf(stderr, "facet-bench: error: %s\n", s.error().message.c_str());
                return 1;
            }
            if (f >= 0)
                std::fprintf(stderr, "facet-bench: frame %d/%d%s: %.1f ms GPU\n", f + 1, frames,
                             runs.size() > 1 ? (std::string(", ") + shading_method_name(r.session->shading().method)).c_str()
                                             : "",
                             r.gpu.back());
        }
    std::string csv = "pass,median_gpu_ms,median_wall_ms,frames\n";
    runs[0].print(job, frames, context, csv);
    if (runs.size() > 1) {
        std::string ignored;
        runs[1].print(jobs[1], frames, context, ignored);
        // The forward pass's ratio: of the medians, and the median of the frame pairs' ratios.
        const std::vector<double>& a_forward = runs[0].per_pass["forward"];
        const std::vector<double>& b_forward = runs[1].per_pass["forward"];
        std::vector<double> ratios;
        for (size_t i = 0; i < std::min(a_forward.size(), b_forward.size()); ++i)
            if (b_forward[i] > 0) ratios.push_back(a_forward[i] / b_forward[i]);
        const std::string a_name = shading_method_name(runs[0].session->shading().method);
        const std::string b_name = shading_method_name(runs[1].session->shading().method);
        std::printf("\n  forward %s / %s: %.2fx (medians), %.2fx (median of %zu frame pairs, in turn in one process)\n",
                    a_name.c_str(), b_name.c_str(), median(a_forward) / std::max(median(b_forward), 1e-9),
                    median(ratios), ratios.size());
    }
    if (a.has("--csv"))
        if (Status s = write_text_file(a.get("--csv"), csv); !s) {
            std::fprintf(stderr, "facet-bench: error: %s\n", s.error().message.c_str());
            return 1;
        }
    return 0;
}

}  // namespace facet
