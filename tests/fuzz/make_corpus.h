#pragma once
// The seed corpora of tests/fuzz/corpus, written by Facet's own writers (write_ktx2,
// OpenImageIO through io/) and by hand-built glTF, valid files first, then malformed
// ones (truncated, wrong lengths, huge counts, out-of-range indices, NaN texels, zero
// sizes). Run by hand: fuzz_make_corpus tests/fuzz/corpus
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace facet::fuzz {

using ByteVector = std::vector<uint8_t>;

void write_seed(const std::filesystem::path& dir, const std::string& name, const ByteVector& bytes);
void write_seed(const std::filesystem::path& dir, const std::string& name, const std::string& text);
ByteVector read_bytes(const std::filesystem::path& path);
// A small RGBA8 PNG through OpenImageIO (the texture seeds embed it).
ByteVector png_bytes(uint32_t width, uint32_t height);

void make_gltf_corpus(const std::filesystem::path& dir);
// Compressed meshes and extension lists (the end of make_corpus_gltf.cpp).
void make_compressed_gltf_corpus(const std::filesystem::path& dir);

}  // namespace facet::fuzz
