#include <facet/gpu/memory.h>

#include <algorithm>
#include <cstdint>
#include <optional>
#include <string>

#include <facet/core/result.h>
#include "core/guarded.h"
#include "core/huge_pages.h"
#include "gpu/fault_injection.h"

namespace facet {

namespace {

// On a CPU device (lavapipe) device memory is ordinary process memory, and a pass that
// writes an image for the first time pays a page fault per 4 KiB: about 20 ms of the
// 22 ms an 8 MiB upload took, which huge pages save (core/huge_pages.h).

// Allocations made and images bound by this thread, in every allocator (made_on_this_thread).
thread_local AllocationCounts this_thread_counts;
// Injected per resource rather than at vkAllocateMemory, so that every resource's
// allocation can be made to fail, not only those that open a new block.
void fail_if_injected(VkDeviceSize size) {
    if (VkResult r = take_injected_fault(FaultSite::memory))
        throw VulkanError(r, "vkAllocateMemory (" + std::to_string(size) + " bytes)");
}

VkDeviceSize align_up(VkDeviceSize value, VkDeviceSize alignment) {
    return (value + alignment - 1) / alignment * alignment;
}
}  // namespace

Allocator::Allocator(VkPhysicalDevice physical_device, VkDevice device) : device_(device) {
    vkGetPhysicalDeviceMemoryProperties(physical_device, &properties_);
    VkPhysicalDeviceProperties properties;
    vkGetPhysicalDeviceProperties(physical_device, &properties);
    non_coherent_atom_ = std::max<VkDeviceSize>(1, properties.limits.nonCoherentAtomSize);
    // Buffers and optimal-tiling images may share a block: keep every sub-allocation
    // aligned to the granularity so neighbours never alias a page (Vulkan spec 12.7).
    granularity_ = std::max<VkDeviceSize>(1, properties.limits.bufferImageGranularity);
    cpu_device_ = properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
}

Allocator::~Allocator() {
    for (Block& block : blocks_)
        if (block.memory) vkFreeMemory(device_, block.memory, nullptr);
}

uint32_t Allocator::find_memory_type(uint32_t type_bits, MemoryUsage usage) const {
    VkMemoryPropertyFlags required = 0, preferred = 0;
    switch (usage) {
        case MemoryUsage::gpu_only:
            preferred = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
            break;
        case MemoryUsage::upload:
            required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
            break;
        case MemoryUsage::readback:
            required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT;
            preferred = VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
            break;
    }
    int best = -1;
    for (uint32_t i = 0; i < properties_.memoryTypeCount; ++i) {
        if (!(type_bits & (1u << i))) continue;
        VkMemoryPropertyFlags flags = properties_.memoryTypes[i].propertyFlags;
        if ((flags & required) != required) continue;
        if ((flags & preferred) == preferred) return i;
        if (best < 0) best = static_cast<int>(i);
    }
    if (best < 0)
        throw VulkanError(VK_ERROR_OUT_OF_DEVICE_MEMORY,
                          "no memory type fits type bits " + std::to_string(type_bits));
    return static_cast<uint32_t>(best);
}

Allocation Allocator::allocate_dedicated(VkDeviceSize size, uint32_t type, VkBuffer buffer,
                                         VkImage image) {
    VkMemoryDedicatedAllocateInfo dedicated{VK_STRUCTURE_TYPE_MEMORY_DEDICATED_ALLOCATE_INFO};
    dedicated.buffer = buffer;
    dedicated.image = image;
    VkMemoryAllocateInfo info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    info.pNext = (buffer || image) ? &dedicated : nullptr;
    info.allocationSize = size;
    info.memoryTypeIndex = type;
    Allocation a;
    vk_check(vkAllocateMemory(device_, &info, nullptr, &a.memory), "vkAllocateMemory (dedicated)");
    a.size = size;
    a.memory_type = type;
    a.block = -1;
    VkMemoryPropertyFlags flags = properties_.memoryTypes[type].propertyFlags;
    a.coherent = flags & VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    if (flags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) {
        VkResult r = vkMapMemory(device_, a.memory, 0, VK_WHOLE_SIZE, 0, &a.mapped);
        if (r != VK_SUCCESS) {
            vkFreeMemory(device_, a.memory, nullptr);
            throw VulkanError(r, "vkMapMemory");
        }
    }
    if (cpu_device_) advise_huge_pages(a.mapped, size);
    ++dedicated_count_;
    ++allocations_made_;
    ++this_thread_counts.allocations_made;
    ++live_;
    dedicated_bytes_ += size;
    in_use_ += size;
    return a;
}

Result<Allocation> Allocator::allocate(const VkMemoryRequirements& requirements, MemoryUsage usage,
                                       bool dedicated) {
    return guarded([&]() -> Result<Allocation> { return allocate_or_throw(requirements, usage, dedicated); });
}

Result<Allocation> Allocator::allocate_for(VkBuffer buffer, MemoryUsage usage) {
    return guarded([&]() -> Result<Allocation> { return bind_or_throw(buffer, usage); });
}

Result<Allocation> Allocator::allocate_for(VkImage image, MemoryUsage usage) {
    return guarded([&]() -> Result<Allocation> { return bind_or_throw(image, usage); });
}

Allocation Allocator::allocate_or_throw(const VkMemoryRequirements& requirements, MemoryUsage usage,
                                        bool dedicated) {
    fail_if_injected(requirements.size);
    std::lock_guard lock(mutex_);
    const uint32_t type = find_memory_type(requirements.memoryTypeBits, usage);
    if (dedicated || requirements.size > dedicated_threshold)
        return allocate_dedicated(requirements.size, type, VK_NULL_HANDLE, VK_NULL_HANDLE);

    const VkDeviceSize alignment = std::max(requirements.alignment, granularity_);
    const VkDeviceSize size = align_up(requirements.size, granularity_);
    auto try_block = [&](int index) -> std::optional<Allocation> {
        Block& block = blocks_[index];
        for (size_t r = 0; r < block.free_ranges.size(); ++r) {
            Range range = block.free_ranges[r];
            VkDeviceSize start = align_up(range.offset, alignment);
            if (start + size > range.offset + range.size) continue;
            // Split the free range into what stays before and after the allocation.
            std::vector<Range> pieces;
            if (start > range.offset) pieces.push_back({range.offset, start - range.offset});
            VkDeviceSize end = start + size;
            if (end < range.offset + range.size) pieces.push_back({end, range.offset + range.size - end});
            block.free_ranges.erase(block.free_ranges.begin() + r);
            block.free_ranges.insert(block.free_ranges.begin() + r, pieces.begin(), pieces.end());
            ++block.live;
            ++allocations_made_;
            ++this_thread_counts.allocations_made;
            ++live_;
            in_use_ += size;
            Allocation a;
            a.memory = block.memory;
            a.offset = start;
            a.size = size;
            a.memory_type = type;
            a.block = index;
            a.mapped = block.mapped ? static_cast<char*>(block.mapped) + start : nullptr;
            a.coherent = properties_.memoryTypes[type].propertyFlags & VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
            return a;
        }
        return std::nullopt;
    };
    for (size_t i = 0; i < blocks_.size(); ++i)
        if (blocks_[i].memory && blocks_[i].memory_type == type)
            if (auto a = try_block(static_cast<int>(i))) return *a;

    Block block;
    block.memory_type = type;
    VkMemoryAllocateInfo info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    info.allocationSize = block_size;
    info.memoryTypeIndex = type;
    vk_check(vkAllocateMemory(device_, &info, nullptr, &block.memory), "vkAllocateMemory (block)");
    if (properties_.memoryTypes[type].propertyFlags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) {
        VkResult r = vkMapMemory(device_, block.memory, 0, VK_WHOLE_SIZE, 0, &block.mapped);
        if (r != VK_SUCCESS) {
            vkFreeMemory(device_, block.memory, nullptr);
            throw VulkanError(r, "vkMapMemory");
        }
    }
    if (cpu_device_) advise_huge_pages(block.mapped, block_size);
    block.free_ranges.push_back({0, block_size});
    // Reuse a slot of a freed block so block indices held by live allocations stay valid.
    auto empty = std::find_if(blocks_.begin(), blocks_.end(), [](const Block& b) { return !b.memory; });
    int index;
    if (empty != blocks_.end()) {
        index = static_cast<int>(empty - blocks_.begin());
        *empty = std::move(block);
    } else {
        index = static_cast<int>(blocks_.size());
        blocks_.push_back(std::move(block));
    }
    return *try_block(index);
}

Allocation Allocator::bind_or_throw(VkBuffer buffer, MemoryUsage usage) {
    VkBufferMemoryRequirementsInfo2 info{VK_STRUCTURE_TYPE_BUFFER_MEMORY_REQUIREMENTS_INFO_2};
    info.buffer = buffer;
    VkMemoryDedicatedRequirements dedicated{VK_STRUCTURE_TYPE_MEMORY_DEDICATED_REQUIREMENTS};
    VkMemoryRequirements2 requirements{VK_STRUCTURE_TYPE_MEMORY_REQUIREMENTS_2};
    requirements.pNext = &dedicated;
    vkGetBufferMemoryRequirements2(device_, &info, &requirements);
    Allocation a;
    const VkMemoryRequirements& r = requirements.memoryRequirements;
    if (dedicated.requiresDedicatedAllocation || dedicated.prefersDedicatedAllocation ||
        r.size > dedicated_threshold) {
        fail_if_injected(r.size);
        std::lock_guard lock(mutex_);
        a = allocate_dedicated(r.size, find_memory_type(r.memoryTypeBits, usage), buffer, VK_NULL_HANDLE);
    } else {
        a = allocate_or_throw(r, usage, false);
    }
    if (VkResult res = vkBindBufferMemory(device_, buffer, a.memory, a.offset); res != VK_SUCCESS) {
        free(a);
        throw VulkanError(res, "vkBindBufferMemory");
    }
    return a;
}

Allocation Allocator::bind_or_throw(VkImage image, MemoryUsage usage) {
    VkImageMemoryRequirementsInfo2 info{VK_STRUCTURE_TYPE_IMAGE_MEMORY_REQUIREMENTS_INFO_2};
    info.image = image;
    VkMemoryDedicatedRequirements dedicated{VK_STRUCTURE_TYPE_MEMORY_DEDICATED_REQUIREMENTS};
    VkMemoryRequirements2 requirements{VK_STRUCTURE_TYPE_MEMORY_REQUIREMENTS_2};
    requirements.pNext = &dedicated;
    vkGetImageMemoryRequirements2(device_, &info, &requirements);
    Allocation a;
    const VkMemoryRequirements& r = requirements.memoryRequirements;
    if (dedicated.requiresDedicatedAllocation || dedicated.prefersDedicatedAllocation ||
        r.size > dedicated_threshold) {
        fail_if_injected(r.size);
        std::lock_guard lock(mutex_);
        a = allocate_dedicated(r.size, find_memory_type(r.memoryTypeBits, usage), VK_NULL_HANDLE, image);
    } else {
        a = allocate_or_throw(r, usage, false);
    }
    if (VkResult res = vkBindImageMemory(device_, image, a.memory, a.offset); res != VK_SUCCESS) {
        free(a);
        throw VulkanError(res, "vkBindImageMemory");
    }
    std::lock_guard lock(mutex_);
    ++images_bound_;
    ++this_thread_counts.images_bound;
    return a;
}

void Allocator::free(Allocation& a) {
    if (!a.memory) return;
    std::lock_guard lock(mutex_);
    --live_;
    in_use_ -= a.size;
    if (a.block < 0) {
        vkFreeMemory(device_, a.memory, nullptr);
        --dedicated_count_;
        dedicated_bytes_ -= a.size;
        a = Allocation{};
        return;
    }
    Block& block = blocks_[a.block];
    auto& ranges = block.free_ranges;
    auto it = std::lower_bound(ranges.begin(), ranges.end(), a.offset,
                               [](const Range& r, VkDeviceSize offset) { return r.offset < offset; });
    it = ranges.insert(it, Range{a.offset, a.size});
    // Coalesce with the next and the previous free range.
    if (it + 1 != ranges.end() && it->offset + it->size == (it + 1)->offset) {
        it->size += (it + 1)->size;
        ranges.erase(it + 1);
    }
    if (it != ranges.begin() && (it - 1)->offset + (it - 1)->size == it->offset) {
        (it - 1)->size += it->size;
        ranges.erase(it);
    }
    // An empty block goes back to the driver, so repeated work keeps memory flat.
    if (--block.live == 0) {
        vkFreeMemory(device_, block.memory, nullptr);
        block = Block{};
    }
    a = Allocation{};
}

Status Allocator::flush(const Allocation& a) {
    if (!a.memory || a.coherent) return Ok{};
    VkMappedMemoryRange range{VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE};
    range.memory = a.memory;
    range.offset = a.offset / non_coherent_atom_ * non_coherent_atom_;
    range.size = VK_WHOLE_SIZE;
    if (VkResult r = vkFlushMappedMemoryRanges(device_, 1, &range); r != VK_SUCCESS)
        return Error{VulkanError(r, "vkFlushMappedMemoryRanges").what(), r};
    return Ok{};
}

Status Allocator::invalidate(const Allocation& a) {
    if (!a.memory || a.coherent) return Ok{};
    VkMappedMemoryRange range{VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE};
    range.memory = a.memory;
    range.offset = a.offset / non_coherent_atom_ * non_coherent_atom_;
    range.size = VK_WHOLE_SIZE;
    if (VkResult r = vkInvalidateMappedMemoryRanges(device_, 1, &range); r != VK_SUCCESS)
        return Error{VulkanError(r, "vkInvalidateMappedMemoryRanges").what(), r};
    return Ok{};
}

AllocationCounts Allocator::made_on_this_thread() { return this_thread_counts; }

AllocatorStats Allocator::stats() const {
    std::lock_guard lock(mutex_);
    AllocatorStats s;
    for (const Block& b : blocks_)
        if (b.memory) {
            ++s.block_count;
            s.bytes_reserved += block_size;
        }
    s.dedicated_count = dedicated_count_;
    s.live_allocations = live_;
    s.bytes_reserved += dedicated_bytes_;
    s.bytes_in_use = in_use_;
    s.allocations_made = allocations_made_;
    s.images_bound = images_bound_;
    return s;
}

}  // namespace facet
