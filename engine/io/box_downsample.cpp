#include "io/box_downsample.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "io/equirect.h"

namespace facet {

namespace {

// Output cell `cell` covers source coordinates [cell * src / dst, (cell + 1) * src / dst);
// the integer test keeps the boundaries exact whatever the ratio.
struct Overlap {
    uint32_t first = 0;
    double from = 0, split = 0, to = 0;  // [from, split) in `first`, [split, to) in first + 1
    bool spills = false;
};

Overlap overlap(uint32_t s, uint32_t src, uint32_t dst) {
    Overlap o;
    o.first = uint32_t(uint64_t(s) * dst / src);
    o.from = s;
    o.to = s + 1.0;
    o.spills = uint64_t(o.first + 1) * src < uint64_t(s + 1) * dst;
    o.split = o.spills ? double(uint64_t(o.first + 1) * src) / double(dst) : o.to;
    return o;
}

}  // namespace

BoxDownsampler::BoxDownsampler(uint32_t src_width, uint32_t src_height, uint32_t dst_width, uint32_t dst_height,
                               uint32_t channels, RowWeights weights, EmitRow emit)
    : src_w_(src_width),
      src_h_(src_height),
      dst_w_(dst_width),
      dst_h_(dst_height),
      channels_(channels),
      weights_(weights),
      emit_(std::move(emit)) {
    if (dst_w_ < 1 || dst_h_ < 1 || dst_w_ > src_w_ || dst_h_ > src_h_ || channels_ < 1)
        throw std::logic_error("BoxDownsampler: the output must be 1..source texels in each direction");
    columns_.resize(src_w_);
    column_sum_.assign(dst_w_, 0.0);
    for (uint32_t x = 0; x < src_w_; ++x) {
        const Overlap o = overlap(x, src_w_, dst_w_);
        columns_[x] = {o.first, o.split - o.from, o.to - o.split};
        column_sum_[o.first] += columns_[x].weight_first;
        if (o.spills) column_sum_[o.first + 1] += columns_[x].weight_second;
    }
    for (auto& a : acc_) a.assign(size_t(dst_w_) * channels_, 0.0);
    out_.resize(size_t(dst_w_) * channels_);
}

double BoxDownsampler::row_weight(double top, double bottom) const {
    if (weights_ == RowWeights::uniform) return bottom - top;
    return equirect_band_solid_angle(top, bottom, src_h_);
}

void BoxDownsampler::emit_row(uint32_t slot) {
    const std::vector<double>& a = acc_[slot];
    for (uint32_t i = 0; i < dst_w_; ++i) {
        const double total = row_sum_[slot] * column_sum_[i];
        for (uint32_t c = 0; c < channels_; ++c) {
            const size_t k = size_t(i) * channels_ + c;
            out_[k] = total > 0 ? a[k] / total : 0.0;
        }
    }
    emit_(open_row_, out_.data());
}

void BoxDownsampler::add_row(const float* values) {
    if (next_row_ >= src_h_) throw std::logic_error("BoxDownsampler: more rows than the source has");
    const Overlap o = overlap(next_row_, src_h_, dst_h_);
    if (o.first > open_row_) {  // every source row of open_row_ is in
        emit_row(0);
        std::swap(acc_[0], acc_[1]);
        std::fill(acc_[1].begin(), acc_[1].end(), 0.0);
        row_sum_[0] = row_sum_[1];
        row_sum_[1] = 0;
        ++open_row_;
    }
    // Columns first (one pass over the source row), then the row's weight(s).
    std::vector<double>& reduced = out_;
    std::fill(reduced.begin(), reduced.end(), 0.0);
    for (uint32_t x = 0; x < src_w_; ++x) {
        const Span& s = columns_[x];
        const float* v = values + size_t(x) * channels_;
        double* r = &reduced[size_t(s.first) * channels_];
        for (uint32_t c = 0; c < channels_; ++c) r[c] += s.weight_first * v[c];
        if (s.weight_second > 0)
            for (uint32_t c = 0; c < channels_; ++c) r[channels_ + c] += s.weight_second * v[c];
    }
    const double w_first = row_weight(o.from, o.split);
    const double w_second = o.spills ? row_weight(o.split, o.to) : 0.0;
    for (size_t k = 0; k < reduced.size(); ++k) {
        acc_[0][k] += w_first * reduced[k];
        if (o.spills) acc_[1][k] += w_second * reduced[k];
    }
    row_sum_[0] += w_first;
    row_sum_[1] += w_second;
    if (++next_row_ == src_h_) emit_row(0);
}

Size2 fit_within(uint32_t src_width, uint32_t src_height, uint32_t max_width, uint32_t max_height) {
    max_width = std::max(max_width, 1u);
    max_height = std::max(max_height, 1u);
    if (src_width <= max_width && src_height <= max_height) return {src_width, src_height};
    const double scale = std::min(double(max_width) / src_width, double(max_height) / src_height);
    auto side = [&](uint32_t src, uint32_t max) {
        return std::clamp(uint32_t(std::lround(src * scale)), 1u, std::min(src, max));
    };
    return {side(src_width, max_width), side(src_height, max_height)};
}

}  // namespace facet
