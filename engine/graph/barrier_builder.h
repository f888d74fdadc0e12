#pragma once
// Derives every barrier and layout transition of a compiled graph from the declared
// accesses (synchronisation2), tracking each image subresource separately.
#include <facet/graph/compiled_graph.h>

namespace facet {

// Fills out.passes[i].barriers_before and out.final_barriers; needs out.passes,
// out.lifetimes and the physical resources already decided.
void build_barriers(const RenderGraph& graph, CompiledGraph& out);

}  // namespace facet
