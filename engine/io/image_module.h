#pragma once
// The C function table between the engine and its image module, libfacet_image_io.so:
// the only code that calls OpenImageIO. OpenImageIO brings about 260 shared libraries
// (codecs, OpenEXR, libraw, ffmpeg, ...) whose loading cost every process that linked
// it ~640 ms of CPU at start, images or not; the engine loads the module (dlopen) the
// first time it reads an image other than a Radiance .hdr, or writes one other than
// .png, .exr or .hdr (those are Facet's own: io/image_codecs.h), instead
// (io/image_module_loader.cpp).
// Plain C types only, so the two sides share no C++ layout; FACET_IMAGE_MODULE_ABI and
// the Facet version are checked when the module is loaded.
#include <cstddef>
#include <cstdint>

extern "C" {

#define FACET_IMAGE_MODULE_ABI 1
// The one symbol the module exports.
#define FACET_IMAGE_MODULE_ENTRY "facet_image_module"

struct FacetImageReader;  // an open image (OIIO::ImageInput and what it reads from)

// The first subimage's data window, as OpenImageIO's ImageSpec holds it.
struct FacetImageSpec {
    int32_t x, y, z;
    int32_t width, height, depth;
    int32_t channels;
    int32_t tile_width, tile_height;  // 0: scanlines
};

enum FacetImagePixels { FACET_IMAGE_FLOAT = 0, FACET_IMAGE_UINT8 = 1 };

// One attribute of the written file (OIIO::ImageSpec::attribute).
struct FacetImageAttribute {
    const char* name;
    const char* text;  // a string attribute, or null for
    int32_t number;    // an int one
};

// Every `char** error` receives, on failure, a message the caller releases with
// free_text (possibly empty: OpenImageIO gave no reason).
struct FacetImageModule {
    uint32_t abi;             // FACET_IMAGE_MODULE_ABI
    const char* facet_version;  // FACET_VERSION of the build that made the module

    // An image file; null on failure (the reason is OpenImageIO's, without the path).
    FacetImageReader* (*open_file)(const char* path, char** error);
    // Bytes in memory (not copied: they outlive the reader); `name`'s extension chooses
    // the decoder. Alpha is kept straight (oiio:UnassociatedAlpha).
    FacetImageReader* (*open_memory)(const uint8_t* bytes, size_t size, const char* name, char** error);
    void (*spec)(const FacetImageReader* reader, FacetImageSpec* out);
    // Rows [ybegin, yend) of the data window (file coordinates: spec.y + row), every
    // channel, the whole width, as float: tiles for a tiled file (yend - ybegin a
    // multiple of the tile height or reaching the last row), scanlines otherwise.
    // Returns 0 on failure.
    int (*read_rows)(FacetImageReader* reader, int32_t ybegin, int32_t yend, float* out, char** error);
    void (*close)(FacetImageReader* reader);

    // Writes `pixels` (rows top first, channels interleaved) to `path`, whose extension
    // chooses the format. Returns 0 on failure; the error reads as the end of a sentence
    // that begins with the file's name ("cannot write this format: ...").
    int (*write)(const char* path, uint32_t width, uint32_t height, uint32_t channels, FacetImagePixels pixels,
                 const void* data, const FacetImageAttribute* attributes, size_t attribute_count, char** error);

    void (*free_text)(char* text);
};

// The entry point: the module's table.
const FacetImageModule* facet_image_module();

}  // extern "C"
