#pragma once
// An NXT brick spoken to through a transport: each request is sent, its reply (if the request
// asks for one) read within the reply timeout and checked (type, echoed opcode, status). Every
// telegram in both directions goes to the raw log. Thread-safe: one exchange at a time.
#include <functional>
#include <memory>
#include <mutex>

#include "devices/nxt/NxtTransport.h"

namespace activetouch::nxt {

/// One line of a device's raw protocol log: direction ("->", "<-", "!!") and text.
using RawLog = std::function<void(const std::string& direction, const std::string& text)>;

std::string hexBytes(const Bytes& bytes);

class NxtBrick {
public:
    explicit NxtBrick(std::unique_ptr<NxtTransport> transport, int replyTimeoutMs = 1000);

    /// Sends `request`; for a request with reply, returns the checked reply. Throws
    /// TransportError (timeout, unplugged) or RigError naming the refused request.
    Reply call(const Bytes& request);

    OutputState outputState(std::uint8_t port);
    std::uint16_t batteryMillivolts();
    /// Sends a keep-alive and returns the brick's sleep time, ms.
    std::uint32_t keepAlive();

    void setRawLog(RawLog log);
    std::string describe() const { return transport_->describe(); }
    /// True once the transport has reported the brick gone; every later call throws at once.
    bool unplugged() const { return unplugged_; }

private:
    std::unique_ptr<NxtTransport> transport_;
    int replyTimeoutMs_;
    std::mutex mutex_;
    RawLog log_;
    bool unplugged_ = false;
    bool drain_ = false;  // a reply timed out: a late reply may still come
};

}  // namespace activetouch::nxt
