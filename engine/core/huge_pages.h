#pragma once
// Large host buffers written once from end to end (device memory on a CPU device, a
// decoded environment, an encoded file) pay a page fault per 4 KiB on first touch: about
// 6-12 us each on the 2-core test machine, 20 ms for 8 MiB. Transparent huge pages, where
// the kernel offers them on request ("madvise" mode, Debian's default), cut that 512-fold
// for the 2 MiB-aligned part of the range. A hint: any failure is harmless and ignored.
#include <cstddef>

namespace facet {

// Asks for huge pages over the 2 MiB-aligned interior of [data, data + size); call it
// before the range is first written.
void advise_huge_pages(void* data, std::size_t size);

}  // namespace facet
