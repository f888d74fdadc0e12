#pragma once
// facet-render's command line, apart from the program so that it can be tested and
// fuzzed without a GPU.
#include <optional>
#include <string>

#include <facet/render/render_job.h>

namespace facet {

struct RenderOptions {
    RenderJob job;
    std::string out, device;
    bool validation = false;
    bool reference = false;
    ReferenceSettings reference_settings;
};

// Nothing when --help or --version was answered; throws std::invalid_argument naming
// the option for bad usage.
std::optional<RenderOptions> parse_render_program_options(int argc, char** argv);

}  // namespace facet
