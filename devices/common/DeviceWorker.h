#pragma once
// The one way a device runs work in a thread of its own (docs/design.md §2, "Device threads").
//
// The policy, which makes shutdown bounded without aborting or leaking:
//  - every call a device thread makes blocks for a bounded time: a read or a socket wait for at
//    most kStepBound_ms, a connect for at most the device's connect timeout, a queued slot for
//    no longer than the calls inside it;
//  - a loop checks stopRequested() between such calls;
//  - stop() asks (the stop flag, and quitting the event loop) and then waits for the thread to
//    end, which the bounds above make short. A thread is never destroyed while it runs (which
//    aborts the process), detached, or left running past its owner (which leaks it).
#include <QThread>
#include <atomic>
#include <functional>
#include <memory>
#include <string>

namespace activetouch {

class DeviceWorker {
public:
    /// The longest a device thread's loop may block between two looks at stopRequested().
    static constexpr int kStepBound_ms = 100;

    explicit DeviceWorker(std::string name);
    ~DeviceWorker();  ///< stop()
    DeviceWorker(const DeviceWorker&) = delete;
    DeviceWorker& operator=(const DeviceWorker&) = delete;

    /// Starts an event loop: objects moved to thread() live in it, and queued calls run there.
    void startEventLoop();
    /// Starts `loop`, which runs until it returns; it must return soon after stopRequested().
    void start(std::function<void()> loop);

    /// The thread while it runs (for QObject::moveToThread), else nullptr.
    QThread* thread() const { return thread_.get(); }
    bool stopRequested() const { return stop_.load(); }
    /// Asks the thread to stop and waits for it to end; then it may be started again. Does
    /// nothing when no thread runs. Never call it from the thread itself.
    void stop();

private:
    std::string name_;
    std::unique_ptr<QThread> thread_;
    std::atomic<bool> stop_{false};
};

}  // namespace activetouch
