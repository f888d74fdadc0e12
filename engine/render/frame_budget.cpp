#include <facet/render/frame_budget.h>

#include <algorithm>
#include <string>

#include <facet/render/views.h>

namespace facet {

std::vector<NamedImage> frame_target_images(const FrameSettings& s) {
    ImageDesc hdr;
    hdr.width = s.width;
    hdr.height = s.height;
    ImageDesc msaa = hdr;
    msaa.samples = VkSampleCountFlagBits(std::max(s.samples, 1u));
    ImageDesc depth = msaa;
    depth.format = VK_FORMAT_D32_SFLOAT;
    ImageDesc ldr = hdr;
    ldr.format = VK_FORMAT_R8G8B8A8_UNORM;
    std::vector<NamedImage> images = {{"HDR colour", hdr, true}, {"depth", depth, true}, {"display colour", ldr, true}};
    if (s.samples > 1) images.push_back({"MSAA colour", msaa, true});
    if (s.skybox) images.push_back({"skybox composite", hdr, true});
    ImageDesc view_depth = hdr;
    view_depth.format = VK_FORMAT_D32_SFLOAT;
    for (View v : s.views) {
        images.push_back({std::string("view ") + view_name(v), hdr, true});
        images.push_back({"view depth", view_depth, true});
    }
    return images;
}

Status check_frame_fits(const Context& context, const FrameSettings& s) {
    Status fits = check_images_fit(device_limits(context), frame_target_images(s));
    if (!fits)
        return Error{"a " + std::to_string(s.width) + "x" + std::to_string(s.height) + " frame with " +
                     std::to_string(s.samples) + " samples and " + std::to_string(s.views.size()) +
                     " views does not fit: " + fits.error().message};
    return Ok{};
}

}  // namespace facet
