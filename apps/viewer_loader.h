#pragma once
// Loading and baking off the render thread. One worker thread runs RenderSession::create
// for the latest request while the window keeps drawing the current session; the render
// thread swaps the finished session in between frames (after its frame fence, so nothing
// of the old session is still in use). A newer request stops the stale load at its next
// safe point (the bake's passes: ibl/bake_settings.h BakeStopFn) and runs after it.
// The worker shares only the Context with the render thread: the new session has its own
// shader compiler, pipelines and executor, and the Context serialises the queue
// (Context::lock_queue for the render thread's own submissions).
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <facet/core/result.h>
#include <facet/render/render_job.h>

namespace facet {

class Context;

class SessionLoader {
public:
    explicit SessionLoader(Context& context);
    // stop().
    ~SessionLoader();
    SessionLoader(const SessionLoader&) = delete;
    SessionLoader& operator=(const SessionLoader&) = delete;

    // Loads `job` (`what` names it in the log). Returns the load it supersedes, whose stop
    // was requested (empty when none was pending).
    std::string request(const RenderJob& job, const std::string& what);
    // From request() until take_finished() returned the result.
    bool pending() const;
    // Stops the load in progress at its next safe point and joins the worker; what the
    // load said (its stop included) stays for take_lines(). No request after it.
    void stop();

    struct Progress {
        std::string what;          // the load's name
        uint32_t passes_done = 0;  // of the bake (0 of 0 before it starts, and without one)
        uint32_t passes_total = 0;
        std::string last_line;     // what the load said last
        bool latest = false;       // the load running is the latest request (not a stale one stopping)
    };
    Progress progress() const;
    // Lines the loads said since the last call: the render thread prints them (the window
    // title belongs to it).
    std::vector<std::string> take_lines();

    struct Finished {
        std::string what;
        Result<std::unique_ptr<RenderSession>> session;
    };
    // The latest request's result, once; nothing while it runs. A superseded load's
    // result never comes here (the worker drops it and says so).
    std::optional<Finished> take_finished();

private:
    struct Request {
        RenderJob job;
        std::string what;
        uint64_t generation = 0;
    };
    void work();
    void say(const std::string& line);

    Context& context_;
    mutable std::mutex mutex_;
    std::condition_variable wake_;
    std::optional<Request> next_;      // requested, not started
    uint64_t latest_ = 0;              // generation of the latest request
    bool running_ = false;             // the worker is inside a load
    uint64_t running_generation_ = 0;  // of that load
    std::optional<Finished> finished_;
    Progress progress_;
    std::vector<std::string> lines_;
    bool quit_ = false;
    std::thread worker_;  // last: it starts once the members above exist
};

}  // namespace facet
