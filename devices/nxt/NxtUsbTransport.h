#pragma once
// The NXT over USB with libusb-1.0 (docs/protocols.md §1): finds 0694:0002 (refusing the SAM-BA boot
// loader 03EB:6124 by name), detaches a kernel driver, resets, selects configuration 1, claims
// interface 0 and moves telegrams over bulk OUT 0x01 / IN 0x82 with bounded timeouts. A vanished
// device is reported as unplugged.
#include <memory>
#include <vector>

#include "devices/nxt/NxtTransport.h"

struct libusb_context;
struct libusb_device_handle;

namespace activetouch::nxt {

struct UsbBrickInfo {
    int bus = 0, address = 0;
    bool bootLoader = false;  ///< a brick in firmware-update mode (SAM-BA)
    std::string serial;       ///< the brick's Bluetooth address, when it could be read
    std::string describe() const;
};

class NxtUsbTransport final : public NxtTransport {
public:
    /// Opens the first NXT found, or the one at bus/address. Throws RigError naming what was found
    /// and what to do (no brick, boot loader, permissions, busy).
    explicit NxtUsbTransport(int bus = 0, int address = 0);
    ~NxtUsbTransport() override;

    /// Every NXT (and boot loader) on the USB buses. Throws RigError if libusb cannot start.
    static std::vector<UsbBrickInfo> list();

    void write(const Bytes& telegram) override;
    Bytes read(int timeoutMs) override;
    std::string describe() const override { return info_.describe(); }

private:
    libusb_context* ctx_ = nullptr;
    libusb_device_handle* handle_ = nullptr;
    UsbBrickInfo info_;
};

}  // namespace activetouch::nxt
