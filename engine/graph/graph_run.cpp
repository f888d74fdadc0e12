#include <facet/graph/graph_run.h>

#include <algorithm>
#include <cstring>

#include <facet/core/result.h>
#include <facet/gpu/context.h>
#include <facet/gpu/device_limits.h>
#include "core/guarded.h"

namespace facet {

namespace {

VkImageSubresourceRange to_vk(const ImageDesc& desc, ImageRange r) {
    const uint32_t mips = r.mip_count == all_remaining ? desc.mip_levels - r.base_mip : r.mip_count;
    const uint32_t layers = r.layer_count == all_remaining ? desc.array_layers - r.base_layer : r.layer_count;
    return {aspect_of(desc.format), r.base_mip, mips, r.base_layer, layers};
}

bool same_range(const VkImageSubresourceRange& a, const VkImageSubresourceRange& b) {
    return a.aspectMask == b.aspectMask && a.baseMipLevel == b.baseMipLevel && a.levelCount == b.levelCount &&
           a.baseArrayLayer == b.baseArrayLayer && a.layerCount == b.layerCount;
}

}  // namespace

// ---- PassContext ----

VkImage PassContext::image(ImageHandle image) const { return run_.image(image); }
const ImageDesc& PassContext::desc(ImageHandle image) const { return run_.image_desc(image.index); }
VkImageView PassContext::view(ImageHandle image, ImageRange range, VkImageViewType type) const {
    return run_.view(image.index, range, type);
}
VkBuffer PassContext::buffer(BufferHandle buffer) const { return run_.buffer(buffer); }
VkDeviceSize PassContext::size(BufferHandle buffer) const {
    return run_.compiled_->graph->resources().at(buffer.index).buffer_desc.size;
}

// ---- GraphRun ----

GraphRun::GraphRun(Context& context, const CompiledGraph& compiled) : context_(context), compiled_(&compiled) {
    // Kept for timings(), which a host reads after its fence, when the graph may be gone.
    for (const CompiledPass& cp : compiled_->passes) pass_names_.push_back(compiled_->graph->passes()[cp.pass].name);
}

GraphRun::GraphRun(Context& context, const CompiledGraph& compiled, GraphResourcePool& pool)
    : GraphRun(context, compiled) {
    pool_ = &pool;
}

Status GraphRun::prepare() {
    if (prepared_) return Ok{};
    Status made = guarded([&] { allocate(pool_); });
    if (!made) {
        // Nothing half made is kept: what was taken from the pool goes back to it.
        if (pool_) release_into(*pool_);
        else release_all();
        return made;
    }
    pool_ = nullptr;
    prepared_ = true;
    return Ok{};
}

void GraphRun::release_all() {
    for (auto& [key, view] : views_) vkDestroyImageView(context_.device(), view, nullptr);
    views_.clear();
    images_.clear();
    buffers_.clear();
    if (queries_) vkDestroyQueryPool(context_.device(), queries_, nullptr);
    queries_ = VK_NULL_HANDLE;
    query_count_ = 0;
}

GraphRun::~GraphRun() {
    VkDevice device = context_.device();
    for (auto& [key, view] : views_) vkDestroyImageView(device, view, nullptr);
    if (queries_) vkDestroyQueryPool(device, queries_, nullptr);
}

void GraphRun::release_into(GraphResourcePool& pool) {
    for (Image& image : images_)
        if (image) pool.images.push_back(std::move(image));
    for (Buffer& buffer : buffers_)
        if (buffer) pool.buffers.push_back(std::move(buffer));
    if (queries_) {
        if (pool.queries) vkDestroyQueryPool(context_.device(), pool.queries, nullptr);
        pool.queries = queries_;
        pool.query_count = query_count_;
        queries_ = VK_NULL_HANDLE;
        query_count_ = 0;
    }
    for (auto& [key, view] : views_) vkDestroyImageView(context_.device(), view, nullptr);
    views_.clear();
    images_.clear();
    buffers_.clear();
}

void GraphRun::allocate(GraphResourcePool* pool) {
    // Sizes no device holds fail here, by name, rather than half way through allocating.
    if (Status fits = check_graph_fits(context_, *compiled_); !fits)
        throw VulkanError(VK_ERROR_OUT_OF_DEVICE_MEMORY, "render graph: " + fits.error().message);
    images_.resize(compiled_->physical_images.size());
    for (size_t p = 0; p < images_.size(); ++p) {
        const PhysicalResource& phys = compiled_->physical_images[p];
        if (phys.imported) continue;
        if (pool) {
            auto same = std::find_if(pool->images.begin(), pool->images.end(), [&](const Image& i) {
                return i.desc() == phys.image_desc && i.usage() == phys.image_usage;
            });
            if (same != pool->images.end()) {
                images_[p] = std::move(*same);
                pool->images.erase(same);
                continue;
            }
        }
        images_[p] = or_throw(Image::create(context_, phys.image_desc, phys.image_usage, phys.name));
    }
    buffers_.resize(compiled_->physical_buffers.size());
    for (size_t p = 0; p < buffers_.size(); ++p) {
        const PhysicalResource& phys = compiled_->physical_buffers[p];
        if (phys.imported) continue;
        if (pool) {
            auto same = std::find_if(pool->buffers.begin(), pool->buffers.end(), [&](const Buffer& b) {
                return b.size() == phys.buffer_desc.size && b.usage() == phys.buffer_usage;
            });
            if (same != pool->buffers.end()) {
                buffers_[p] = std::move(*same);
                pool->buffers.erase(same);
                continue;
            }
        }
        buffers_[p] = or_throw(
            Buffer::create(context_, phys.buffer_desc.size, phys.buffer_usage, MemoryUsage::gpu_only, phys.name));
    }
    uint32_t family_count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(context_.physical_device(), &family_count, nullptr);
    std::vector<VkQueueFamilyProperties> families(family_count);
    vkGetPhysicalDeviceQueueFamilyProperties(context_.physical_device(), &family_count, families.data());
    const bool has_timestamps = families.at(context_.queue_family()).timestampValidBits > 0;
    const uint32_t needed = static_cast<uint32_t>(compiled_->passes.size() * 2);
    if (needed == 0 || !has_timestamps) return;
    if (pool && pool->queries && pool->query_count >= needed) {
        queries_ = pool->queries;
        query_count_ = pool->query_count;
        pool->queries = VK_NULL_HANDLE;
        pool->query_count = 0;
        return;
    }
    VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    info.queryType = VK_QUERY_TYPE_TIMESTAMP;
    info.queryCount = needed;
    vk_check(vkCreateQueryPool(context_.device(), &info, nullptr, &queries_), "vkCreateQueryPool");
    query_count_ = needed;
    context_.set_name(queries_, VK_OBJECT_TYPE_QUERY_POOL, "render graph timestamps");
}

VkImage GraphRun::physical_image(uint32_t p) const {
    const PhysicalResource& phys = compiled_->physical_images[p];
    if (phys.imported) return compiled_->graph->resources()[phys.imported_resource].imported_image.image;
    if (!prepared_) throw UsageError("GraphRun: image '" + phys.name + "' looked up before prepare()");
    return images_[p].handle();
}

VkBuffer GraphRun::physical_buffer(uint32_t p) const {
    const PhysicalResource& phys = compiled_->physical_buffers[p];
    if (phys.imported) return compiled_->graph->resources()[phys.imported_resource].imported_buffer.buffer;
    if (!prepared_) throw UsageError("GraphRun: buffer '" + phys.name + "' looked up before prepare()");
    return buffers_[p].handle();
}

VkImage GraphRun::image(ImageHandle image) const {
    const uint32_t p = compiled_->physical_of.at(image.index);
    if (p == invalid_index)
        throw UsageError("image '" + compiled_->graph->resources()[image.index].name + "' is not used by the graph");
    return physical_image(p);
}

VkBuffer GraphRun::buffer(BufferHandle buffer) const {
    const uint32_t p = compiled_->physical_of.at(buffer.index);
    if (p == invalid_index)
        throw UsageError("buffer '" + compiled_->graph->resources()[buffer.index].name + "' is not used by the graph");
    return physical_buffer(p);
}

Image* GraphRun::transient_image(ImageHandle image) {
    const uint32_t p = compiled_->physical_of.at(image.index);
    if (!prepared_ || p == invalid_index || compiled_->physical_images[p].imported || !images_[p]) return nullptr;
    return &images_[p];
}

Image GraphRun::detach_image(ImageHandle image) {
    Image* held = transient_image(image);
    if (!held)
        throw UsageError("detach_image: '" + compiled_->graph->resources().at(image.index).name +
                         "' is imported, unused by the graph or already detached");
    return std::move(*held);
}

Buffer* GraphRun::transient_buffer(BufferHandle buffer) {
    const uint32_t p = compiled_->physical_of.at(buffer.index);
    if (!prepared_ || p == invalid_index || compiled_->physical_buffers[p].imported) return nullptr;
    return &buffers_[p];
}

const ImageDesc& GraphRun::image_desc(uint32_t resource) const {
    return compiled_->graph->resources().at(resource).image_desc;
}

VkImageView GraphRun::view(uint32_t resource, ImageRange range, VkImageViewType type) {
    const uint32_t p = compiled_->physical_of.at(resource);
    const ImageDesc& desc = image_desc(resource);
    const VkImageSubresourceRange r = to_vk(desc, range);
    if (type == VK_IMAGE_VIEW_TYPE_MAX_ENUM) {
        if (desc.cube && r.layerCount % 6 == 0)
            type = r.layerCount == 6 ? VK_IMAGE_VIEW_TYPE_CUBE : VK_IMAGE_VIEW_TYPE_CUBE_ARRAY;
        else
            type = r.layerCount == 1 ? VK_IMAGE_VIEW_TYPE_2D : VK_IMAGE_VIEW_TYPE_2D_ARRAY;
    }
    if (!compiled_->physical_images[p].imported) {
        if (!images_[p]) throw UsageError("view of a detached image");
        return images_[p].make_view(r, type);
    }
    for (const auto& [key, v] : views_)
        if (key.physical == p && key.type == type && same_range(key.range, r)) return v;
    VkImageViewCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    info.image = physical_image(p);
    info.viewType = type;
    info.format = desc.format;
    info.subresourceRange = r;
    VkImageView view = VK_NULL_HANDLE;
    vk_check(vkCreateImageView(context_.device(), &info, nullptr, &view), "vkCreateImageView (render graph)");
    context_.set_name(view, VK_OBJECT_TYPE_IMAGE_VIEW,
                      compiled_->graph->resources()[resource].name + " mips " + std::to_string(r.baseMipLevel) + "+" +
                          std::to_string(r.levelCount) + " layers " + std::to_string(r.baseArrayLayer) + "+" +
                          std::to_string(r.layerCount));
    views_.push_back({{p, r, type}, view});
    return view;
}

void GraphRun::record_barriers(VkCommandBuffer cmd, const BarrierBatch& batch) const {
    if (batch.empty()) return;
    std::vector<VkImageMemoryBarrier2> images;
    for (const ImageBarrier& b : batch.images) {
        VkImageMemoryBarrier2 v{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
        v.srcStageMask = b.src_stages;
        v.srcAccessMask = b.src_access;
        v.dstStageMask = b.dst_stages;
        v.dstAccessMask = b.dst_access;
        v.oldLayout = b.old_layout;
        v.newLayout = b.new_layout;
        v.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        v.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        v.image = physical_image(b.physical);
        v.subresourceRange = b.range;
        images.push_back(v);
    }
    std::vector<VkBufferMemoryBarrier2> buffers;
    for (const BufferBarrier& b : batch.buffers) {
        VkBufferMemoryBarrier2 v{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2};
        v.srcStageMask = b.src_stages;
        v.srcAccessMask = b.src_access;
        v.dstStageMask = b.dst_stages;
        v.dstAccessMask = b.dst_access;
        v.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        v.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        v.buffer = physical_buffer(b.physical);
        v.size = VK_WHOLE_SIZE;
        buffers.push_back(v);
    }
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.imageMemoryBarrierCount = static_cast<uint32_t>(images.size());
    dep.pImageMemoryBarriers = images.data();
    dep.bufferMemoryBarrierCount = static_cast<uint32_t>(buffers.size());
    dep.pBufferMemoryBarriers = buffers.data();
    vkCmdPipelineBarrier2(cmd, &dep);
}

void GraphRun::record_pass(VkCommandBuffer cmd, uint32_t i) {
    const CompiledPass& cp = compiled_->passes[i];
    const PassNode& pass = compiled_->graph->passes()[cp.pass];
    if (context_.cmd_begin_label) {
        VkDebugUtilsLabelEXT label{VK_STRUCTURE_TYPE_DEBUG_UTILS_LABEL_EXT};
        label.pLabelName = pass.name.c_str();
        context_.cmd_begin_label(cmd, &label);
    }
    record_barriers(cmd, cp.barriers_before);
    if (queries_) vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, queries_, i * 2);
    if (pass.execute) {
        PassContext pc(*this, context_, cmd);
        pass.execute(pc);
    }
    if (queries_) vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, queries_, i * 2 + 1);
    if (context_.cmd_end_label) context_.cmd_end_label(cmd);
}

Status GraphRun::record(VkCommandBuffer cmd) {
    if (recorded_) throw UsageError("a GraphRun records once; compile and run the graph again");
    if (Status ready = prepare(); !ready) return ready;
    return guarded([&] { record_or_throw(cmd); });
}

void GraphRun::record_or_throw(VkCommandBuffer cmd) {
    recorded_ = true;
    if (queries_) vkCmdResetQueryPool(cmd, queries_, 0, static_cast<uint32_t>(compiled_->passes.size() * 2));
    for (uint32_t i = 0; i < compiled_->passes.size(); ++i) record_pass(cmd, i);
    record_barriers(cmd, compiled_->final_barriers);
}

Status GraphRun::submit_and_wait() {
    if (recorded_) throw UsageError("a GraphRun records once; compile and run the graph again");
    if (Status ready = prepare(); !ready) return ready;
    return context_.submit_and_wait([this](VkCommandBuffer cmd) { record_or_throw(cmd); },
                                    "a render graph");
}

Status GraphRun::submit_and_wait(const Progress& progress) {
    if (recorded_) throw UsageError("a GraphRun records once; compile and run the graph again");
    if (Status ready = prepare(); !ready) return ready;
    return guarded([&] { submit_or_throw(progress); });
}

void GraphRun::submit_or_throw(const Progress& progress) {
    recorded_ = true;
    const uint32_t total = static_cast<uint32_t>(compiled_->passes.size());
    if (queries_)
        or_throw(context_.submit_and_wait([&](VkCommandBuffer cmd) { vkCmdResetQueryPool(cmd, queries_, 0, total * 2); },
                                          "a timestamp reset"));
    for (uint32_t i = 0; i < total; ++i) {
        const std::string& name = compiled_->graph->passes()[compiled_->passes[i].pass].name;
        or_throw(context_.submit_and_wait(
            [&](VkCommandBuffer cmd) {
                record_pass(cmd, i);
                if (i + 1 == total) record_barriers(cmd, compiled_->final_barriers);
            },
            ("pass '" + name + "'").c_str()));
        if (progress) progress(i + 1, total, name);
    }
    if (total == 0)
        or_throw(context_.submit_and_wait([&](VkCommandBuffer cmd) { record_barriers(cmd, compiled_->final_barriers); },
                                          "a render graph's final barriers"));
}

std::vector<PassTiming> GraphRun::timings() const {
    std::vector<PassTiming> out;
    if (!queries_ || !recorded_) return out;
    std::vector<uint64_t> ticks(pass_names_.size() * 2);
    VkResult r = vkGetQueryPoolResults(context_.device(), queries_, 0, static_cast<uint32_t>(ticks.size()),
                                       ticks.size() * sizeof(uint64_t), ticks.data(), sizeof(uint64_t),
                                       VK_QUERY_RESULT_64_BIT);
    if (r != VK_SUCCESS) return out;
    for (uint32_t i = 0; i < pass_names_.size(); ++i) {
        const uint64_t begin = ticks[i * 2], end = ticks[i * 2 + 1];
        const double ms = end >= begin ? double(end - begin) * context_.timestamp_period_ns() * 1e-6 : 0.0;
        out.push_back({pass_names_[i], ms});
    }
    return out;
}

Result<std::unique_ptr<GraphRun>> run_graph(Context& context, const CompiledGraph& compiled) {
    auto run = std::make_unique<GraphRun>(context, compiled);
    if (Status done = run->submit_and_wait(); !done) return done.error();
    return run;
}

}  // namespace facet
