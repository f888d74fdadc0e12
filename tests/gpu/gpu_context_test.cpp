// GPU context, memory allocator and transfer helpers on lavapipe.
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <vector>

#if defined(__GLIBC__) && !defined(__SANITIZE_ADDRESS__) && !defined(__SANITIZE_THREAD__)
#include <malloc.h>
#define FACET_GLIBC_MALLOC 1  // not a sanitizer's allocator, which answers mallopt itself
#else
#define FACET_GLIBC_MALLOC 0
#endif

#include <facet/gpu/context.h>
#include <facet/gpu/memory.h>
#include <facet/gpu/resources.h>
#include <facet/gpu/transfer.h>
#include "support/gpu_test.h"

namespace facet {
namespace {

using test::GpuTest;

TEST_F(GpuTest, PicksAVulkan13DeviceWithValidation) {
    EXPECT_GE(ctx().properties().apiVersion, VK_API_VERSION_1_3);
    EXPECT_TRUE(ctx().validation_enabled());
    EXPECT_NE(ctx().cmd_push_descriptor_set, nullptr);
    EXPECT_FALSE(ctx().device_name().empty());
    EXPECT_GT(ctx().timestamp_period_ns(), 0.0);
}

TEST(GpuContext, SelectsDeviceByIndexAndByName) {
    ContextOptions by_index;
    by_index.validation = false;
    by_index.device = "0";
    auto first = test::create_context(by_index);
    ASSERT_TRUE(first) << first.error().message;

    ContextOptions by_name;
    by_name.validation = false;
    // A substring of the name in any case selects the same device.
    std::string name = first.value()->device_name();
    by_name.device = name.substr(0, 4);
    for (char& c : by_name.device) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    auto second = test::create_context(by_name);
    ASSERT_TRUE(second) << second.error().message;
    EXPECT_EQ(second.value()->device_name(), name);
}

// ContextOptions::keep_freed_memory_on_cpu_device: on lavapipe, after Context::create, a
// 20 MiB block comes from the heap (not a mapping of its own) and stays there when freed
// (not trimmed back to the kernel); the option off, or another device, leaves malloc alone.
TEST(GpuContext, KeepsFreedMemoryOnACpuDevice) {
    ContextOptions options;
    options.validation = false;
    options.keep_freed_memory_on_cpu_device = false;
    auto untouched = test::create_context(options);
    ASSERT_TRUE(untouched) << untouched.error().message;
    EXPECT_FALSE(untouched.value()->keeps_freed_memory());
    options.keep_freed_memory_on_cpu_device = true;
    auto context = test::create_context(options);
    ASSERT_TRUE(context) << context.error().message;
    const bool cpu = context.value()->properties().deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
    EXPECT_EQ(context.value()->keeps_freed_memory(), cpu && FACET_GLIBC_MALLOC);
#if FACET_GLIBC_MALLOC
    if (!cpu) return;
    void* (*volatile allocate)(size_t) = std::malloc;  // not elided with the free below
    const size_t bytes = 20u << 20;
    const size_t mapped_before = mallinfo2().hblkhd;
    void* block = allocate(bytes);
    ASSERT_NE(block, nullptr);
    std::memset(block, 1, bytes);
    EXPECT_EQ(mallinfo2().hblkhd, mapped_before) << "a 20 MiB block was given a mapping of its own";
    std::free(block);
    EXPECT_GE(mallinfo2().fordblks, bytes) << "the freed 20 MiB went back to the kernel";
#endif
}

TEST(GpuContext, UnknownDeviceIsAClearError) {
    ContextOptions options;
    options.validation = false;
    options.device = "no-such-gpu-xyz";
    auto context = test::create_context(options);
    ASSERT_FALSE(context);
    EXPECT_NE(context.error().message.find("no-such-gpu-xyz"), std::string::npos) << context.error().message;
    EXPECT_NE(context.error().message.find("devices:"), std::string::npos) << context.error().message;

    options.device = "99";
    auto by_index = test::create_context(options);
    ASSERT_FALSE(by_index);
    EXPECT_NE(by_index.error().message.find("'99'"), std::string::npos) << by_index.error().message;
}

TEST_F(GpuTest, AllocatorSubAllocatesAlignedAndReturnsMemory) {
    Allocator& allocator = ctx().allocator();
    const AllocatorStats before = allocator.stats();
    VkMemoryRequirements req{};
    req.size = 1000;
    req.alignment = 256;
    req.memoryTypeBits = ~0u;
    std::vector<Allocation> allocations;
    for (int i = 0; i < 8; ++i) allocations.push_back(test::must(allocator.allocate(req, MemoryUsage::gpu_only)));
    for (size_t i = 0; i < allocations.size(); ++i) {
        EXPECT_EQ(allocations[i].offset % 256, 0u);
        EXPECT_GE(allocations[i].block, 0);
        for (size_t j = 0; j < i; ++j) {
            if (allocations[i].memory != allocations[j].memory) continue;
            const bool disjoint = allocations[i].offset >= allocations[j].offset + allocations[j].size ||
                                  allocations[j].offset >= allocations[i].offset + allocations[i].size;
            EXPECT_TRUE(disjoint) << "allocations " << i << " and " << j << " overlap";
        }
    }
    // A freed range is reused by the next allocation of the same size.
    const VkDeviceSize freed_offset = allocations[3].offset;
    VkDeviceMemory freed_memory = allocations[3].memory;
    allocator.free(allocations[3]);
    Allocation again = test::must(allocator.allocate(req, MemoryUsage::gpu_only));
    EXPECT_EQ(again.memory, freed_memory);
    EXPECT_EQ(again.offset, freed_offset);
    allocations[3] = again;

    // Large requests get memory of their own.
    VkMemoryRequirements large = req;
    large.size = Allocator::dedicated_threshold + 4096;
    Allocation dedicated = test::must(allocator.allocate(large, MemoryUsage::gpu_only));
    EXPECT_EQ(dedicated.block, -1);
    EXPECT_EQ(allocator.stats().dedicated_count, before.dedicated_count + 1);

    allocator.free(dedicated);
    for (Allocation& a : allocations) allocator.free(a);
    const AllocatorStats after = allocator.stats();
    EXPECT_EQ(after.live_allocations, before.live_allocations);
    EXPECT_EQ(after.bytes_in_use, before.bytes_in_use);
    EXPECT_EQ(after.bytes_reserved, before.bytes_reserved) << "empty blocks go back to the driver";
}

TEST_F(GpuTest, HostVisibleAllocationsAreMapped) {
    Buffer upload =
        test::must(Buffer::create(ctx(), 4096, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUsage::upload, "test upload"));
    Buffer readback = test::must(
        Buffer::create(ctx(), 4096, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUsage::readback, "test readback"));
    EXPECT_NE(upload.mapped(), nullptr);
    EXPECT_NE(readback.mapped(), nullptr);
}

TEST_F(GpuTest, BufferRoundTripThroughDeviceMemory) {
    std::vector<uint32_t> data(10000);
    for (uint32_t i = 0; i < data.size(); ++i) data[i] = i * 2654435761u;
    Buffer buffer = test::must(Buffer::create(ctx(), data.size() * 4,
                                              VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                                                  VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                              MemoryUsage::gpu_only, "test buffer"));
    test::must(upload_buffer(ctx(), buffer, std::as_bytes(std::span(data))));
    std::vector<std::byte> back = test::must(read_buffer(ctx(), buffer));
    ASSERT_EQ(back.size(), data.size() * 4);
    EXPECT_EQ(std::memcmp(back.data(), data.data(), back.size()), 0);
}

TEST_F(GpuTest, ImageRoundTripPerMipAndLayer) {
    ImageDesc desc;
    desc.format = VK_FORMAT_R32G32B32A32_SFLOAT;
    desc.width = 16;
    desc.height = 8;
    desc.mip_levels = 3;
    desc.array_layers = 6;
    desc.cube = false;
    Image image = test::must(Image::create(
        ctx(), desc, VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
        "test image"));
    for (uint32_t layer : {0u, 5u}) {
        for (uint32_t mip = 0; mip < 3; ++mip) {
            const uint32_t n = desc.mip_width(mip) * desc.mip_height(mip) * 4;
            std::vector<float> texels(n);
            for (uint32_t i = 0; i < n; ++i) texels[i] = float(i) + 1000.0f * mip + 0.25f * layer;
            test::must(upload_image(ctx(), image, mip, layer, std::as_bytes(std::span(texels)),
                                    VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL));
            std::vector<std::byte> back =
                test::must(read_image(ctx(), image, mip, layer, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL));
            ASSERT_EQ(back.size(), n * 4u);
            EXPECT_EQ(std::memcmp(back.data(), texels.data(), back.size()), 0) << "mip " << mip << " layer " << layer;
        }
    }
    // A view of one mip of one layer is cached.
    VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 1, 1, 2, 1};
    EXPECT_EQ(test::must(image.view(range)), test::must(image.view(range)));
    EXPECT_NE(test::must(image.view(range)), test::must(image.view()));
}

TEST_F(GpuTest, BadUploadSizeIsAUsageError) {
    ImageDesc desc;
    desc.width = 4;
    desc.height = 4;
    Image image = test::must(Image::create(ctx(), desc, VK_IMAGE_USAGE_TRANSFER_DST_BIT, "test image"));
    std::vector<float> too_small(3);
    EXPECT_THROW((void)upload_image(ctx(), image, 0, 0, std::as_bytes(std::span(too_small)),
                                    VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL),
                 UsageError);
    EXPECT_THROW((void)read_image(ctx(), image, 1, 0, VK_IMAGE_LAYOUT_GENERAL), UsageError);
}

}  // namespace
}  // namespace facet

namespace facet {
namespace {

// The counter that every GPU test checks must see real validation errors: a barrier
// that names the wrong old layout is reported at submit time.
TEST(GpuValidation, WrongLayoutIsCounted) {
    ContextOptions options;
    options.validation = true;
    auto created = test::create_context(options);
    ASSERT_TRUE(created) << created.error().message;
    Context& context = *created.value();
    ImageDesc desc;
    desc.width = 4;
    desc.height = 4;
    std::vector<float> texels(4 * 4 * 4, 1.0f);
    {
        Image image = test::must(
            Image::create(context, desc, VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, "misused image"));
        test::must(upload_image(context, image, 0, 0, std::as_bytes(std::span(texels)), VK_IMAGE_LAYOUT_UNDEFINED,
                                VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL));
        EXPECT_EQ(context.validation_message_count(), 0u);
        testing::internal::CaptureStderr();
        test::must(upload_image(context, image, 0, 0, std::as_bytes(std::span(texels)), VK_IMAGE_LAYOUT_GENERAL,
                                VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL));
        std::string printed = testing::internal::GetCapturedStderr();
        EXPECT_GT(context.validation_message_count(), 0u);
        EXPECT_NE(printed.find("validation"), std::string::npos) << printed;
    }
}

}  // namespace
}  // namespace facet

namespace facet {
namespace {

// Synchronization validation is on: a copy that reads a buffer right after a fill writes
// it, with no barrier between them, is a read-after-write hazard it must report.
TEST(GpuValidation, MissingBarrierIsASyncHazard) {
    ContextOptions options;
    options.validation = true;
    options.sync_validation = true;
    auto created = test::create_context(options);
    ASSERT_TRUE(created) << created.error().message;
    Context& context = *created.value();
    Buffer a = test::must(Buffer::create(context, 256, VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                         MemoryUsage::gpu_only, "hazard source"));
    Buffer b = test::must(
        Buffer::create(context, 256, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUsage::gpu_only, "hazard destination"));
    testing::internal::CaptureStderr();
    test::must(context.submit_and_wait([&](VkCommandBuffer cmd) {
        vkCmdFillBuffer(cmd, a.handle(), 0, 256, 42);
        VkBufferCopy region{0, 0, 256};
        vkCmdCopyBuffer(cmd, a.handle(), b.handle(), 1, &region);
    }));
    std::string printed = testing::internal::GetCapturedStderr();
    EXPECT_GT(context.validation_message_count(), 0u);
    EXPECT_NE(printed.find("SYNC-HAZARD"), std::string::npos) << printed;
}

}  // namespace
}  // namespace facet
