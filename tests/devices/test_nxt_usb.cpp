// The NXT's libusb path against a mocked USB device (umockdev, see support/MockedUsbBrick.h):
// listing, opening, telegrams both ways, timeouts, faults, unplug and the boot loader.
// Runs under umockdev-wrapper (see tests/CMakeLists.txt).
// clang-format off
#include "support/MockedUsbBrick.h"  // first: GLib before Qt
// clang-format on

#include <QtTest>
#include <chrono>

#include "devices/nxt/NxtBrick.h"
#include "devices/nxt/NxtUsbTransport.h"

using namespace activetouch;
using namespace activetouch::nxt;
using activetouch::emu::FakeNxtBrick;
using namespace activetouch::test::usb;

class TestNxtUsb : public QObject {
    Q_OBJECT
private slots:
    void initTestCase() { QVERIFY2(umockdevPreloaded(), "run this test through umockdev-wrapper"); }

    void findsOpensAndTalksToTheBrickThroughLibusb() {
        Testbed t;
        t.addDevice(2, kNxtDescriptors, true);
        const auto found = NxtUsbTransport::list();
        QCOMPARE(int(found.size()), 1);
        QCOMPARE(found[0].bus, 1);
        QCOMPARE(found[0].address, 2);
        QVERIFY(!found[0].bootLoader);

        NxtBrick brick(std::make_unique<NxtUsbTransport>(), 300);
        QVERIFY(brick.describe().find("NXT on USB bus 1 device 2") != std::string::npos);
        QCOMPARE(int(brick.batteryMillivolts()), 8150);
        QCOMPARE(brick.keepAlive(), std::uint32_t(600000));
        brick.call(playTone(440, 100, false));  // no reply: nothing is read
        brick.call(
            setOutputState(0, 50, MotorOn | Regulated, RegulationSpeed, 0, RunRunning, 90, true));
        QTest::qWait(300);
        const OutputState s = brick.outputState(0);
        QVERIFY2(s.rotationCount >= 90 && s.rotationCount < 100,
                 qPrintable(QString::number(s.rotationCount)));
        QCOMPARE(int(s.runState), int(RunIdle));  // stopped at the tacho limit
        QVERIFY(t.mocked.submitted >= 8);
    }

    void aSilentBrickTimesOutAndRecovers() {
        Testbed t;
        t.addDevice(2, kNxtDescriptors, true);
        NxtBrick brick(std::make_unique<NxtUsbTransport>(), 200);
        t.mocked.brick.injectFault(FakeNxtBrick::Fault::NoReply);
        const auto t0 = std::chrono::steady_clock::now();
        try {
            brick.batteryMillivolts();
            QFAIL("a silent brick did not time out");
        } catch (const TransportError& e) {
            QCOMPARE(int(e.kind()), int(TransportError::Kind::Timeout));
        }
        qInfo("a silent brick timed out in %.3f s (timeout 200 ms)",
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
        QCOMPARE(int(brick.batteryMillivolts()), 8150);  // in step again
    }

    void aWrongEchoedOpcodeAndAStatusAreRefused() {
        Testbed t;
        t.addDevice(2, kNxtDescriptors, true);
        NxtBrick brick(std::make_unique<NxtUsbTransport>(), 300);
        t.mocked.brick.injectFault(FakeNxtBrick::Fault::WrongOpcode);
        QVERIFY_THROWS_EXCEPTION(RigError, brick.batteryMillivolts());
        t.mocked.brick.injectFault(FakeNxtBrick::Fault::Status, 0, 0, 0xC0);
        try {
            brick.batteryMillivolts();
            QFAIL("a non-zero status was accepted");
        } catch (const RigError& e) {
            QVERIFY2(std::string(e.what()).find("status 0xC0") != std::string::npos, e.what());
        }
    }

    void anUnpluggedBrickIsReportedAsGone() {
        Testbed t;
        t.addDevice(2, kNxtDescriptors, true);
        NxtBrick brick(std::make_unique<NxtUsbTransport>(), 300);
        t.mocked.brick.injectFault(FakeNxtBrick::Fault::Unplug);
        try {
            brick.batteryMillivolts();
            QFAIL("an unplugged brick was not reported");
        } catch (const TransportError& e) {
            QCOMPARE(int(e.kind()), int(TransportError::Kind::Unplugged));
            QVERIFY(std::string(e.what()).find("gone") != std::string::npos);
        }
        QVERIFY(brick.unplugged());
        QVERIFY_THROWS_EXCEPTION(TransportError, brick.keepAlive());
    }

    void theBootLoaderIsRefusedByName() {
        Testbed t;
        t.addDevice(3, kSambaDescriptors, true);
        const auto found = NxtUsbTransport::list();
        QCOMPARE(int(found.size()), 1);
        QVERIFY(found[0].bootLoader);
        try {
            NxtUsbTransport usb;
            QFAIL("the boot loader was opened");
        } catch (const RigError& e) {
            QVERIFY(std::string(e.what()).find("SAM-BA boot loader") != std::string::npos);
        }
    }

    void noBrickIsAClearError() {
        Testbed t;
        try {
            NxtUsbTransport usb;
            QFAIL("opened a brick that is not there");
        } catch (const RigError& e) {
            QVERIFY(std::string(e.what()).find("no brick (0694:0002)") != std::string::npos);
        }
    }
};

QTEST_GUILESS_MAIN(TestNxtUsb)
#include "test_nxt_usb.moc"
