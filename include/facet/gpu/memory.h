#pragma once
// A small device-memory allocator (no allocator library is packaged in Debian):
// blocks sub-allocated first-fit per memory type, dedicated allocations for large
// resources and where the driver asks for them.
//
// Errors: allocation returns an Error (VK_ERROR_OUT_OF_DEVICE_MEMORY and the like,
// naming the call and the size); so do flush and invalidate. Nothing here throws.
// Thread safety: every member may be called from several threads at once.
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

#include <vulkan/vulkan.h>

#include <facet/core/result.h>

namespace facet {

enum class MemoryUsage {
    gpu_only,  // device local
    upload,    // host visible + coherent, mapped
    readback,  // host visible, cached if possible, mapped
};

struct Allocation {
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkDeviceSize offset = 0;
    VkDeviceSize size = 0;
    void* mapped = nullptr;  // host pointer at `offset` for upload/readback memory
    uint32_t memory_type = 0;
    int32_t block = -1;  // index of the block it came from; -1: dedicated
    bool coherent = true;
};

struct AllocatorStats {
    uint32_t block_count = 0;
    uint32_t dedicated_count = 0;
    uint32_t live_allocations = 0;
    VkDeviceSize bytes_reserved = 0;  // device memory held (blocks + dedicated)
    VkDeviceSize bytes_in_use = 0;
    // Running totals since the allocator was made (for "a steady frame allocates nothing").
    uint64_t allocations_made = 0;  // every allocation, sub-allocated or dedicated
    uint64_t images_bound = 0;      // images given memory (one per VkImage Facet creates)
};

// Running totals of one thread (Allocator::made_on_this_thread).
struct AllocationCounts {
    uint64_t allocations_made = 0;
    uint64_t images_bound = 0;
};

class Allocator {
public:
    static constexpr VkDeviceSize block_size = 64ull << 20;
    static constexpr VkDeviceSize dedicated_threshold = 16ull << 20;

    Allocator(VkPhysicalDevice physical_device, VkDevice device);
    ~Allocator();
    Allocator(const Allocator&) = delete;
    Allocator& operator=(const Allocator&) = delete;

    // An Error (VK_ERROR_OUT_OF_DEVICE_MEMORY, ...) names the call and the size.
    Result<Allocation> allocate(const VkMemoryRequirements& requirements, MemoryUsage usage,
                                bool dedicated = false);
    Result<Allocation> allocate_for(VkBuffer buffer, MemoryUsage usage);  // allocates and binds
    Result<Allocation> allocate_for(VkImage image, MemoryUsage usage);    // allocates and binds
    void free(Allocation& allocation);

    // Makes host writes visible / device writes visible to the host for non-coherent
    // memory (nothing to do, and always Ok, for coherent memory).
    Status flush(const Allocation& allocation);
    Status invalidate(const Allocation& allocation);

    AllocatorStats stats() const;
    // What the calling thread allocated, in every allocator of the process: a render
    // thread checks that its steady frames allocate nothing while another thread loads
    // and bakes on the same device (the viewer).
    static AllocationCounts made_on_this_thread();

private:
    struct Range {
        VkDeviceSize offset, size;
    };
    struct Block {
        VkDeviceMemory memory = VK_NULL_HANDLE;
        uint32_t memory_type = 0;
        void* mapped = nullptr;
        std::vector<Range> free_ranges;  // sorted by offset, coalesced
        uint32_t live = 0;
    };

    // The throwing implementations behind the public calls (which catch).
    Allocation allocate_or_throw(const VkMemoryRequirements& requirements, MemoryUsage usage, bool dedicated);
    Allocation bind_or_throw(VkBuffer buffer, MemoryUsage usage);
    Allocation bind_or_throw(VkImage image, MemoryUsage usage);
    uint32_t find_memory_type(uint32_t type_bits, MemoryUsage usage) const;
    Allocation allocate_dedicated(VkDeviceSize size, uint32_t type, VkBuffer buffer,
                                  VkImage image);

    VkDevice device_;
    VkPhysicalDeviceMemoryProperties properties_{};
    VkDeviceSize non_coherent_atom_ = 1;
    VkDeviceSize granularity_ = 1;
    bool cpu_device_ = false;  // lavapipe and the like: device memory is the process's memory
    mutable std::mutex mutex_;
    std::vector<Block> blocks_;
    uint32_t dedicated_count_ = 0;
    uint32_t live_ = 0;
    VkDeviceSize dedicated_bytes_ = 0;
    VkDeviceSize in_use_ = 0;
    uint64_t allocations_made_ = 0;
    uint64_t images_bound_ = 0;
};

}  // namespace facet
