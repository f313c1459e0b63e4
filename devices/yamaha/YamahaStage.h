#pragma once
// The Yamaha XY stage behind an RCX controller (docs/protocols.md §2) as a Stage: servo on, origin
// search, absolute moves at a speed, the position query, arrival confirmed by polling the position
// within a tolerance, soft limits checked before anything is sent, and stop (ETX). Every line in
// both directions goes to the raw log; every wait has a bound.
#include <atomic>
#include <functional>
#include <mutex>

#include "core/rig/Rig.h"
#include "devices/yamaha/RcxProtocol.h"
#include "devices/yamaha/SerialLineChannel.h"

namespace activetouch::rcx {

struct YamahaStageSettings {
    SerialSettings serial;
    Dialect dialect = Dialect::Rcx22x;
    int speedPercent = 20;
    /// Speed at 100 %, mm/s, to bound how long a move may take (unverified: depends on the axes).
    double fullSpeed_mm_s = 1000.0;
    Vec2 softMin{0.0, 0.0}, softMax{650.0, 300.0};  ///< the paper rig's XY-X travel
    double arrivalTolerance_mm = 0.05;
    int replyTimeoutMs = 2000;
    int pollPeriodMs = 20;
    double originTimeout_s = 60.0;
    double motionMargin_s = 2.0;  ///< added to the expected travel time
    double timeScale = 1.0;       ///< emulated controllers may run faster than real time
    /// When this becomes true (Ctrl-C in the headless runner), an origin search in progress is
    /// stopped with ETX and home() throws. Not owned; none: the search runs to its end.
    const std::atomic<bool>* stopOriginSearch = nullptr;
};

class YamahaStage final : public Stage {
public:
    using RawLog = std::function<void(const std::string& direction, const std::string& text)>;
    explicit YamahaStage(YamahaStageSettings settings, RawLog log = {});
    ~YamahaStage() override;

    /// Opens the port, switches the servo on, searches the origin if `searchOrigin`, reads the
    /// position. Throws RigError.
    void connect(bool searchOrigin = true);
    void disconnect();
    /// Searches the origin (returns once the controller reports it done). Throws RigError, also
    /// when `stopOriginSearch` stops it.
    void home();

    void moveTo(Vec2 target) override;
    Vec2 position() const override;
    /// Asks the controller where the stage is and returns it.
    Vec2 queryPosition();
    /// Stops motion at once (ETX). Never throws; false if the stop could not be sent.
    bool stop() noexcept;
    /// For closing, from any thread: stops motion (ETX), ends a move or query waiting on the
    /// controller within a few tens of milliseconds with RigError instead of letting it wait out
    /// its bound, and refuses every later command. Never throws.
    void interrupt() noexcept;

    /// Whether `p` lies within the soft limits.
    bool withinSoftLimits(Vec2 p) const;
    const YamahaStageSettings& settings() const { return s_; }

private:
    /// Logs and writes `line`; RigError if interrupt() was called.
    void send(const std::string& line);
    /// Logs and writes `line`, whatever came before; `now`: returns once it has left the process
    /// (at most a second), false if it has not.
    bool write(const std::string& line, bool now = false);
    /// The next meaningful reply within `timeoutMs`: garbage lines are logged and skipped, END
    /// lines are remembered and skipped unless `wantEnd`, errors throw RigError naming `what`.
    std::optional<Reply> await(const std::string& what, int timeoutMs, bool wantEnd = false);
    /// Sends `line` and waits for OK (or END). If `stopWhen` becomes true first, stops the
    /// stage (ETX) and throws.
    void expectOk(const std::string& line, int timeoutMs,
                  const std::atomic<bool>* stopWhen = nullptr);
    int motionTimeoutMs(double distance_mm) const;
    /// Throws RigError if interrupt() was called.
    void refuseIfInterrupted() const;

    std::atomic<bool> interrupted_{false};
    YamahaStageSettings s_;
    RawLog log_;
    SerialLineChannel channel_;
    mutable std::mutex mutex_;
    Vec2 position_;
    bool endSeen_ = false;
};

}  // namespace activetouch::rcx
