#include <algorithm>

#include "feed.h"
#include <facet/io/ktx2.h>

namespace facet::fuzz {

namespace {

void check_image(const Ktx2Image& image) {
    FACET_FUZZ_EXPECT(ktx2_texel_size(image.format) != 0, "unsupported format accepted");
    FACET_FUZZ_EXPECT(image.width > 0 && image.height > 0, "zero size accepted");
    FACET_FUZZ_EXPECT(image.faces == 1 || (image.faces == 6 && image.width == image.height), "bad face count accepted");
    FACET_FUZZ_EXPECT(image.levels >= 1 && image.level_data.size() == image.levels, "levels and level data disagree");
    for (uint32_t l = 0; l < image.levels; ++l)
        FACET_FUZZ_EXPECT(image.level_data[l].size() == ktx2_level_size(image, l),
                          "level " + std::to_string(l) + " holds the wrong number of bytes");
}

}  // namespace

bool feed_ktx2(Bytes input) {
    const std::string path = write_input(input, "input.ktx2");
    Result<Ktx2Image> image = read_ktx2(path);
    if (!image) {
        expect_names_file(image.error(), path);
        return false;
    }
    check_image(*image);

    // What reads must write, and read back as the same image (key/value pairs sorted).
    const std::string copy = work_dir() + "/copy.ktx2";
    Status written = write_ktx2(copy, *image);
    FACET_FUZZ_EXPECT(written.ok(), "a file that reads does not write: " + written.error().message);
    Result<Ktx2Image> again = read_ktx2(copy);
    FACET_FUZZ_EXPECT(again.ok(), "a written file does not read: " + again.error().message);
    Ktx2Image& a = *image;
    const Ktx2Image& b = *again;
    std::stable_sort(a.key_values.begin(), a.key_values.end(),
                     [](const auto& x, const auto& y) { return x.first < y.first; });
    FACET_FUZZ_EXPECT(a.format == b.format && a.width == b.width && a.height == b.height && a.faces == b.faces &&
                          a.levels == b.levels,
                      "the header changed in a round trip");
    FACET_FUZZ_EXPECT(a.level_data == b.level_data, "texels changed in a round trip");
    FACET_FUZZ_EXPECT(a.key_values == b.key_values, "key/value data changed in a round trip");
    return true;
}

}  // namespace facet::fuzz
