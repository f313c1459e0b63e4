#pragma once
// An emulated NXT brick at the telegram level, with the firmware's semantics: no reply to the
// 0x80 / 0x81 variants, status codes for bad ports and unknown opcodes, motors whose tacho count
// moves with power over (scaled) time, stops at the tacho limit and overshoots when braked.
// Faults can be armed for tests and demos. Thread-safe.
#include <array>
#include <chrono>
#include <deque>
#include <mutex>
#include <optional>
#include <string>

#include "devices/nxt/NxtTransport.h"

namespace activetouch::emu {

struct FakeNxtSettings {
    double fullPowerDegreesPerSecond = 900.0;  ///< regulated speed at power 100
    double brakeOvershoot_s = 0.01;            ///< the motor keeps turning this long after a brake
    double timeScale = 1.0;                    ///< emulated seconds per wall second
    std::uint16_t batteryMillivolts = 8150;
    std::uint32_t sleepMs = 600000;
    std::string name = "NXT";
};

class FakeNxtBrick {
public:
    enum class Fault {
        NoReply,      ///< the request is swallowed: the host times out
        WrongOpcode,  ///< the reply echoes another opcode
        Status,       ///< the reply carries a non-zero status
        Unplug,       ///< the brick is gone from now on
    };

    explicit FakeNxtBrick(FakeNxtSettings settings = {});

    /// The brick's answer to one request telegram (nothing for no-reply requests, swallowed
    /// requests, or once unplugged).
    std::optional<nxt::Bytes> handle(const nxt::Bytes& request);

    /// Arms a one-shot fault on the `skip`+1-th next request with `opcode` (0: any opcode).
    void injectFault(Fault fault, std::uint8_t opcode = 0, int skip = 0,
                     std::uint8_t status = 0xBD);
    bool unplugged() const;
    void replug();

    /// The motor's angle since the host last reset its rotation count (the tapper's retract
    /// angle), degrees, advanced to the present.
    double rotationDegrees(std::uint8_t port);
    bool motorRunning(std::uint8_t port);
    int power(std::uint8_t port);
    int requestsHandled() const;

private:
    struct Motor {
        int power = 0;
        std::uint8_t mode = 0, regulation = 0, runState = 0;
        int turn = 0;
        std::uint32_t limit = 0;
        double tacho = 0.0, blockStart = 0.0, rotationStart = 0.0, runStart = 0.0;
    };
    void advance();
    nxt::Bytes outputStateReply(std::uint8_t port, std::uint8_t status);
    struct Armed;
    /// The first armed fault for opcode `op` whose skips are spent, taken off the list.
    std::optional<Armed> takeFault(std::uint8_t op);
    /// A direct command's status (0 for success) and reply payload, for every opcode but
    /// GETOUTPUTSTATE, whose reply outputStateReply() builds.
    std::uint8_t command(const nxt::Bytes& q, nxt::Bytes& payload);
    std::uint8_t setOutputState(const nxt::Bytes& q);

    FakeNxtSettings s_;
    mutable std::mutex mutex_;
    std::array<Motor, 3> motors_;
    std::chrono::steady_clock::time_point last_;
    struct Armed {
        Fault fault;
        std::uint8_t opcode;
        int skip;
        std::uint8_t status;
    };
    std::deque<Armed> faults_;
    bool unplugged_ = false;
    int handled_ = 0;
};

/// A transport straight to a FakeNxtBrick in this process.
class FakeNxtTransport final : public nxt::NxtTransport {
public:
    explicit FakeNxtTransport(FakeNxtBrick& brick) : brick_(brick) {}
    void write(const nxt::Bytes& telegram) override;
    nxt::Bytes read(int timeoutMs) override;
    std::string describe() const override { return "emulated NXT brick"; }

private:
    FakeNxtBrick& brick_;
    std::deque<nxt::Bytes> replies_;
};

}  // namespace activetouch::emu
