#pragma once
// Transfer passes that many graphs need: host data into an image.
#include <facet/graph/render_graph.h>

namespace facet {

// Copies tightly packed texels for mip 0 / layer 0 from `staging` (a host-written buffer,
// usually imported with initial state HOST / HOST_WRITE) into `image`; returns the
// image's new version.
ImageHandle add_upload_pass(RenderGraph& graph, const std::string& name, BufferHandle staging, ImageHandle image);

}  // namespace facet
