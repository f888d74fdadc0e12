#pragma once
// facet-viewer's command line and --script commands, apart from the program so that
// they can be tested and fuzzed without a GPU or a window.
#include <optional>
#include <string>
#include <vector>

#include <facet/render/render_job.h>

namespace facet {

struct ViewerOptions {
    RenderJob job;
    std::vector<std::string> script;  // commands (see --script); empty: interactive
    std::string device;
};

// Nothing when --help or --version was answered; throws std::invalid_argument naming
// the option (or the script command) for bad usage.
std::optional<ViewerOptions> parse_viewer_options(int argc, char** argv);

}  // namespace facet
