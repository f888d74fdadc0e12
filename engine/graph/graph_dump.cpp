// Text and Graphviz views of a compiled graph, for debugging and documentation.
#include <sstream>

#include "graph/access.h"
#include <facet/graph/compiled_graph.h>

namespace facet {

namespace {

const char* layout_name(VkImageLayout l) {
    switch (l) {
        case VK_IMAGE_LAYOUT_UNDEFINED: return "UNDEFINED";
        case VK_IMAGE_LAYOUT_GENERAL: return "GENERAL";
        case VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL: return "COLOR_ATTACHMENT";
        case VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL: return "DEPTH_ATTACHMENT";
        case VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL: return "DEPTH_READ_ONLY";
        case VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL: return "SHADER_READ_ONLY";
        case VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL: return "TRANSFER_SRC";
        case VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL: return "TRANSFER_DST";
        case VK_IMAGE_LAYOUT_PRESENT_SRC_KHR: return "PRESENT_SRC";
        default: return "OTHER";
    }
}

std::string hex(uint64_t v) {
    std::ostringstream s;
    s << "0x" << std::hex << v;
    return s.str();
}

void dump_batch(std::ostringstream& s, const CompiledGraph& g, const BarrierBatch& batch) {
    for (const ImageBarrier& b : batch.images)
        s << "    barrier image '" << g.physical_images[b.physical].name << "' mips " << b.range.baseMipLevel << "+"
          << b.range.levelCount << " layers " << b.range.baseArrayLayer << "+" << b.range.layerCount << ": "
          << layout_name(b.old_layout) << " -> " << layout_name(b.new_layout) << ", stages "
          << hex(b.src_stages) << " -> " << hex(b.dst_stages) << ", access " << hex(b.src_access) << " -> "
          << hex(b.dst_access) << "\n";
    for (const BufferBarrier& b : batch.buffers)
        s << "    barrier buffer '" << g.physical_buffers[b.physical].name << "': stages " << hex(b.src_stages)
          << " -> " << hex(b.dst_stages) << ", access " << hex(b.src_access) << " -> " << hex(b.dst_access) << "\n";
}

std::string dot_id(const std::string& text) {
    std::string out = "\"";
    for (char c : text) out += (c == '"' || c == '\\') ? std::string("\\") + c : std::string(1, c);
    return out + "\"";
}

}  // namespace

std::string CompiledGraph::to_text() const {
    std::ostringstream s;
    const auto& passes_decl = graph->passes();
    const auto& resources = graph->resources();
    s << "render graph: " << passes.size() << " passes, " << culled.size() << " culled\n";
    for (uint32_t i = 0; i < passes.size(); ++i) {
        const PassNode& p = passes_decl[passes[i].pass];
        dump_batch(s, *this, passes[i].barriers_before);
        s << i << ": pass '" << p.name << "'\n";
        for (const ResourceUse& u : p.uses) {
            const ResourceNode& r = resources[u.resource];
            s << "    " << (is_write(u.access) ? "writes '" : "reads '") << r.name << "' v" << u.version;
            if (is_write(u.access)) s << " -> v" << (u.version + 1);
            s << " (" << access_name(u.access);
            if (u.is_image)
                s << ", mips " << u.range.base_mip << "+" << u.range.mip_count << ", layers " << u.range.base_layer
                  << "+" << u.range.layer_count;
            s << ")\n";
        }
    }
    if (!final_barriers.empty()) {
        s << "final:\n";
        dump_batch(s, *this, final_barriers);
    }
    for (uint32_t c : culled) s << "culled: '" << passes_decl[c].name << "'\n";
    for (uint32_t r = 0; r < resources.size(); ++r) {
        const Lifetime& l = lifetimes[r];
        s << "resource '" << resources[r].name << "'" << (resources[r].imported ? " (imported)" : "")
          << (resources[r].exported ? " (exported)" : "");
        if (!l.used()) {
            s << ": unused\n";
            continue;
        }
        s << ": passes " << l.first << ".." << l.last << ", physical "
          << (resources[r].is_image ? "image " : "buffer ") << physical_of[r] << "\n";
    }
    return s.str();
}

std::string CompiledGraph::to_dot() const {
    std::ostringstream s;
    const auto& passes_decl = graph->passes();
    const auto& resources = graph->resources();
    s << "digraph render_graph {\n  rankdir=LR;\n  node [fontname=\"sans\"];\n";
    std::vector<bool> alive(passes_decl.size(), false);
    for (const CompiledPass& cp : passes) alive[cp.pass] = true;
    for (uint32_t p = 0; p < passes_decl.size(); ++p)
        s << "  " << dot_id("pass:" + passes_decl[p].name) << " [shape=box, label=" << dot_id(passes_decl[p].name)
          << (alive[p] ? ", style=filled, fillcolor=\"#cfe3ff\"" : ", style=dashed") << "];\n";
    for (uint32_t p = 0; p < passes_decl.size(); ++p) {
        for (const ResourceUse& u : passes_decl[p].uses) {
            const ResourceNode& r = resources[u.resource];
            const std::string in = r.name + " v" + std::to_string(u.version);
            s << "  " << dot_id("res:" + in) << " [shape=ellipse, label=" << dot_id(in) << "];\n";
            s << "  " << dot_id("res:" + in) << " -> " << dot_id("pass:" + passes_decl[p].name) << ";\n";
            if (is_write(u.access)) {
                const std::string outv = r.name + " v" + std::to_string(u.version + 1);
                s << "  " << dot_id("res:" + outv) << " [shape=ellipse, label=" << dot_id(outv) << "];\n";
                s << "  " << dot_id("pass:" + passes_decl[p].name) << " -> " << dot_id("res:" + outv) << ";\n";
            }
        }
    }
    s << "}\n";
    return s.str();
}

}  // namespace facet
