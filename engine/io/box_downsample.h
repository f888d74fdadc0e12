#pragma once
// Area-weighted (box) downsampling fed one source row at a time, so that a large image
// is reduced while it is read: memory is the output plus two rows of accumulators,
// never the source. Each output texel is the weighted mean of the source area it
// covers (fractional texels at its edges count by their overlap), so for an integer
// ratio it is the plain f x f box. Rows are weighted either uniformly (textures) or by
// the exact solid angle of the latitude band they span (equirectangular maps,
// io/equirect.h): a band from latitude a to b spans 2 pi (sin b - sin a), and the bands of
// the source rows inside an output row add up exactly to that row's band, so the
// output keeps the integral of radiance over the sphere (its mean) to rounding.
#include <cstdint>
#include <functional>
#include <vector>

namespace facet {

enum class RowWeights { uniform, equirect_solid_angle };

class BoxDownsampler {
public:
    // Output row `row`: dst_width * channels values, the weighted means.
    using EmitRow = std::function<void(uint32_t row, const double* values)>;

    // Requires 1 <= dst <= src in both directions.
    BoxDownsampler(uint32_t src_width, uint32_t src_height, uint32_t dst_width, uint32_t dst_height,
                   uint32_t channels, RowWeights weights, EmitRow emit);

    // Source rows in order from the top: src_width * channels values each. Output rows
    // are emitted, in order, as soon as every source row they cover has been added.
    void add_row(const float* values);
    uint32_t rows_added() const { return next_row_; }

private:
    struct Span {  // a source column's overlap with output columns first and first + 1
        uint32_t first = 0;
        double weight_first = 0, weight_second = 0;
    };
    double row_weight(double top, double bottom) const;
    void emit_row(uint32_t slot);

    uint32_t src_w_, src_h_, dst_w_, dst_h_, channels_;
    RowWeights weights_;
    EmitRow emit_;
    std::vector<Span> columns_;
    std::vector<double> column_sum_;   // per output column
    std::vector<double> acc_[2];       // output rows open_row_ and open_row_ + 1
    double row_sum_[2] = {0, 0};
    std::vector<double> out_;
    uint32_t open_row_ = 0, next_row_ = 0;
};

// The size that fits `src` inside max_width x max_height, keeping its aspect
// (each side at least 1); `src` itself when it already fits.
struct Size2 {
    uint32_t width = 0, height = 0;
};
Size2 fit_within(uint32_t src_width, uint32_t src_height, uint32_t max_width, uint32_t max_height);

}  // namespace facet
