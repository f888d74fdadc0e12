#include "graph/barrier_builder.h"

#include <optional>

#include "graph/access.h"

namespace facet {

namespace {

constexpr VkAccessFlags2 write_access_mask =
    VK_ACCESS_2_SHADER_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT |
    VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_HOST_WRITE_BIT |
    VK_ACCESS_2_MEMORY_WRITE_BIT;

// Synchronisation state of one image subresource or one buffer.
struct State {
    VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkPipelineStageFlags2 write_stages = 0;    // the last write (or layout transition)
    VkAccessFlags2 pending_writes = 0;         // its accesses not yet made available
    VkPipelineStageFlags2 visible_stages = 0;  // where the last write is already visible
    VkAccessFlags2 visible_access = 0;
    VkPipelineStageFlags2 read_stages = 0;     // reads since the last write (write-after-read)
};

struct Params {
    VkPipelineStageFlags2 src_stages, dst_stages;
    VkAccessFlags2 src_access, dst_access;
    VkImageLayout old_layout, new_layout;
    bool operator==(const Params&) const = default;
};

State initial_state(const ResourceState& s) {
    State st;
    st.layout = s.layout;
    st.write_stages = s.stages;
    st.pending_writes = s.access & write_access_mask;
    st.read_stages = s.stages;
    return st;
}

// The barrier (if any) that must precede an access, and the state after it.
std::optional<Params> transition(State& s, const AccessInfo& a, bool is_image) {
    const bool layout_change = is_image && s.layout != a.layout;
    if (!a.writes && !layout_change) {
        const bool visible = (a.stages & ~s.visible_stages) == 0 && (a.access & ~s.visible_access) == 0;
        s.read_stages |= a.stages;
        if (s.write_stages == 0 || visible) return std::nullopt;
        Params p{s.write_stages, a.stages, s.pending_writes, a.access, s.layout, s.layout};
        s.pending_writes = 0;
        s.visible_stages |= a.stages;
        s.visible_access |= a.access;
        return p;
    }
    const VkPipelineStageFlags2 src = s.write_stages | s.read_stages;
    std::optional<Params> p;
    if (layout_change || src != 0)
        p = Params{src, a.stages, s.pending_writes, a.access, s.layout, is_image ? a.layout : VK_IMAGE_LAYOUT_UNDEFINED};
    if (is_image) s.layout = a.layout;
    if (a.writes) {
        s.write_stages = a.stages;
        s.pending_writes = a.access & write_access_mask;
        s.visible_stages = 0;
        s.visible_access = 0;
        s.read_stages = 0;
    } else {
        // A layout transition is a write that the barrier made visible to this read.
        s.write_stages = a.stages;
        s.pending_writes = 0;
        s.visible_stages = a.stages;
        s.visible_access = a.access;
        s.read_stages = a.stages;
    }
    return p;
}

struct ImageStates {
    ImageDesc desc;
    std::vector<State> sub;  // [mip * layers + layer]
    State& at(uint32_t mip, uint32_t layer) { return sub[mip * desc.array_layers + layer]; }
};

// Appends a barrier, merging it into the previous one when it continues that range.
void push_image_barrier(std::vector<ImageBarrier>& list, uint32_t physical, VkImageAspectFlags aspect,
                        uint32_t mip, uint32_t layer, const Params& p) {
    if (!list.empty()) {
        ImageBarrier& last = list.back();
        const Params lp{last.src_stages, last.dst_stages, last.src_access, last.dst_access, last.old_layout,
                        last.new_layout};
        if (last.physical == physical && lp == p) {
            const VkImageSubresourceRange& r = last.range;
            // Next layer of the same single mip.
            if (r.levelCount == 1 && r.baseMipLevel == mip && r.baseArrayLayer + r.layerCount == layer) {
                ++last.range.layerCount;
                return;
            }
        }
    }
    ImageBarrier b;
    b.physical = physical;
    b.range = {aspect, mip, 1, layer, 1};
    b.src_stages = p.src_stages;
    b.dst_stages = p.dst_stages;
    b.src_access = p.src_access;
    b.dst_access = p.dst_access;
    b.old_layout = p.old_layout;
    b.new_layout = p.new_layout;
    list.push_back(b);
}

// Joins barriers of consecutive mips that cover the same layers with the same parameters.
void merge_mips(std::vector<ImageBarrier>& list) {
    std::vector<ImageBarrier> merged;
    for (const ImageBarrier& b : list) {
        if (!merged.empty()) {
            ImageBarrier& m = merged.back();
            if (m.physical == b.physical && m.src_stages == b.src_stages && m.dst_stages == b.dst_stages &&
                m.src_access == b.src_access && m.dst_access == b.dst_access && m.old_layout == b.old_layout &&
                m.new_layout == b.new_layout && m.range.baseArrayLayer == b.range.baseArrayLayer &&
                m.range.layerCount == b.range.layerCount &&
                m.range.baseMipLevel + m.range.levelCount == b.range.baseMipLevel) {
                m.range.levelCount += b.range.levelCount;
                continue;
            }
        }
        merged.push_back(b);
    }
    list = std::move(merged);
}

std::optional<Params> to_final(State& s, const ResourceState& target, bool is_image) {
    const VkImageLayout layout = target.layout == VK_IMAGE_LAYOUT_UNDEFINED ? s.layout : target.layout;
    const bool layout_change = is_image && layout != s.layout;
    if (!layout_change && target.stages == 0) return std::nullopt;
    Params p{s.write_stages | s.read_stages, target.stages, s.pending_writes, target.access, s.layout,
             is_image ? layout : VK_IMAGE_LAYOUT_UNDEFINED};
    s.layout = layout;
    return p;
}

}  // namespace

void build_barriers(const RenderGraph& graph, CompiledGraph& out) {
    const auto& resources = graph.resources();
    std::vector<ImageStates> images(out.physical_images.size());
    for (uint32_t p = 0; p < images.size(); ++p) {
        const PhysicalResource& phys = out.physical_images[p];
        images[p].desc = phys.image_desc;
        State init = phys.imported ? initial_state(resources[phys.imported_resource].imported_image.initial) : State{};
        images[p].sub.assign(size_t(phys.image_desc.mip_levels) * phys.image_desc.array_layers, init);
    }
    std::vector<State> buffers(out.physical_buffers.size());
    for (uint32_t p = 0; p < buffers.size(); ++p) {
        const PhysicalResource& phys = out.physical_buffers[p];
        if (phys.imported) buffers[p] = initial_state(resources[phys.imported_resource].imported_buffer.initial);
    }

    for (uint32_t i = 0; i < out.passes.size(); ++i) {
        const PassNode& pass = graph.passes()[out.passes[i].pass];
        BarrierBatch& batch = out.passes[i].barriers_before;
        std::vector<bool> started(resources.size(), false);
        for (const ResourceUse& u : pass.uses) {
            const uint32_t phys = out.physical_of[u.resource];
            const AccessInfo a = access_info(pass.kind, u.access, u.is_image);
            // First use of a transient on its (possibly shared) physical resource: the old
            // contents are not needed, so every subresource starts from UNDEFINED.
            const bool fresh = !resources[u.resource].imported && out.lifetimes[u.resource].first == i &&
                               !started[u.resource];
            started[u.resource] = true;
            if (!u.is_image) {
                if (auto p = transition(buffers[phys], a, false))
                    batch.buffers.push_back({phys, p->src_stages, p->dst_stages, p->src_access, p->dst_access});
                continue;
            }
            ImageStates& img = images[phys];
            if (fresh)
                for (State& s : img.sub) s.layout = VK_IMAGE_LAYOUT_UNDEFINED;
            const VkImageAspectFlags aspect = aspect_of(img.desc.format);
            const size_t first_new = batch.images.size();
            for (uint32_t m = u.range.base_mip; m < u.range.base_mip + u.range.mip_count; ++m)
                for (uint32_t l = u.range.base_layer; l < u.range.base_layer + u.range.layer_count; ++l)
                    if (auto p = transition(img.at(m, l), a, true))
                        push_image_barrier(batch.images, phys, aspect, m, l, *p);
            std::vector<ImageBarrier> added(batch.images.begin() + first_new, batch.images.end());
            merge_mips(added);
            batch.images.resize(first_new);
            batch.images.insert(batch.images.end(), added.begin(), added.end());
        }
    }

    // Imported resources leave in the state the host asked for; exported ones likewise.
    for (uint32_t r = 0; r < resources.size(); ++r) {
        const ResourceNode& node = resources[r];
        const uint32_t phys = out.physical_of[r];
        if (phys == invalid_index || !(node.imported || node.exported)) continue;
        const ResourceState& target = node.imported ? (node.is_image ? node.imported_image.final
                                                                     : node.imported_buffer.final)
                                                    : node.export_state;
        if (!node.is_image) {
            if (auto p = to_final(buffers[phys], target, false))
                out.final_barriers.buffers.push_back({phys, p->src_stages, p->dst_stages, p->src_access, p->dst_access});
            continue;
        }
        ImageStates& img = images[phys];
        std::vector<ImageBarrier> added;
        for (uint32_t m = 0; m < img.desc.mip_levels; ++m)
            for (uint32_t l = 0; l < img.desc.array_layers; ++l)
                if (auto p = to_final(img.at(m, l), target, true))
                    push_image_barrier(added, phys, aspect_of(img.desc.format), m, l, *p);
        merge_mips(added);
        out.final_barriers.images.insert(out.final_barriers.images.end(), added.begin(), added.end());
    }
}

}  // namespace facet
