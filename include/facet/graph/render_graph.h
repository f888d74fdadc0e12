#pragma once
// A render graph in the FrameGraph style: each pass declares in a setup step what it
// reads and writes, and records its commands in a separate execute step. compile()
// (graph/compiled_graph.h) is a pure step: it culls, orders, derives barriers and
// lifetimes; run_graph() (graph/graph_run.h) records and submits.
#include <functional>
#include <string>
#include <vector>

#include <facet/graph/types.h>

namespace facet {

class PassContext;
class PassBuilder;
struct CompiledGraph;

struct ResourceUse {
    bool is_image = true;
    uint32_t resource = 0;
    uint32_t version = 0;  // the version read, or the version written over
    Access access = Access::sampled;
    ImageRange range;       // images only
};

struct PassNode {
    std::string name;
    PassKind kind = PassKind::compute;
    std::vector<ResourceUse> uses;
    std::function<void(PassContext&)> execute;
    bool side_effect = false;
};

struct ResourceNode {
    std::string name;
    bool is_image = true;
    ImageDesc image_desc;    // images
    BufferDesc buffer_desc;  // buffers
    bool imported = false;
    ImportedImage imported_image;
    ImportedBuffer imported_buffer;
    bool exported = false;
    ResourceState export_state;  // final state of an exported transient (layout UNDEFINED: as it ends)
    // producers[v] is the pass that wrote version v (v >= 1); version 0 is the initial
    // content: the host's for imported resources, nothing for transients.
    std::vector<uint32_t> producers{invalid_index};
    uint32_t version() const { return static_cast<uint32_t>(producers.size() - 1); }
};

class RenderGraph {
public:
    using Setup = std::function<void(PassBuilder&)>;
    using Execute = std::function<void(PassContext&)>;

    ImageHandle create_image(std::string name, const ImageDesc& desc);
    BufferHandle create_buffer(std::string name, const BufferDesc& desc);
    ImageHandle import_image(std::string name, const ImportedImage& image);
    BufferHandle import_buffer(std::string name, const ImportedBuffer& buffer);

    // Keeps a transient resource alive after the run (so its producers are not culled);
    // `final` names the state it must be left in (e.g. for a readback).
    void export_image(ImageHandle image, ResourceState final = {});
    void export_buffer(BufferHandle buffer, ResourceState final = {});

    uint32_t add_pass(std::string name, PassKind kind, const Setup& setup, Execute execute);
    uint32_t add_compute_pass(std::string name, const Setup& setup, Execute execute) {
        return add_pass(std::move(name), PassKind::compute, setup, std::move(execute));
    }
    uint32_t add_graphics_pass(std::string name, const Setup& setup, Execute execute) {
        return add_pass(std::move(name), PassKind::graphics, setup, std::move(execute));
    }
    uint32_t add_transfer_pass(std::string name, const Setup& setup, Execute execute) {
        return add_pass(std::move(name), PassKind::transfer, setup, std::move(execute));
    }

    // Orders pass `after` behind pass `before` (for dependencies the resources do not show).
    void add_dependency(uint32_t before, uint32_t after);

    const std::vector<PassNode>& passes() const { return passes_; }
    const std::vector<ResourceNode>& resources() const { return resources_; }
    const std::vector<std::pair<uint32_t, uint32_t>>& dependencies() const { return dependencies_; }
    const ResourceNode& resource(ImageHandle h) const { return resources_.at(h.index); }
    const ResourceNode& resource(BufferHandle h) const { return resources_.at(h.index); }

    CompiledGraph compile() const;

private:
    friend class PassBuilder;
    std::vector<PassNode> passes_;
    std::vector<ResourceNode> resources_;
    std::vector<std::pair<uint32_t, uint32_t>> dependencies_;
};

// The setup step's view of one pass: verbs at the point of use. Reads return the same
// handle; writes return the resource's next version, which later passes must use.
class PassBuilder {
public:
    ImageHandle sample(ImageHandle image, ImageRange range = {}) { return read(image, Access::sampled, range); }
    ImageHandle read_storage(ImageHandle image, ImageRange range = {}) {
        return read(image, Access::storage_read, range);
    }
    ImageHandle write_storage(ImageHandle image, ImageRange range = {}) {
        return write(image, Access::storage_write, range);
    }
    ImageHandle read_write_storage(ImageHandle image, ImageRange range = {}) {
        return write(image, Access::storage_read_write, range);
    }
    ImageHandle color_attachment(ImageHandle image, ImageRange range = ImageRange::mip(0)) {
        return write(image, Access::color_attachment, range);
    }
    ImageHandle depth_attachment(ImageHandle image) { return write(image, Access::depth_attachment, ImageRange::mip(0)); }
    ImageHandle copy_from(ImageHandle image, ImageRange range = {}) { return read(image, Access::transfer_src, range); }
    ImageHandle copy_to(ImageHandle image, ImageRange range = {}) { return write(image, Access::transfer_dst, range); }

    BufferHandle read(BufferHandle buffer, Access access = Access::storage_read);
    BufferHandle write(BufferHandle buffer, Access access = Access::storage_write);

    ImageHandle read(ImageHandle image, Access access, ImageRange range = {});
    ImageHandle write(ImageHandle image, Access access, ImageRange range = {});

    // The pass has effects outside the graph's resources: never culled.
    void side_effect();

private:
    friend class RenderGraph;
    PassBuilder(RenderGraph& graph, uint32_t pass) : graph_(graph), pass_(pass) {}
    uint32_t use(bool is_image, uint32_t index, uint32_t version, Access access, ImageRange range);
    RenderGraph& graph_;
    uint32_t pass_;
};

}  // namespace facet
