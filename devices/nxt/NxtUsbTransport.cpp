#include "devices/nxt/NxtUsbTransport.h"

#include <libusb.h>

namespace activetouch::nxt {
namespace {

constexpr std::uint16_t kLegoVendor = 0x0694, kNxtProduct = 0x0002;
constexpr std::uint16_t kAtmelVendor = 0x03EB, kSambaProduct = 0x6124;
constexpr unsigned char kBulkOut = 0x01, kBulkIn = 0x82;
constexpr unsigned kWriteTimeoutMs = 1000;

std::string usbError(int code) {
    return std::string(libusb_error_name(code)) + ": " + libusb_strerror(code);
}

TransportError transferError(int code, const std::string& what, const std::string& where) {
    if (code == LIBUSB_ERROR_TIMEOUT)
        return TransportError(TransportError::Kind::Timeout,
                              "NXT: no " + what + " within the timeout (" + where + ")");
    if (code == LIBUSB_ERROR_NO_DEVICE)
        return TransportError(TransportError::Kind::Unplugged,
                              "NXT: the brick is gone (" + where + ", " + usbError(code) +
                                  "); check the USB cable and that the brick is on, then connect "
                                  "again");
    return TransportError(TransportError::Kind::Failed,
                          "NXT: the " + what + " failed (" + where + ", " + usbError(code) + ")");
}

struct Context {
    libusb_context* ctx = nullptr;
    Context() {
        const int r = libusb_init(&ctx);
        if (r != 0) throw RigError("USB: libusb cannot start (" + usbError(r) + ")");
    }
    ~Context() {
        if (ctx) libusb_exit(ctx);
    }
    libusb_context* release() {
        auto* c = ctx;
        ctx = nullptr;
        return c;
    }
};

std::vector<std::pair<libusb_device*, UsbBrickInfo>> bricks(libusb_device** devices) {
    std::vector<std::pair<libusb_device*, UsbBrickInfo>> found;
    for (libusb_device** d = devices; *d; ++d) {
        libusb_device_descriptor desc{};
        if (libusb_get_device_descriptor(*d, &desc) != 0) continue;
        const bool nxt = desc.idVendor == kLegoVendor && desc.idProduct == kNxtProduct;
        const bool samba = desc.idVendor == kAtmelVendor && desc.idProduct == kSambaProduct;
        if (!nxt && !samba) continue;
        UsbBrickInfo info;
        info.bus = libusb_get_bus_number(*d);
        info.address = libusb_get_device_address(*d);
        info.bootLoader = samba;
        found.emplace_back(*d, info);
    }
    return found;
}

}  // namespace

std::string UsbBrickInfo::describe() const {
    std::string s = (bootLoader ? "NXT boot loader (SAM-BA) on USB bus " : "NXT on USB bus ") +
                    std::to_string(bus) + " device " + std::to_string(address);
    if (!serial.empty()) s += ", " + serial;
    return s;
}

std::vector<UsbBrickInfo> NxtUsbTransport::list() {
    Context c;
    libusb_device** devices = nullptr;
    const ssize_t n = libusb_get_device_list(c.ctx, &devices);
    if (n < 0) throw RigError("USB: cannot list devices (" + usbError(static_cast<int>(n)) + ")");
    std::vector<UsbBrickInfo> out;
    for (auto& [dev, info] : bricks(devices)) out.push_back(info);
    libusb_free_device_list(devices, 1);
    return out;
}

NxtUsbTransport::NxtUsbTransport(int bus, int address) {
    Context c;
    libusb_device** devices = nullptr;
    const ssize_t n = libusb_get_device_list(c.ctx, &devices);
    if (n < 0) throw RigError("USB: cannot list devices (" + usbError(static_cast<int>(n)) + ")");
    libusb_device* chosen = nullptr;
    bool sawBootLoader = false;
    for (auto& [dev, info] : bricks(devices)) {
        if (bus && (info.bus != bus || info.address != address)) continue;
        if (info.bootLoader) {
            sawBootLoader = true;
            continue;
        }
        chosen = dev;
        info_ = info;
        break;
    }
    if (!chosen) {
        libusb_free_device_list(devices, 1);
        if (sawBootLoader)
            throw RigError(
                "NXT: the brick on USB is in firmware-update mode (SAM-BA boot loader, "
                "03EB:6124), not running the LEGO firmware; flash or reboot it first");
        throw RigError(bus ? "NXT: no brick at USB bus " + std::to_string(bus) + " device " +
                                 std::to_string(address) + "; refresh the list"
                           : "NXT: no brick (0694:0002) on USB; plug it in and switch it on");
    }
    int r = libusb_open(chosen, &handle_);
    libusb_free_device_list(devices, 1);
    if (r != 0)
        throw RigError("NXT: cannot open " + info_.describe() + " (" + usbError(r) + ")" +
                       (r == LIBUSB_ERROR_ACCESS
                            ? "; install resources/udev/70-lego-nxt.rules or run as a member of "
                              "the plugdev group"
                            : ""));
    auto fail = [&](const std::string& step, int code) {
        libusb_close(handle_);
        handle_ = nullptr;
        throw RigError("NXT: " + step + " failed on " + info_.describe() + " (" + usbError(code) +
                       ")" +
                       (code == LIBUSB_ERROR_BUSY ? "; another program holds the brick" : ""));
    };
    r = libusb_detach_kernel_driver(handle_, 0);
    if (r != 0 && r != LIBUSB_ERROR_NOT_FOUND && r != LIBUSB_ERROR_NOT_SUPPORTED)
        fail("detaching the kernel driver", r);
    // The firmware needs a reset when a host connects a second time.
    r = libusb_reset_device(handle_);
    if (r != 0 && r != LIBUSB_ERROR_NOT_FOUND) fail("resetting the device", r);
    if ((r = libusb_set_configuration(handle_, 1)) != 0) fail("selecting configuration 1", r);
    if ((r = libusb_claim_interface(handle_, 0)) != 0) fail("claiming interface 0", r);
    unsigned char serial[64] = {};
    libusb_device_descriptor desc{};
    if (libusb_get_device_descriptor(libusb_get_device(handle_), &desc) == 0 &&
        desc.iSerialNumber &&
        libusb_get_string_descriptor_ascii(handle_, desc.iSerialNumber, serial, sizeof serial) > 0)
        info_.serial = reinterpret_cast<const char*>(serial);
    ctx_ = c.release();
}

NxtUsbTransport::~NxtUsbTransport() {
    if (handle_) {
        libusb_release_interface(handle_, 0);
        libusb_close(handle_);
    }
    if (ctx_) libusb_exit(ctx_);
}

void NxtUsbTransport::write(const Bytes& telegram) {
    if (telegram.size() > 64)
        throw TransportError(TransportError::Kind::Failed,
                             "NXT: a telegram of " + std::to_string(telegram.size()) +
                                 " bytes does not fit a 64-byte USB packet");
    int done = 0;
    const int r =
        libusb_bulk_transfer(handle_, kBulkOut, const_cast<unsigned char*>(telegram.data()),
                             static_cast<int>(telegram.size()), &done, kWriteTimeoutMs);
    if (r != 0) throw transferError(r, "request sent", describe());
    if (done != static_cast<int>(telegram.size()))
        throw TransportError(TransportError::Kind::Failed,
                             "NXT: only " + std::to_string(done) + " of " +
                                 std::to_string(telegram.size()) + " bytes were sent");
}

Bytes NxtUsbTransport::read(int timeoutMs) {
    Bytes buffer(64);
    int got = 0;
    const int r = libusb_bulk_transfer(handle_, kBulkIn, buffer.data(), 64, &got,
                                       static_cast<unsigned>(std::max(timeoutMs, 1)));
    if (r != 0) throw transferError(r, "reply", describe());
    buffer.resize(static_cast<std::size_t>(got));
    return buffer;
}

}  // namespace activetouch::nxt
