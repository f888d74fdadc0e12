#include "viewer_loader.h"

#include <exception>

#include <facet/gpu/context.h>
#include <facet/ibl/bake_settings.h>

namespace facet {

SessionLoader::SessionLoader(Context& context) : context_(context), worker_([this] { work(); }) {}

SessionLoader::~SessionLoader() { stop(); }

void SessionLoader::stop() {
    {
        std::lock_guard lock(mutex_);
        quit_ = true;
    }
    wake_.notify_all();
    if (worker_.joinable()) worker_.join();
}

std::string SessionLoader::request(const RenderJob& job, const std::string& what) {
    std::string superseded;
    {
        std::lock_guard lock(mutex_);
        if (next_) {
            superseded = next_->what;
            lines_.push_back("the load of " + superseded + " was superseded before it started");
        } else if (running_) {
            superseded = progress_.what;
        } else if (finished_) {  // done, not yet swapped in: dropped here
            superseded = finished_->what;
            lines_.push_back("the superseded load of " + superseded + " ended before a safe point; its result is dropped");
        }
        finished_.reset();
        next_ = Request{job, what, ++latest_};
    }
    wake_.notify_all();
    return superseded;
}

bool SessionLoader::pending() const {
    std::lock_guard lock(mutex_);
    return next_ || running_ || finished_;
}

SessionLoader::Progress SessionLoader::progress() const {
    std::lock_guard lock(mutex_);
    if (next_) return Progress{next_->what};  // a stale load may still be stopping: shown as not started
    Progress p = progress_;
    p.latest = running_ && running_generation_ == latest_;
    return p;
}

std::vector<std::string> SessionLoader::take_lines() {
    std::lock_guard lock(mutex_);
    return std::exchange(lines_, {});
}

std::optional<SessionLoader::Finished> SessionLoader::take_finished() {
    std::lock_guard lock(mutex_);
    return std::exchange(finished_, std::nullopt);
}

void SessionLoader::say(const std::string& line) {
    std::lock_guard lock(mutex_);
    lines_.push_back(line);
    progress_.last_line = line;
}

void SessionLoader::work() {
    for (;;) {
        Request request;
        {
            std::unique_lock lock(mutex_);
            wake_.wait(lock, [&] { return quit_ || next_; });
            if (quit_) return;
            request = std::move(*next_);
            next_.reset();
            running_ = true;
            running_generation_ = request.generation;
            progress_ = Progress{request.what};
        }
        const uint64_t generation = request.generation;
        std::string stopped_at;  // the safe point where a superseded load stopped
        RenderSession::Callbacks callbacks;
        callbacks.progress = [&](const std::string& line) { say(line); };
        callbacks.bake_pass_done = [&](uint32_t done, uint32_t total, const std::string&) {
            std::lock_guard lock(mutex_);
            progress_.passes_done = done;
            progress_.passes_total = total;
        };
        callbacks.stop = [&](const char* point) {
            std::lock_guard lock(mutex_);
            if (quit_ || latest_ != generation) {
                stopped_at = point;
                return true;
            }
            return false;
        };
        Result<std::unique_ptr<RenderSession>> session = Error{"not loaded"};
        try {
            session = RenderSession::create(context_, request.job, callbacks);
        } catch (const std::exception& e) {  // programmer misuse or memory: shown as an error
            session = Error{request.what + ": " + e.what()};
        }
        const bool cancelled = !session && is_cancelled(session.error());
        std::unique_ptr<RenderSession> dropped;  // a superseded session, destroyed here (unlocked)
        {
            std::lock_guard lock(mutex_);
            running_ = false;
            if (!quit_ && latest_ == generation && !cancelled) {
                finished_ = Finished{request.what, std::move(session)};
                continue;
            }
            const Progress& p = progress_;
            if (cancelled)
                lines_.push_back("stopped the load of " + request.what + " at its safe point '" + stopped_at + "' (" +
                                 std::to_string(p.passes_done) + "/" + std::to_string(p.passes_total) +
                                 " bake passes done)");
            else
                lines_.push_back("the superseded load of " + request.what +
                                 " ended before a safe point; its result is dropped");
            if (session) dropped = std::move(*session);
        }
    }
}

}  // namespace facet
