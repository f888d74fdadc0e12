// Textures decoded once per file content (issue 15): loading the same model again decodes
// none of its images (the viewer's reload, the bench's repeated renders) and gives the
// same texels; other decode settings (a smaller kept size) decode again; the cache keeps
// within its capacity, least recently used out first.
#include <gtest/gtest.h>

#include <string>

#include <facet/scene/gltf_loader.h>
#include "io/texture_decode.h"

namespace facet {
namespace {

// Three 1024x1024 PNGs (4 MiB each decoded).
const std::string kSuzanne = FACET_SHARED_DATA_DIR "/models/suzanne/02_suzanne.gltf";

Scene load(const std::string& path, const GltfLimits& limits = {}) {
    auto scene = load_gltf(path, limits);
    EXPECT_TRUE(scene) << scene.error().message;
    return scene ? std::move(scene).value() : Scene{};
}

class TextureDecodeCache : public ::testing::Test {
protected:
    void SetUp() override { set_texture_cache_capacity(kDefaultCapacity); }
    void TearDown() override { set_texture_cache_capacity(kDefaultCapacity); }
    static constexpr uint64_t kDefaultCapacity = 256ull << 20;
};

TEST_F(TextureDecodeCache, TheSameModelLoadedAgainDecodesNothing) {
    set_texture_cache_capacity(0);  // empty, whatever ran before in this process
    set_texture_cache_capacity(kDefaultCapacity);
    const TextureCacheStats start = texture_cache_stats();
    const Scene first = load(kSuzanne);
    ASSERT_EQ(first.images.size(), 3u);
    const TextureCacheStats loaded = texture_cache_stats();
    EXPECT_EQ(loaded.decodes - start.decodes, 3u);
    EXPECT_EQ(loaded.hits - start.hits, 0u);
    EXPECT_EQ(loaded.bytes_kept, 3u * 1024 * 1024 * 4);

    const Scene second = load(kSuzanne);
    const TextureCacheStats again = texture_cache_stats();
    EXPECT_EQ(again.decodes, loaded.decodes) << "nothing decoded twice";
    EXPECT_EQ(again.hits - loaded.hits, 3u);
    ASSERT_EQ(second.images.size(), first.images.size());
    for (size_t i = 0; i < first.images.size(); ++i) {
        EXPECT_EQ(second.images[i].name, first.images[i].name);
        EXPECT_EQ(second.images[i].width, first.images[i].width);
        EXPECT_EQ(second.images[i].rgba, first.images[i].rgba) << first.images[i].name;
    }
    EXPECT_EQ(second.content_hash, first.content_hash);
}

TEST_F(TextureDecodeCache, OtherDecodeSettingsDecodeAgain) {
    const Scene full = load(kSuzanne);
    const TextureCacheStats before = texture_cache_stats();
    GltfLimits small;
    small.max_texture_size = 256;  // downsampled while decoded: another result from the same bytes
    const Scene reduced = load(kSuzanne, small);
    const TextureCacheStats after = texture_cache_stats();
    EXPECT_EQ(after.decodes - before.decodes, 3u);
    ASSERT_EQ(reduced.images.size(), 3u);
    EXPECT_EQ(reduced.images[0].width, 256u);
    EXPECT_EQ(full.images[0].width, 1024u);
}

TEST_F(TextureDecodeCache, KeepsWithinItsCapacityLeastRecentlyUsedOutFirst) {
    const uint64_t image_bytes = 1024 * 1024 * 4;
    set_texture_cache_capacity(0);
    EXPECT_EQ(texture_cache_stats().bytes_kept, 0u);
    // An image is kept when it is at most an eighth of the capacity.
    set_texture_cache_capacity(8 * image_bytes);
    const Scene first = load(kSuzanne);
    EXPECT_EQ(texture_cache_stats().bytes_kept, 3 * image_bytes);
    // Shrinking evicts at once, the least recently used first (the first image decoded).
    const TextureCacheStats full = texture_cache_stats();
    set_texture_cache_capacity(image_bytes * 5 / 2);
    const TextureCacheStats shrunk = texture_cache_stats();
    EXPECT_EQ(shrunk.bytes_kept, 2 * image_bytes);
    EXPECT_EQ(shrunk.evictions - full.evictions, 1u);
    // Loading again decodes the evicted one only, and does not keep it (over an eighth now).
    const Scene second = load(kSuzanne);
    const TextureCacheStats again = texture_cache_stats();
    EXPECT_EQ(again.decodes - shrunk.decodes, 1u);
    EXPECT_EQ(again.hits - shrunk.hits, 2u);
    EXPECT_EQ(again.bytes_kept, 2 * image_bytes);
    ASSERT_EQ(second.images.size(), 3u);
    EXPECT_EQ(second.images[0].rgba, first.images[0].rgba);
    set_texture_cache_capacity(0);
    EXPECT_EQ(texture_cache_stats().bytes_kept, 0u);
}

}  // namespace
}  // namespace facet
