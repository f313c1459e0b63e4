#pragma once
// A mocked NXT on a mocked USB bus (umockdev): the device and configuration descriptors of
// docs/protocols.md §1 in a mocked sysfs, and the usbdevfs ioctls that libusb issues (claim, reset,
// bulk URBs on 0x01 / 0x82, discards on timeout) answered by an emulated brick. Tests using it run
// under umockdev-wrapper (see tests/CMakeLists.txt). Include it before any Qt header: GLib's
// headers use names that Qt defines as keywords.
#include <linux/usbdevice_fs.h>
#include <sys/ioctl.h>
#include <umockdev.h>

#include <QString>
#include <QtTest>
#include <algorithm>
#include <cerrno>
#include <cstring>
#include <deque>
#include <mutex>

#include "devices/emulators/FakeNxtBrick.h"

namespace activetouch::test::usb {

using activetouch::emu::FakeNxtBrick;
using activetouch::nxt::Bytes;

constexpr const char* kNxtDescriptors =
    "12010002000000089406020000000000010109022000010100c0000904000002ffffff000705010240000007058202"
    "400000";
constexpr const char* kSambaDescriptors =
    "1201000202000008eb032461100100000001"
    "09022000010100c0000904000002ffffff000705010240000007058202400000";

/// Whether umockdev's preload library is in place (the test was started through
/// umockdev-wrapper); without it libusb would see the machine's real buses.
inline bool umockdevPreloaded() {
    return qEnvironmentVariable("LD_PRELOAD").contains("umockdev");
}

/// The usbdevfs side of a mocked NXT: OUT URBs go to the emulated brick, IN URBs get its replies.
struct MockedBrick {
    explicit MockedBrick(FakeNxtBrick& b) : brick(b) {}
    FakeNxtBrick& brick;
    std::mutex mutex;
    std::deque<UMockdevIoctlData*> done, inFlight;  // URBs (referenced)
    std::deque<Bytes> replies;
    bool gone = false;
    int submitted = 0;

    static gboolean onIoctl(UMockdevIoctlBase*, UMockdevIoctlClient* client, gpointer self) {
        return static_cast<MockedBrick*>(self)->handle(client);
    }

    void finishIn(UMockdevIoctlData* urbData, const Bytes& reply) {
        auto* urb = reinterpret_cast<usbdevfs_urb*>(urbData->data);
        const int n = std::min<int>(urb->buffer_length, static_cast<int>(reply.size()));
        std::memcpy(urb->buffer, reply.data(), static_cast<std::size_t>(n));
        urb->actual_length = n;
        urb->status = 0;
    }

    /// Answers a reap with `urbData` (and lets go of it).
    static gboolean reaped(UMockdevIoctlClient* client, UMockdevIoctlData* arg,
                           UMockdevIoctlData* urbData) {
        UMockdevIoctlData* ptr = umockdev_ioctl_data_resolve(arg, 0, sizeof(gpointer), nullptr);
        umockdev_ioctl_data_set_ptr(ptr, 0, urbData);
        umockdev_ioctl_data_unref(ptr);
        umockdev_ioctl_data_unref(urbData);
        umockdev_ioctl_client_complete(client, 0, 0);
        return TRUE;
    }

    gboolean handle(UMockdevIoctlClient* client) {
        std::lock_guard lock(mutex);
        const gulong request = umockdev_ioctl_client_get_request(client);
        UMockdevIoctlData* arg = umockdev_ioctl_client_get_arg(client);
        if (gone) {
            // Unplugged: as the kernel does, URBs in flight complete with -ESHUTDOWN and every
            // new request fails with ENODEV.
            const bool reap = request == USBDEVFS_REAPURB || request == USBDEVFS_REAPURBNDELAY;
            for (auto* list : {&done, &inFlight}) {
                if (!reap || list->empty()) continue;
                UMockdevIoctlData* urbData = list->front();
                list->pop_front();
                auto* urb = reinterpret_cast<usbdevfs_urb*>(urbData->data);
                urb->status = -ESHUTDOWN;
                urb->actual_length = 0;
                return reaped(client, arg, urbData);
            }
            umockdev_ioctl_client_complete(client, -1, ENODEV);
            return TRUE;
        }
        switch (request) {
            case USBDEVFS_GET_CAPABILITIES: {
                UMockdevIoctlData* d =
                    umockdev_ioctl_data_resolve(arg, 0, sizeof(guint32), nullptr);
                *reinterpret_cast<guint32*>(d->data) =
                    USBDEVFS_CAP_BULK_CONTINUATION | USBDEVFS_CAP_NO_PACKET_SIZE_LIM;
                umockdev_ioctl_data_unref(d);
                umockdev_ioctl_client_complete(client, 0, 0);
                return TRUE;
            }
            case USBDEVFS_GETDRIVER:
            case USBDEVFS_IOCTL:  // no kernel driver bound: nothing to detach
                umockdev_ioctl_client_complete(client, -1, ENODATA);
                return TRUE;
            case USBDEVFS_CLAIMINTERFACE:
            case USBDEVFS_RELEASEINTERFACE:
            case USBDEVFS_SETCONFIGURATION:
            case USBDEVFS_RESET:
            case USBDEVFS_CLEAR_HALT:
            case USBDEVFS_RESETEP:
                umockdev_ioctl_client_complete(client, 0, 0);
                return TRUE;
            case USBDEVFS_SUBMITURB: {
                UMockdevIoctlData* urbData =
                    umockdev_ioctl_data_resolve(arg, 0, sizeof(usbdevfs_urb), nullptr);
                auto* urb = reinterpret_cast<usbdevfs_urb*>(urbData->data);
                UMockdevIoctlData* buffer =
                    umockdev_ioctl_data_resolve(urbData, G_STRUCT_OFFSET(usbdevfs_urb, buffer),
                                                static_cast<gsize>(urb->buffer_length), nullptr);
                umockdev_ioctl_data_unref(buffer);  // held by its parent
                ++submitted;
                if (urb->type == USBDEVFS_URB_TYPE_BULK && urb->endpoint == 0x01) {
                    const auto* p = static_cast<const std::uint8_t*>(urb->buffer);
                    if (auto r = brick.handle(Bytes(p, p + urb->buffer_length)))
                        replies.push_back(*r);
                    urb->actual_length = urb->buffer_length;
                    urb->status = 0;
                    done.push_back(urbData);
                    gone = brick.unplugged();  // the cable came out with this request
                } else if (urb->type == USBDEVFS_URB_TYPE_BULK && urb->endpoint == 0x82) {
                    inFlight.push_back(urbData);
                } else {
                    // Control requests (string descriptors): the mocked brick stalls them.
                    urb->actual_length = 0;
                    urb->status = -EPIPE;
                    done.push_back(urbData);
                }
                umockdev_ioctl_client_complete(client, 0, 0);
                return TRUE;
            }
            case USBDEVFS_REAPURB:
            case USBDEVFS_REAPURBNDELAY: {
                while (!inFlight.empty() && !replies.empty()) {
                    finishIn(inFlight.front(), replies.front());
                    replies.pop_front();
                    done.push_back(inFlight.front());
                    inFlight.pop_front();
                }
                if (done.empty()) {
                    umockdev_ioctl_client_complete(client, -1, EAGAIN);
                    return TRUE;
                }
                UMockdevIoctlData* urbData = done.front();
                done.pop_front();
                return reaped(client, arg, urbData);
            }
            case USBDEVFS_DISCARDURB: {
                const gulong addr = reinterpret_cast<gulong>(*reinterpret_cast<void**>(arg->data));
                for (auto it = inFlight.begin(); it != inFlight.end(); ++it) {
                    if ((*it)->client_addr != addr) continue;
                    auto* urb = reinterpret_cast<usbdevfs_urb*>((*it)->data);
                    urb->status = -ENOENT;
                    urb->actual_length = 0;
                    done.push_back(*it);
                    inFlight.erase(it);
                    umockdev_ioctl_client_complete(client, 0, 0);
                    return TRUE;
                }
                umockdev_ioctl_client_complete(client, -1, EINVAL);
                return TRUE;
            }
            default:
                return FALSE;
        }
    }
};

/// A mocked sysfs and /dev with USB devices; the emulated ones answer through `mocked`, which
/// forwards to the brick given (or one of its own).
class Testbed {
    FakeNxtBrick own_;

public:
    UMockdevTestbed* bed = umockdev_testbed_new();
    UMockdevIoctlBase* handler = umockdev_ioctl_base_new();
    MockedBrick mocked;
    explicit Testbed(FakeNxtBrick* brick = nullptr) : mocked(brick ? *brick : own_) {
        g_signal_connect(handler, "handle-ioctl", G_CALLBACK(&MockedBrick::onIoctl), &mocked);
    }
    Testbed(const Testbed&) = delete;
    Testbed& operator=(const Testbed&) = delete;
    ~Testbed() {
        g_object_unref(handler);
        g_object_unref(bed);
    }
    void addDevice(int devnum, const char* descriptors, bool emulate) {
        const QString node = QString("/dev/bus/usb/001/%1").arg(devnum, 3, 10, QChar('0'));
        if (emulate)
            QVERIFY(
                umockdev_testbed_attach_ioctl(bed, node.toUtf8().constData(), handler, nullptr));
        const QString text = QString(
                                 "P: /devices/usb1/1-%1\n"
                                 "N: bus/usb/001/%2\n"
                                 "E: SUBSYSTEM=usb\nE: DRIVER=usb\nE: BUSNUM=001\n"
                                 "E: DEVNUM=%2\nE: DEVNAME=%3\nE: DEVTYPE=usb_device\n"
                                 "A: bConfigurationValue=1\\n\nA: busnum=1\\n\n"
                                 "A: devnum=%1\\n\nA: speed=12\\n\nH: descriptors=%4\n")
                                 .arg(devnum)
                                 .arg(devnum, 3, 10, QChar('0'))
                                 .arg(node)
                                 .arg(descriptors);
        QVERIFY(umockdev_testbed_add_from_string(bed, text.toUtf8().constData(), nullptr));
    }
};

}  // namespace activetouch::test::usb
