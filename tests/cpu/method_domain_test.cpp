// The bake's method warnings read the input's dynamic range and lights only where a
// method's domain depends on them; elsewhere the stats of the size alone must give the
// same warnings (bake_warnings skips the median and the light search there).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <facet/ibl/irradiance.h>
#include <facet/ibl/method_domain.h>

namespace facet {
namespace {

struct TestImage {
    uint32_t width, height;
    std::vector<float> rgba;
};

// A sky of radiance 1 with a sun 4e4 times brighter a few texels wide, or all black.
TestImage sky(uint32_t width, uint32_t height, float sun, float base = 1.0f) {
    TestImage img{width, height, std::vector<float>(size_t(width) * height * 4, base)};
    for (uint32_t y = height / 4; y < height / 4 + 3; ++y)
        for (uint32_t x = width / 3; x < width / 3 + 3; ++x)
            for (int c = 0; c < 3; ++c) img.rgba[(size_t(y) * width + x) * 4 + c] = sun;
    for (size_t i = 3; i < img.rgba.size(); i += 4) img.rgba[i] = 1.0f;
    return img;
}

TEST(MethodDomain, WarningsNeedTheContentOnlyWhereTheyReadIt) {
    const TestImage images[] = {sky(128, 64, 4e4f), sky(16, 8, 4e4f), sky(64, 32, 1.0f), sky(64, 32, 0.0f, 0.0f)};
    const IrradianceMethod irradiance[] = {IrradianceMethod::convolve, IrradianceMethod::riemann,
                                           IrradianceMethod::sh9, IrradianceMethod::blur, IrradianceMethod::lowmip};
    const SpecularMethod specular[] = {SpecularMethod::automatic, SpecularMethod::importance,
                                       SpecularMethod::filtered,  SpecularMethod::convolve,
                                       SpecularMethod::mips,      SpecularMethod::hybrid};
    int lazy = 0, differing = 0;
    for (const TestImage& img : images) {
        const EnvironmentStats full = environment_stats(img.rgba, img.width, img.height);
        const EnvironmentStats size = environment_stats(img.rgba, img.width, img.height, false);
        EXPECT_EQ(full.black, size.black);
        for (IrradianceMethod i : irradiance)
            for (SpecularMethod s : specular)
                for (uint32_t samples : {256u, 1024u}) {
                    IblSettings settings;
                    settings.irradiance.method = i;
                    settings.specular.method = s;
                    settings.specular.sample_count = samples;
                    const auto with_content = method_warnings(full, settings);
                    if (!method_warnings_read_content(settings)) {
                        ++lazy;
                        EXPECT_EQ(method_warnings(size, settings), with_content)
                            << irradiance_method_name(i) << " " << int(s) << " " << samples;
                    } else if (method_warnings(size, settings) != with_content) {
                        ++differing;
                    }
                }
    }
    EXPECT_GT(lazy, 0);
    EXPECT_GT(differing, 0) << "the sun sky must warn for some method that reads the content";
}

}  // namespace
}  // namespace facet
