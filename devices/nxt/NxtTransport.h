#pragma once
// How telegrams reach an NXT brick: over USB (NxtUsbTransport, libusb) or to an in-process
// emulator. A transport moves whole telegrams and never waits without a bound.
#include <string>

#include "core/rig/Rig.h"
#include "devices/nxt/NxtTelegram.h"

namespace activetouch::nxt {

/// A transport failure. `kind` says whether the brick did not answer in time, has gone (unplugged)
/// or the transfer failed otherwise.
class TransportError : public RigError {
public:
    enum class Kind { Timeout, Unplugged, Failed };
    TransportError(Kind kind, const std::string& what) : RigError(what), kind_(kind) {}
    Kind kind() const { return kind_; }

private:
    Kind kind_;
};

class NxtTransport {
public:
    virtual ~NxtTransport() = default;
    /// Sends one telegram (at most 64 bytes). Throws TransportError.
    virtual void write(const Bytes& telegram) = 0;
    /// Reads one reply telegram, waiting at most `timeoutMs`. Throws TransportError (Timeout when
    /// nothing came).
    virtual Bytes read(int timeoutMs) = 0;
    /// Where the brick is, for messages ("USB bus 1 device 4, NXT 00:16:53:...").
    virtual std::string describe() const = 0;
};

}  // namespace activetouch::nxt
