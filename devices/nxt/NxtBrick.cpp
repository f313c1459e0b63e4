#include "devices/nxt/NxtBrick.h"

#include <cstdio>

namespace activetouch::nxt {

std::string hexBytes(const Bytes& bytes) {
    std::string s;
    char b[4];
    for (std::size_t i = 0; i < bytes.size(); ++i) {
        std::snprintf(b, sizeof b, i ? " %02X" : "%02X", bytes[i]);
        s += b;
    }
    return s;
}

NxtBrick::NxtBrick(std::unique_ptr<NxtTransport> transport, int replyTimeoutMs)
    : transport_(std::move(transport)), replyTimeoutMs_(replyTimeoutMs) {}

void NxtBrick::setRawLog(RawLog log) {
    std::lock_guard lock(mutex_);
    log_ = std::move(log);
}

Reply NxtBrick::call(const Bytes& request) {
    std::lock_guard lock(mutex_);
    if (unplugged_)
        throw TransportError(TransportError::Kind::Unplugged,
                             "NXT: the brick is gone (" + transport_->describe() +
                                 "); plug it in again and reconnect");
    try {
        if (drain_) {
            // The reply to a request that timed out may arrive late; drop it so that replies
            // stay in step with requests.
            drain_ = false;
            try {
                const Bytes late = transport_->read(50);
                if (log_) log_("!!", "dropped a late reply: " + hexBytes(late));
            } catch (const TransportError& e) {
                if (e.kind() != TransportError::Kind::Timeout) throw;
            }
        }
        if (log_) log_("->", hexBytes(request));
        transport_->write(request);
        if (!expectsReply(request))
            return Reply{request.size() > 1 ? request[1] : std::uint8_t(0), 0, {}};
        const Bytes reply = transport_->read(replyTimeoutMs_);
        if (log_) log_("<-", hexBytes(reply));
        try {
            return decodeReply(reply, request);
        } catch (const TelegramError& e) {
            throw RigError(std::string("NXT: ") + e.what());
        }
    } catch (const TransportError& e) {
        if (e.kind() == TransportError::Kind::Unplugged) unplugged_ = true;
        if (e.kind() == TransportError::Kind::Timeout) drain_ = true;
        if (log_) log_("!!", e.what());
        throw;
    } catch (const RigError& e) {
        if (log_) log_("!!", e.what());
        throw;
    }
}

OutputState NxtBrick::outputState(std::uint8_t port) {
    return decodeOutputState(call(getOutputState(port)));
}

std::uint16_t NxtBrick::batteryMillivolts() {
    return decodeBatteryMillivolts(call(getBatteryLevel()));
}

std::uint32_t NxtBrick::keepAlive() {
    return decodeKeepAliveSleepMs(call(nxt::keepAlive()));
}

}  // namespace activetouch::nxt
