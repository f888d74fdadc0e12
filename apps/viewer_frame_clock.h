#pragma once
// The viewer's own measure of smoothness: wall time between the ends of consecutive
// frames, which is what a user sees (work done between frames, such as a bake on the
// render thread, counts). The first frame (pipelines built, the window mapped) is left
// out. Frames per second over the rest, and the longest interval, overall and over a
// span (a background load's: from its request to its swap).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>

namespace facet {

class FrameClock {
public:
    using Clock = std::chrono::steady_clock;

    // After each frame's fence.
    void frame_done() {
        const Clock::time_point now = Clock::now();
        if (frames_ > 0) {
            const double ms = std::chrono::duration<double, std::milli>(now - last_).count();
            if (ms > longest_ms_) longest_ms_ = ms, longest_frame_ = frames_;
            span_longest_ms_ = std::max(span_longest_ms_, ms);
            ++span_frames_;
        } else {
            first_end_ = now;
        }
        last_ = now;
        ++frames_;
    }
    // Starts a span: its frames and its longest interval count from here.
    void start_span() {
        span_frames_ = 0;
        span_longest_ms_ = 0;
    }
    int span_frames() const { return span_frames_; }
    double span_longest_ms() const { return span_longest_ms_; }

    // "12.9 frames per second after the first frame (99 in 7.67 s), longest frame 81.2 ms (frame 41)"
    std::string summary() const {
        if (frames_ < 2) return "too few frames to time";
        const double seconds = std::chrono::duration<double>(last_ - first_end_).count();
        char line[160];
        std::snprintf(line, sizeof line,
                      "%.1f frames per second after the first frame (%d in %.2f s), longest frame %.1f ms (frame %d)",
                      (frames_ - 1) / seconds, frames_ - 1, seconds, longest_ms_, longest_frame_);
        return line;
    }

private:
    int frames_ = 0, longest_frame_ = 0, span_frames_ = 0;
    double longest_ms_ = 0, span_longest_ms_ = 0;
    Clock::time_point first_end_, last_;
};

}  // namespace facet
