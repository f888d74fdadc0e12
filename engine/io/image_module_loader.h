#pragma once
// The image module (io/image_module.h), loaded the first time an image is read or
// written: OpenImageIO and its libraries stay out of every process that uses none.
#include <memory>
#include <string>

#include <facet/core/result.h>
#include "io/image_module.h"

namespace facet {

// The module's table; loaded once per process (thread-safe). An Error says why it cannot
// be (not found, another Facet version's), the same each time it is asked.
Result<const FacetImageModule*> image_module();

// A module message (char** error) as a string, released.
std::string take_module_text(const FacetImageModule& module, char* text);

struct ImageReaderCloser {
    const FacetImageModule* module = nullptr;
    void operator()(FacetImageReader* reader) const { module->close(reader); }
};
using ImageReader = std::unique_ptr<FacetImageReader, ImageReaderCloser>;

}  // namespace facet
