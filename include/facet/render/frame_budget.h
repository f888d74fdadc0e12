#pragma once
// The frame's render targets against the device (gpu/device_limits.h), checked from the
// settings alone so that an image size no device can hold (a 16384 x 16384 frame with
// 8x MSAA is 34 GiB) is refused before the scene is loaded and the lighting baked.
#include <vector>

#include <facet/core/result.h>
#include <facet/gpu/device_limits.h>
#include <facet/render/forward_renderer.h>

namespace facet {

class Context;

// What ForwardRenderer::add_passes creates for these settings: the HDR target, its
// MSAA colour and depth, the skybox composite, the display image and each view's
// target and depth.
std::vector<NamedImage> frame_target_images(const FrameSettings& settings);

// Fails naming the frame's size, sample count and the limit it breaks.
Status check_frame_fits(const Context& context, const FrameSettings& settings);

}  // namespace facet
