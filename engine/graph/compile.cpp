// RenderGraph::compile(): culling, ordering, lifetimes, physical resources. Pure: no
// Vulkan calls, so every rule is unit-tested without a GPU. Barriers: barrier_builder.cpp.
#include <algorithm>
#include <functional>
#include <map>
#include <queue>
#include <set>

#include <facet/core/result.h>
#include "graph/access.h"
#include "graph/barrier_builder.h"
#include <facet/graph/compiled_graph.h>

namespace facet {

namespace {

struct Edges {
    std::vector<std::set<uint32_t>> order;  // order[a] contains b: a runs before b
    std::vector<std::set<uint32_t>> needs;  // needs[b] contains a: b consumes a's output
};

Edges build_edges(const RenderGraph& graph) {
    const auto& passes = graph.passes();
    const auto& resources = graph.resources();
    Edges e{std::vector<std::set<uint32_t>>(passes.size()), std::vector<std::set<uint32_t>>(passes.size())};
    // Readers of every (resource, version), for write-after-read ordering.
    std::map<std::pair<uint32_t, uint32_t>, std::vector<uint32_t>> readers;
    for (uint32_t p = 0; p < passes.size(); ++p)
        for (const ResourceUse& u : passes[p].uses)
            if (!is_write(u.access)) readers[{u.resource, u.version}].push_back(p);

    for (uint32_t p = 0; p < passes.size(); ++p) {
        for (const ResourceUse& u : passes[p].uses) {
            const ResourceNode& r = resources[u.resource];
            const uint32_t producer = r.producers[u.version];
            if (!is_write(u.access)) {
                if (producer == p)
                    throw UsageError("render graph has a cycle: pass '" + passes[p].name + "' reads '" + r.name +
                                     "' version " + std::to_string(u.version) + ", which it writes itself");
                if (producer != invalid_index) {
                    e.order[producer].insert(p);
                    e.needs[p].insert(producer);
                }
                continue;
            }
            // A write keeps what it does not overwrite (other mips, untouched texels), so
            // it consumes the previous version: write-after-write.
            if (producer != invalid_index && producer != p) {
                e.order[producer].insert(p);
                e.needs[p].insert(producer);
            }
            auto it = readers.find({u.resource, u.version});
            if (it != readers.end())
                for (uint32_t reader : it->second)
                    if (reader != p) e.order[reader].insert(p);  // write-after-read
        }
    }
    for (auto [before, after] : graph.dependencies())
        if (before != after) e.order[before].insert(after);
        else throw UsageError("render graph has a cycle: pass '" + passes[before].name + "' depends on itself");
    return e;
}

std::vector<bool> find_needed(const RenderGraph& graph, const Edges& e) {
    const auto& passes = graph.passes();
    const auto& resources = graph.resources();
    std::vector<bool> needed(passes.size(), false);
    std::vector<uint32_t> stack;
    auto mark = [&](uint32_t p) {
        if (p != invalid_index && !needed[p]) {
            needed[p] = true;
            stack.push_back(p);
        }
    };
    for (uint32_t p = 0; p < passes.size(); ++p) {
        if (passes[p].side_effect) mark(p);
        for (const ResourceUse& u : passes[p].uses)
            if (is_write(u.access) && resources[u.resource].imported) mark(p);
    }
    for (const ResourceNode& r : resources)
        if (r.exported) mark(r.producers.back());
    while (!stack.empty()) {
        uint32_t p = stack.back();
        stack.pop_back();
        for (uint32_t producer : e.needs[p]) mark(producer);
    }
    return needed;
}

[[noreturn]] void report_cycle(const RenderGraph& graph, const Edges& e, const std::vector<uint32_t>& remaining) {
    // Walk forward inside the unordered passes until a pass repeats: that loop is a cycle.
    std::set<uint32_t> left(remaining.begin(), remaining.end());
    std::vector<uint32_t> path{remaining.front()};
    std::map<uint32_t, size_t> seen{{remaining.front(), 0}};
    while (true) {
        uint32_t next = invalid_index;
        for (uint32_t n : e.order[path.back()])
            if (left.count(n)) {
                next = n;
                break;
            }
        if (next == invalid_index) break;
        if (auto it = seen.find(next); it != seen.end()) {
            std::string names;
            for (size_t i = it->second; i < path.size(); ++i) names += "'" + graph.passes()[path[i]].name + "' -> ";
            throw UsageError("render graph has a cycle: " + names + "'" + graph.passes()[next].name + "'");
        }
        seen[next] = path.size();
        path.push_back(next);
    }
    throw UsageError("render graph has a cycle among its passes");
}

std::vector<uint32_t> order_passes(const RenderGraph& graph, const Edges& e, const std::vector<bool>& needed) {
    const uint32_t n = static_cast<uint32_t>(graph.passes().size());
    std::vector<uint32_t> in_degree(n, 0);
    for (uint32_t a = 0; a < n; ++a)
        if (needed[a])
            for (uint32_t b : e.order[a])
                if (needed[b]) ++in_degree[b];
    // Kahn's algorithm; among ready passes the earliest declared goes first, so the
    // order is the declaration order whenever the dependencies allow it.
    std::priority_queue<uint32_t, std::vector<uint32_t>, std::greater<>> ready;
    for (uint32_t p = 0; p < n; ++p)
        if (needed[p] && in_degree[p] == 0) ready.push(p);
    std::vector<uint32_t> order;
    while (!ready.empty()) {
        uint32_t p = ready.top();
        ready.pop();
        order.push_back(p);
        for (uint32_t b : e.order[p])
            if (needed[b] && --in_degree[b] == 0) ready.push(b);
    }
    std::vector<uint32_t> remaining;
    for (uint32_t p = 0; p < n; ++p)
        if (needed[p] && in_degree[p] > 0) remaining.push_back(p);
    if (!remaining.empty()) report_cycle(graph, e, remaining);
    return order;
}

VkImageUsageFlags image_usage(Access a) {
    switch (a) {
        case Access::sampled: return VK_IMAGE_USAGE_SAMPLED_BIT;
        case Access::storage_read:
        case Access::storage_write:
        case Access::storage_read_write: return VK_IMAGE_USAGE_STORAGE_BIT;
        case Access::color_attachment: return VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
        case Access::depth_attachment:
        case Access::depth_read: return VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
        case Access::transfer_src: return VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
        case Access::transfer_dst: return VK_IMAGE_USAGE_TRANSFER_DST_BIT;
        default: return 0;
    }
}

VkBufferUsageFlags buffer_usage(Access a) {
    switch (a) {
        case Access::storage_read:
        case Access::storage_write:
        case Access::storage_read_write: return VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
        case Access::uniform_read: return VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT;
        case Access::vertex_read: return VK_BUFFER_USAGE_VERTEX_BUFFER_BIT;
        case Access::index_read: return VK_BUFFER_USAGE_INDEX_BUFFER_BIT;
        case Access::transfer_src: return VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
        case Access::transfer_dst: return VK_BUFFER_USAGE_TRANSFER_DST_BIT;
        default: return 0;
    }
}

// Transient resources with equal descriptions and disjoint lifetimes share one physical
// resource (greedy, in order of first use). Exported resources keep theirs to the end.
void assign_physical(const RenderGraph& graph, CompiledGraph& out) {
    const auto& resources = graph.resources();
    out.physical_of.assign(resources.size(), invalid_index);
    std::vector<uint32_t> by_first;
    for (uint32_t r = 0; r < resources.size(); ++r)
        if (out.lifetimes[r].used()) by_first.push_back(r);
    std::stable_sort(by_first.begin(), by_first.end(),
                     [&](uint32_t a, uint32_t b) { return out.lifetimes[a].first < out.lifetimes[b].first; });
    std::vector<uint32_t> free_after_image, free_after_buffer;  // per physical: last busy position
    const uint32_t forever = invalid_index;
    for (uint32_t r : by_first) {
        const ResourceNode& node = resources[r];
        auto& physicals = node.is_image ? out.physical_images : out.physical_buffers;
        auto& free_after = node.is_image ? free_after_image : free_after_buffer;
        uint32_t chosen = invalid_index;
        if (!node.imported) {
            for (uint32_t p = 0; p < physicals.size(); ++p) {
                const PhysicalResource& phys = physicals[p];
                if (phys.imported || free_after[p] == forever || free_after[p] >= out.lifetimes[r].first) continue;
                if (node.is_image ? phys.image_desc == node.image_desc : phys.buffer_desc == node.buffer_desc) {
                    chosen = p;
                    break;
                }
            }
        }
        if (chosen == invalid_index) {
            PhysicalResource phys;
            phys.name = node.name;
            phys.imported = node.imported;
            phys.imported_resource = node.imported ? r : invalid_index;
            phys.image_desc = node.image_desc;
            phys.buffer_desc = node.buffer_desc;
            physicals.push_back(phys);
            free_after.push_back(0);
            chosen = static_cast<uint32_t>(physicals.size() - 1);
        } else {
            physicals[chosen].name += "+" + node.name;
        }
        physicals[chosen].resources.push_back(r);
        free_after[chosen] = (node.exported || node.imported) ? forever : out.lifetimes[r].last;
        out.physical_of[r] = chosen;
    }
    for (const CompiledPass& cp : out.passes)
        for (const ResourceUse& u : graph.passes()[cp.pass].uses) {
            const uint32_t p = out.physical_of[u.resource];
            if (u.is_image) out.physical_images[p].image_usage |= image_usage(u.access);
            else out.physical_buffers[p].buffer_usage |= buffer_usage(u.access);
        }
    // Exported results are read back or copied by their users, or sampled by a later
    // graph when they are left in a shader-readable layout.
    for (uint32_t r = 0; r < resources.size(); ++r) {
        if (!resources[r].exported || out.physical_of[r] == invalid_index) continue;
        if (resources[r].is_image) {
            VkImageUsageFlags& usage = out.physical_images[out.physical_of[r]].image_usage;
            usage |= VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
            if (resources[r].export_state.layout == VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL)
                usage |= VK_IMAGE_USAGE_SAMPLED_BIT;
        } else {
            out.physical_buffers[out.physical_of[r]].buffer_usage |= VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
        }
    }
}

}  // namespace

CompiledGraph RenderGraph::compile() const {
    CompiledGraph out;
    out.graph = this;
    const Edges edges = build_edges(*this);
    const std::vector<bool> needed = find_needed(*this, edges);
    for (uint32_t p = 0; p < passes_.size(); ++p)
        if (!needed[p]) out.culled.push_back(p);
    for (uint32_t p : order_passes(*this, edges, needed)) out.passes.push_back({p, {}});

    out.lifetimes.assign(resources_.size(), Lifetime{});
    for (uint32_t i = 0; i < out.passes.size(); ++i)
        for (const ResourceUse& u : passes_[out.passes[i].pass].uses) {
            Lifetime& l = out.lifetimes[u.resource];
            if (!l.used()) l.first = i;
            l.last = i;
        }
    for (uint32_t r = 0; r < resources_.size(); ++r)
        if (resources_[r].exported && out.lifetimes[r].used())
            out.lifetimes[r].last = static_cast<uint32_t>(out.passes.size() - 1);
    assign_physical(*this, out);
    build_barriers(*this, out);
    return out;
}

}  // namespace facet
