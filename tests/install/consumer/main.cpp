// Uses the installed headers and library: a headless context, a run-time compiled
// compute shader, one dispatch, and the result checked on the CPU; then an image written
// and read back through the installed image module (lib/facet/libfacet_image_io.so, found
// through the run path the package adds), which alone brings OpenImageIO into the process.
#include <facet/gpu/context.h>
#include <facet/gpu/pipeline.h>
#include <facet/gpu/resources.h>
#include <facet/gpu/transfer.h>
#include <facet/io/environment_image.h>
#include <facet/io/image_io.h>
#include <facet/shader/compiler.h>

#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

bool mapped(const char* library) {
    std::ifstream maps("/proc/self/maps");
    std::stringstream text;
    text << maps.rdbuf();
    return text.str().find(library) != std::string::npos;
}

// A 4x2 EXR written and read back: the texels survive, and only now is OpenImageIO loaded.
int image_round_trip() {
    if (mapped("libOpenImageIO")) {
        std::fprintf(stderr, "consumer: OpenImageIO is loaded before any image is read or written\n");
        return 1;
    }
    std::vector<float> rgba(4 * 2 * 4);
    for (size_t i = 0; i < rgba.size(); ++i) rgba[i] = i % 4 == 3 ? 1.0f : float(i) * 0.25f;
    const std::string path = "/tmp/facet_consumer_" + std::to_string(::getpid()) + ".exr";
    facet::Status written = facet::write_hdr_image(path, 4, 2, rgba);
    auto read = written ? facet::load_environment(path) : facet::Result<facet::EnvironmentImage>(written.error());
    std::remove(path.c_str());
    if (!read) {
        std::fprintf(stderr, "consumer: %s\n", read.error().message.c_str());
        return 1;
    }
    if (read->width != 4 || read->height != 2 || read->rgba != rgba) {
        std::fprintf(stderr, "consumer: the image read back differs from the one written\n");
        return 1;
    }
    if (!mapped("libfacet_image_io") || !mapped("libOpenImageIO")) {
        std::fprintf(stderr, "consumer: the image was read without the image module?\n");
        return 1;
    }
    return 0;
}

}  // namespace

int main() {
    if (int failed = image_round_trip()) return failed;
    facet::ContextOptions options;
    options.validation = true;  // the library reads no FACET_VALIDATION: a host chooses
    auto context = facet::Context::create(options);
    if (!context) {
        std::fprintf(stderr, "consumer: %s\n", context.error().message.c_str());
        return 1;
    }
    facet::ShaderCompiler compiler;
    auto spirv = compiler.compile_source(facet::ShaderStage::compute, "squares.comp", R"(#version 460
layout(local_size_x = 64) in;
layout(std430, binding = 0) buffer Values { uint values[]; };
void main() { uint i = gl_GlobalInvocationID.x; values[i] = i * i; }
)");
    if (!spirv) {
        std::fprintf(stderr, "consumer: %s\n", spirv.error().message.c_str());
        return 1;
    }
    facet::Context& ctx = *context.value();
    auto built = facet::Pipeline::compute(ctx, spirv->words, "squares");
    if (!built) {
        std::fprintf(stderr, "consumer: %s\n", built.error().message.c_str());
        return 1;
    }
    facet::Pipeline& pipeline = built.value();
    const uint32_t count = 256;
    auto made = facet::Buffer::create(ctx, count * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                      facet::MemoryUsage::readback, "squares");
    if (!made) {
        std::fprintf(stderr, "consumer: %s\n", made.error().message.c_str());
        return 1;
    }
    facet::Buffer& buffer = *made;
    facet::Status done = ctx.submit_and_wait([&](VkCommandBuffer cmd) {
        pipeline.bind(cmd);
        const facet::DescriptorWrite writes[] = {facet::DescriptorWrite::storage_buffer(buffer.handle())};
        pipeline.push_descriptors(cmd, writes);
        vkCmdDispatch(cmd, facet::group_count(count, pipeline.workgroup_size()[0]), 1, 1);
        facet::memory_barrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                       VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
    });
    if (done) done = buffer.invalidate();
    if (!done) {
        std::fprintf(stderr, "consumer: %s\n", done.error().message.c_str());
        return 1;
    }
    const auto* values = static_cast<const uint32_t*>(buffer.mapped());
    for (uint32_t i = 0; i < count; ++i)
        if (values[i] != i * i) {
            std::fprintf(stderr, "consumer: value %u is %u, expected %u\n", i, values[i], i * i);
            return 1;
        }
    std::printf("consumer: ok on %s\n", ctx.device_name().c_str());
    return 0;
}
