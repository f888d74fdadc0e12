#include "io/image_module_loader.h"

#include <dlfcn.h>

#include <cstring>
#include <mutex>

namespace facet {

namespace {

// Found the way the dynamic linker finds a library: through the run path of the program
// (or shared library) that linked facet::engine. The build sets it to the build tree's
// lib/facet, installed programs to $ORIGIN/../lib/facet, and a project that links the
// installed facet::engine gets PREFIX/lib/facet from the package (facetTargets.cmake).
// The library itself reads no environment variable.
constexpr const char* kImageModuleFile = "libfacet_image_io.so";

Result<const FacetImageModule*> load_image_module() {
#ifdef FACET_IMAGE_MODULE_LINKED
    // Built into the program (the fuzz targets, which link OpenImageIO themselves).
    const FacetImageModule* module = facet_image_module();
#else
    // RTLD_LAZY as the program's own libraries are bound; RTLD_LOCAL: OpenImageIO's symbols
    // stay out of the global scope. Never unloaded (readers may outlive any one caller).
    void* handle = ::dlopen(kImageModuleFile, RTLD_LAZY | RTLD_LOCAL);
    if (!handle)
        return Error{std::string("cannot load Facet's image module, which reads and writes images through "
                                 "OpenImageIO: ") +
                     ::dlerror() + " (it is installed in lib/facet beside libfacet.a; programs linked with " +
                     "facet::engine find it through their run path)"};
    auto entry = reinterpret_cast<const FacetImageModule* (*)()>(::dlsym(handle, FACET_IMAGE_MODULE_ENTRY));
    if (!entry) return Error{std::string(kImageModuleFile) + ": not Facet's image module (no " + FACET_IMAGE_MODULE_ENTRY + ")"};
    const FacetImageModule* module = entry();
#endif
    if (!module || module->abi != FACET_IMAGE_MODULE_ABI || std::strcmp(module->facet_version, FACET_VERSION) != 0)
        return Error{std::string(kImageModuleFile) + " is from Facet " +
                     (module && module->abi == FACET_IMAGE_MODULE_ABI ? module->facet_version : "(another ABI)") +
                     ", this program from Facet " + FACET_VERSION};
    return module;
}

}  // namespace

Result<const FacetImageModule*> image_module() {
    static std::once_flag once;
    static Result<const FacetImageModule*> loaded = Error{"not loaded"};
    std::call_once(once, [] { loaded = load_image_module(); });
    return loaded;
}

std::string take_module_text(const FacetImageModule& module, char* text) {
    if (!text) return {};
    std::string copy(text);
    module.free_text(text);
    return copy;
}

}  // namespace facet
