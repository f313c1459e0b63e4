#pragma once
// An emulated Yamaha RCX controller on a pseudo-terminal (docs/protocols.md §2): the driver opens the
// pty's slave like a serial port. Dialect rcx22x or rcx340; state (servo, origin done, position);
// travel time from distance and speed; NG for moves before the origin search or beyond the travel;
// ETX stops. Faults for tests: no reply, NG, garbage, dropped END (or OK), the port vanishing.
#include <atomic>
#include <chrono>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "core/geometry/Vec2.h"
#include "devices/yamaha/RcxProtocol.h"

namespace activetouch::emu {

struct FakeRcxSettings {
    rcx::Dialect dialect = rcx::Dialect::Rcx22x;
    double fullSpeed_mm_s = 1000.0;
    double timeScale = 1.0;
    Vec2 travel{650.0, 300.0};
    double origin_s = 0.3;  ///< how long the origin search takes
    bool originDone = false;
    Vec2 start{0.0, 0.0};
};

class FakeRcxController {
public:
    enum class Fault { NoReply, Ng, Garbage, DropEnd, Vanish };

    explicit FakeRcxController(FakeRcxSettings settings = {});
    ~FakeRcxController();
    FakeRcxController(const FakeRcxController&) = delete;
    FakeRcxController& operator=(const FakeRcxController&) = delete;

    /// Opens the pseudo-terminal and starts answering. Throws std::runtime_error.
    void start();
    void stop();
    /// The slave's path, e.g. /dev/pts/3: the serial port name for the driver.
    std::string portName() const { return slaveName_; }

    /// Arms a one-shot fault for the `skip`+1-th next command (DropEnd: next motion command).
    void injectFault(Fault fault, int skip = 0);
    Vec2 position();
    bool moving();
    /// Every command line received, in order (without '@' and line end).
    std::vector<std::string> commands();

private:
    void loop();
    void handle(const std::string& command);
    void reply(const std::string& line);
    void startMotion(Vec2 target, double speed_mm_s, bool isOrigin);
    Vec2 positionLocked(std::chrono::steady_clock::time_point now) const;

    FakeRcxSettings s_;
    int master_ = -1, slave_ = -1;
    std::string slaveName_;
    std::thread thread_;
    std::atomic<bool> running_{false};
    std::mutex mutex_;
    std::string in_, out_;
    std::vector<std::string> commands_;
    struct Armed {
        Fault fault;
        int skip;
    };
    std::vector<Armed> faults_;
    bool servo_ = false, originDone_ = false;
    Vec2 from_, to_;
    std::chrono::steady_clock::time_point motionStart_, motionEnd_;
    bool moving_ = false, dropEnd_ = false;
};

}  // namespace activetouch::emu
