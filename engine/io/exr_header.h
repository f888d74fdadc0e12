#pragma once
// A check of an OpenEXR file's header before OpenImageIO reads it. OpenEXR 3.1 (Debian
// bookworm) allocates and fills whatever an attribute's size field declares before it
// finds the file too short, so a few hundred bytes can make it take 2 GiB.
#include <string>

namespace facet {

// Walks the attributes of every header ("OpenEXR File Layout": name, type, int32 size,
// value) and returns the first whose size runs past the end of the file, as a reason
// naming it; empty when the file is not an EXR or its sizes fit (OpenImageIO and
// OpenEXR then check everything else).
std::string check_exr_attribute_sizes(const std::string& path);

}  // namespace facet
