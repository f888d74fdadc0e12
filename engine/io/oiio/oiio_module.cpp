// libfacet_image_io.so: every call Facet makes into OpenImageIO, behind the C table of
// io/image_module.h. Built as a module of its own (never part of facet::engine), so that
// OpenImageIO is loaded only by a process that reads or writes an image.
#include "io/image_module.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>

struct FacetImageReader {
    // Declared first, destroyed last: the input reads through it until it is closed.
    std::unique_ptr<OIIO::Filesystem::IOMemReader> memory;
    std::unique_ptr<OIIO::ImageInput> input;
    OIIO::ImageSpec spec;
};

namespace {

// The message for `error`, or nothing when the caller passed no place for it.
void set_error(char** error, const std::string& message) {
    if (!error) return;
    *error = static_cast<char*>(std::malloc(message.size() + 1));
    if (*error) std::memcpy(*error, message.c_str(), message.size() + 1);
}

FacetImageReader* opened(std::unique_ptr<FacetImageReader> reader, char** error) {
    if (!reader->input) {
        set_error(error, OIIO::geterror());
        return nullptr;
    }
    reader->spec = reader->input->spec();
    return reader.release();
}

FacetImageReader* open_file(const char* path, char** error) {
    auto reader = std::make_unique<FacetImageReader>();
    // open() reads the header only: the size is known before any texel is.
    reader->input = OIIO::ImageInput::open(path);
    return opened(std::move(reader), error);
}

FacetImageReader* open_memory(const uint8_t* bytes, size_t size, const char* name, char** error) {
    auto reader = std::make_unique<FacetImageReader>();
    reader->memory = std::make_unique<OIIO::Filesystem::IOMemReader>(bytes, size);
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);  // glTF's alpha is straight, keep it so
    // OpenImageIO 2.4's plugins take the proxy from the configuration when given one.
    OIIO::Filesystem::IOProxy* proxy_pointer = reader->memory.get();
    config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy_pointer);
    reader->input = OIIO::ImageInput::open(name, &config, reader->memory.get());
    return opened(std::move(reader), error);
}

void spec(const FacetImageReader* reader, FacetImageSpec* out) {
    const OIIO::ImageSpec& s = reader->spec;
    *out = FacetImageSpec{s.x, s.y, s.z, s.width, s.height, s.depth, s.nchannels, s.tile_width, s.tile_height};
}

int read_rows(FacetImageReader* reader, int32_t ybegin, int32_t yend, float* out, char** error) {
    const OIIO::ImageSpec& s = reader->spec;
    OIIO::ImageInput& in = *reader->input;
    const bool ok = s.tile_width > 0
                        ? in.read_tiles(0, 0, s.x, s.x + s.width, ybegin, yend, s.z, s.z + 1, 0, s.nchannels,
                                        OIIO::TypeDesc::FLOAT, out)
                        : in.read_scanlines(0, 0, ybegin, yend, s.z, 0, s.nchannels, OIIO::TypeDesc::FLOAT, out);
    if (!ok) set_error(error, in.geterror());
    return ok;
}

void close(FacetImageReader* reader) {
    if (!reader) return;
    reader->input->close();
    delete reader;
}

int write(const char* path, uint32_t width, uint32_t height, uint32_t channels, FacetImagePixels pixels,
          const void* data, const FacetImageAttribute* attributes, size_t attribute_count, char** error) {
    const OIIO::TypeDesc format = pixels == FACET_IMAGE_UINT8 ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::FLOAT;
    OIIO::ImageSpec spec(int(width), int(height), int(channels), format);
    for (size_t i = 0; i < attribute_count; ++i) {
        if (attributes[i].text) spec.attribute(attributes[i].name, attributes[i].text);
        else spec.attribute(attributes[i].name, int(attributes[i].number));
    }
    auto out = OIIO::ImageOutput::create(path);
    if (!out) {
        set_error(error, "cannot write this format: " + OIIO::geterror());
        return 0;
    }
    if (!out->open(path, spec)) {
        set_error(error, "cannot open for writing: " + out->geterror());
        return 0;
    }
    if (!out->write_image(spec.format, data)) {
        std::string reason = out->geterror();
        out->close();
        set_error(error, "write failed: " + reason);
        return 0;
    }
    if (!out->close()) {
        set_error(error, "write failed: " + out->geterror());
        return 0;
    }
    return 1;
}

void free_text(char* text) { std::free(text); }

const FacetImageModule table = {FACET_IMAGE_MODULE_ABI, FACET_VERSION, open_file, open_memory, spec, read_rows,
                                close, write, free_text};

}  // namespace

extern "C" __attribute__((visibility("default"))) const FacetImageModule* facet_image_module() { return &table; }
