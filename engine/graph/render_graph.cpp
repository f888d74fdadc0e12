#include <facet/graph/render_graph.h>

#include <facet/core/result.h>
#include "graph/access.h"

namespace facet {

namespace {

std::string describe(const PassNode& pass, const ResourceNode& resource) {
    return "pass '" + pass.name + "', resource '" + resource.name + "'";
}

}  // namespace

ImageHandle RenderGraph::create_image(std::string name, const ImageDesc& desc) {
    if (desc.width == 0 || desc.height == 0 || desc.mip_levels == 0 || desc.array_layers == 0)
        throw UsageError("image '" + name + "' has a zero size, mip count or layer count");
    ResourceNode node;
    node.name = std::move(name);
    node.image_desc = desc;
    resources_.push_back(std::move(node));
    return {static_cast<uint32_t>(resources_.size() - 1), 0};
}

BufferHandle RenderGraph::create_buffer(std::string name, const BufferDesc& desc) {
    if (desc.size == 0) throw UsageError("buffer '" + name + "' has size 0");
    ResourceNode node;
    node.name = std::move(name);
    node.is_image = false;
    node.buffer_desc = desc;
    resources_.push_back(std::move(node));
    return {static_cast<uint32_t>(resources_.size() - 1), 0};
}

ImageHandle RenderGraph::import_image(std::string name, const ImportedImage& image) {
    if (!image.image) throw UsageError("imported image '" + name + "' has no VkImage");
    ResourceNode node;
    node.name = std::move(name);
    node.image_desc = image.desc;
    node.imported = true;
    node.imported_image = image;
    resources_.push_back(std::move(node));
    return {static_cast<uint32_t>(resources_.size() - 1), 0};
}

BufferHandle RenderGraph::import_buffer(std::string name, const ImportedBuffer& buffer) {
    if (!buffer.buffer) throw UsageError("imported buffer '" + name + "' has no VkBuffer");
    ResourceNode node;
    node.name = std::move(name);
    node.is_image = false;
    node.buffer_desc = {buffer.size};
    node.imported = true;
    node.imported_buffer = buffer;
    resources_.push_back(std::move(node));
    return {static_cast<uint32_t>(resources_.size() - 1), 0};
}

void RenderGraph::export_image(ImageHandle image, ResourceState final) {
    ResourceNode& node = resources_.at(image.index);
    if (!node.is_image) throw UsageError("export_image: '" + node.name + "' is a buffer");
    node.exported = true;
    node.export_state = final;
}

void RenderGraph::export_buffer(BufferHandle buffer, ResourceState final) {
    ResourceNode& node = resources_.at(buffer.index);
    if (node.is_image) throw UsageError("export_buffer: '" + node.name + "' is an image");
    node.exported = true;
    node.export_state = final;
}

uint32_t RenderGraph::add_pass(std::string name, PassKind kind, const Setup& setup, Execute execute) {
    PassNode pass;
    pass.name = std::move(name);
    pass.kind = kind;
    pass.execute = std::move(execute);
    passes_.push_back(std::move(pass));
    const uint32_t index = static_cast<uint32_t>(passes_.size() - 1);
    PassBuilder builder(*this, index);
    if (setup) setup(builder);
    return index;
}

void RenderGraph::add_dependency(uint32_t before, uint32_t after) {
    if (before >= passes_.size() || after >= passes_.size())
        throw UsageError("add_dependency: no such pass");
    dependencies_.emplace_back(before, after);
}

uint32_t PassBuilder::use(bool is_image, uint32_t index, uint32_t version, Access access, ImageRange range) {
    PassNode& pass = graph_.passes_[pass_];
    if (index >= graph_.resources_.size())
        throw UsageError("pass '" + pass.name + "' uses an invalid handle");
    ResourceNode& resource = graph_.resources_[index];
    if (resource.is_image != is_image)
        throw UsageError(describe(pass, resource) + ": handle kind does not match the resource");
    access_info(pass.kind, access, is_image);  // throws for accesses the pass kind cannot make
    if (version != resource.version())
        throw UsageError(describe(pass, resource) + ": stale handle (version " + std::to_string(version) +
                         ", the resource is at version " + std::to_string(resource.version()) +
                         "; use the handle the last write returned)");
    const bool write = is_write(access);
    if (!write && version == 0 && !resource.imported)
        throw UsageError(describe(pass, resource) + ": reads a resource that no pass has written");
    if (is_image) {
        const ImageDesc& d = resource.image_desc;
        if (range.mip_count == all_remaining) range.mip_count = d.mip_levels - std::min(range.base_mip, d.mip_levels);
        if (range.layer_count == all_remaining)
            range.layer_count = d.array_layers - std::min(range.base_layer, d.array_layers);
        if (range.mip_count == 0 || range.layer_count == 0 || range.base_mip + range.mip_count > d.mip_levels ||
            range.base_layer + range.layer_count > d.array_layers)
            throw UsageError(describe(pass, resource) + ": mip/layer range outside the image");
    }
    pass.uses.push_back({is_image, index, version, access, range});
    if (!write) return version;
    resource.producers.push_back(pass_);
    return resource.version();
}

ImageHandle PassBuilder::read(ImageHandle image, Access access, ImageRange range) {
    if (is_write(access)) throw UsageError(std::string("read() with a writing access: ") + access_name(access));
    return {image.index, use(true, image.index, image.version, access, range)};
}

ImageHandle PassBuilder::write(ImageHandle image, Access access, ImageRange range) {
    if (!is_write(access)) throw UsageError(std::string("write() with a read-only access: ") + access_name(access));
    return {image.index, use(true, image.index, image.version, access, range)};
}

BufferHandle PassBuilder::read(BufferHandle buffer, Access access) {
    if (is_write(access)) throw UsageError(std::string("read() with a writing access: ") + access_name(access));
    return {buffer.index, use(false, buffer.index, buffer.version, access, {})};
}

BufferHandle PassBuilder::write(BufferHandle buffer, Access access) {
    if (!is_write(access)) throw UsageError(std::string("write() with a read-only access: ") + access_name(access));
    return {buffer.index, use(false, buffer.index, buffer.version, access, {})};
}

void PassBuilder::side_effect() { graph_.passes_[pass_].side_effect = true; }

}  // namespace facet
