#pragma once
// The options facet-render and facet-viewer share: model, environment, camera, display,
// lights, presets and shading switches, parsed into a RenderJob.
#include <memory>

#include "cli.h"
#include "gpu/context.h"
#include "render_job.h"

namespace facet {

void add_render_options(cli::Parser& parser);
// Throws std::invalid_argument naming the option.
void parse_render_options(const cli::Parsed& args, RenderJob& job);
// A number option within [min, max]; throws std::invalid_argument naming it.
float number_option(const cli::Parsed& args, const char* name, float min, float max);

// The Vulkan context of a program: the chosen device (empty: FACET_DEVICE, a GPU, else
// lavapipe), validation when asked (else FACET_VALIDATION decides); throws
// std::runtime_error with the reason when Vulkan cannot start.
std::unique_ptr<Context> start_vulkan(const std::string& device, bool validation);

}  // namespace facet
