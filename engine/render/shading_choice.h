#pragma once
// The session's shading method resolved from the job (render/render_job.h): an explicit
// --shading, the older switches (extract_lights, frame.dominant_direction), or the
// automatic choice, made in two steps: before the bake (extract lights, wide regions
// included) and after it (what the extraction found).
#include <cstddef>

#include <facet/render/render_job.h>
#include <facet/render/shading_method.h>

namespace facet {

struct ResolvedShading {
    RenderJob job;  // the request with extract_lights and frame.dominant_direction set
    ShadingChoice choice;
};

ResolvedShading resolve_shading(const RenderJob& requested);
// After the bake: `lights` disks found holding `power_fraction` of the environment's power.
void finish_shading_choice(ResolvedShading& shading, size_t lights, double power_fraction);

}  // namespace facet
