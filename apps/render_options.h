#pragma once
// The options facet-render and facet-viewer share: model, environment, camera, display,
// lights, presets and shading switches, parsed into a RenderJob.
#include "cli.h"
#include <facet/render/render_job.h>
#include "start_vulkan.h"

namespace facet {

void add_render_options(cli::Parser& parser);
// Throws std::invalid_argument naming the option.
void parse_render_options(const cli::Parsed& args, RenderJob& job);
// --samples (1, 2, 4 or 8) and --shading (a method's name), where given; throw
// std::invalid_argument naming the option.
uint32_t samples_option(const cli::Parsed& args, uint32_t fallback);
ShadingMethod shading_option(const cli::Parsed& args, ShadingMethod fallback);
// A number option within [min, max]; throws std::invalid_argument naming it.
float number_option(const cli::Parsed& args, const char* name, float min, float max);

}  // namespace facet
