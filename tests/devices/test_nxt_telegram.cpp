// The NXT telegram codec against the byte-exact examples of docs/protocols.md §1, round trips, every
// status code, and the replies it must refuse.
#include <QtTest>

#include "devices/nxt/NxtTelegram.h"

using namespace activetouch::nxt;

namespace {
Bytes hex(const char* text) {
    Bytes b;
    const QByteArray raw = QByteArray::fromHex(QByteArray(text).replace(' ', ""));
    for (char c : raw) b.push_back(static_cast<std::uint8_t>(c));
    return b;
}
}  // namespace

class TestNxtTelegram : public QObject {
    Q_OBJECT
private slots:
    void requestsMatchTheDocumentedBytes() {
        QVERIFY(playTone(440, 1000, false) == hex("80 03 B8 01 E8 03"));
        QVERIFY(setOutputState(1, -100, MotorOn, RegulationIdle, -5, RunRunning, 0x04030201,
                               false) == hex("80 04 01 9C 01 00 FB 20 01 02 03 04"));
        QVERIFY(setInputMode(2, 0x01, 0x20, false) == hex("80 05 02 01 20"));
        QVERIFY(resetMotorPosition(1, true, true) == hex("00 0A 01 01"));
        QVERIFY(getBatteryLevel() == hex("00 0B"));
        QVERIFY(keepAlive() == hex("00 0D"));
        QVERIFY(getDeviceInfo() == hex("01 9B"));
        QVERIFY(getOutputState(0) == hex("00 06 00"));
        QVERIFY(getInputValues(3) == hex("00 07 03"));
        QVERIFY(!expectsReply(playTone(440, 1000, false)));  // never read after a 0x80
        QVERIFY(expectsReply(getBatteryLevel()));
        QVERIFY(expectsReply(getDeviceInfo()));
    }

    void repliesDecodeToTheDocumentedValues() {
        const OutputState o = decodeOutputState(
            decodeReply(hex("02 06 00 01 9C 01 00 FB 20 01020304 11121314 21222324 31323334"),
                        getOutputState(1)));
        QCOMPARE(o.port, 1);
        QCOMPARE(o.power, -100);
        QCOMPARE(o.mode, MotorOn);
        QCOMPARE(o.turnRatio, -5);
        QCOMPARE(o.runState, RunRunning);
        QCOMPARE(o.tachoLimit, 0x04030201u);
        QCOMPARE(o.tachoCount, 0x14131211);
        QCOMPARE(o.blockTachoCount, 0x24232221);
        QCOMPARE(o.rotationCount, 0x34333231);
        const InputValues in = decodeInputValues(
            decodeReply(hex("02 07 00 02 01 00 01 20 0102 1112 2122 3132"), getInputValues(2)));
        QCOMPARE(in.port, 2);
        QVERIFY(in.valid && !in.calibrated);
        QCOMPARE(in.type, 0x01);
        QCOMPARE(in.mode, 0x20);
        QCOMPARE(in.raw, 0x0201);
        QCOMPARE(in.normalized, 0x1211);
        QCOMPARE(in.scaled, 0x2221);
        QCOMPARE(in.calibratedValue, 0x3231);
        QCOMPARE(decodeBatteryMillivolts(decodeReply(hex("02 0B 00 28 23"), getBatteryLevel())),
                 9000);
        QCOMPARE(decodeReply(hex("02 0A 00"), resetMotorPosition(1, true, true)).status, 0);
        QCOMPARE(decodeKeepAliveSleepMs(decodeReply(hex("02 0D 00 60 EA 00 00"), keepAlive())),
                 60000u);
        const DeviceInfo d =
            decodeDeviceInfo(decodeReply(hex("02 9B 00 4E5854 000000000000000000000000 00 16 53 01 "
                                             "02 03 00 00000000 00 80 00 00"),
                                         getDeviceInfo()));
        QCOMPARE(QString::fromStdString(d.name), QString("NXT"));
        QCOMPARE(d.bluetoothAddress[1], 0x16);
        QCOMPARE(d.freeFlash, 0x8000u);
    }

    void roundTripsThroughAnEncodedReply() {
        for (int power : {-100, -37, 0, 55, 100}) {
            const Bytes request = setOutputState(2, power, MotorOn | Regulated, RegulationSpeed, 0,
                                                 RunRunning, 360, true);
            QCOMPARE(int(static_cast<std::int8_t>(request[3])), power);
            Bytes reply{0x02,       0x06,       0x00,       0x02,      request[3],
                        request[4], request[5], request[6], request[7]};
            for (int i = 0; i < 4; ++i) reply.push_back(request[8 + i]);
            for (int i = 0; i < 12; ++i) reply.push_back(0);
            const OutputState o = decodeOutputState(decodeReply(reply, getOutputState(2)));
            QCOMPARE(o.power, power);
            QCOMPARE(o.tachoLimit, 360u);
        }
    }

    void everyStatusCodeHasAName_data() {
        QTest::addColumn<int>("status");
        QTest::addColumn<QString>("name");
        QTest::newRow("0x00") << 0x00 << "ok";
        QTest::newRow("0x20") << 0x20 << "pending";
        QTest::newRow("0x40") << 0x40 << "mailbox queue is empty";
        for (int s = 0x81; s <= 0x93; ++s)
            QTest::newRow(qPrintable(QString("0x%1").arg(s, 2, 16))) << s << "file system error";
        QTest::newRow("0xBD") << 0xBD << "request failed";
        QTest::newRow("0xBE") << 0xBE << "unknown command opcode";
        QTest::newRow("0xBF") << 0xBF << "insane packet";
        QTest::newRow("0xC0") << 0xC0 << "out-of-range";
        QTest::newRow("0xDD") << 0xDD << "bus error";
        QTest::newRow("0xDE") << 0xDE << "no free memory";
        QTest::newRow("0xDF") << 0xDF << "not valid";
        QTest::newRow("0xE0") << 0xE0 << "not configured or busy";
        QTest::newRow("0xEC") << 0xEC << "no active program";
        QTest::newRow("0xED") << 0xED << "illegal size";
        QTest::newRow("0xEE") << 0xEE << "illegal mailbox";
        QTest::newRow("0xEF") << 0xEF << "invalid field";
        QTest::newRow("0xF0") << 0xF0 << "bad input or output";
        QTest::newRow("0xFB") << 0xFB << "insufficient memory";
        QTest::newRow("0xFF") << 0xFF << "bad arguments";
        QTest::newRow("unlisted") << 0x55 << "unknown status 0x55";
    }
    void everyStatusCodeHasAName() {
        QFETCH(int, status);
        QFETCH(QString, name);
        QVERIFY2(
            QString::fromStdString(statusName(static_cast<std::uint8_t>(status))).contains(name),
            qPrintable(name));
        if (status == 0) return;
        // A non-zero status is an error naming the opcode and the status.
        try {
            decodeReply(Bytes{0x02, 0x0B, static_cast<std::uint8_t>(status)}, getBatteryLevel());
            QFAIL("a non-zero status was accepted");
        } catch (const TelegramError& e) {
            QVERIFY(QString(e.what()).contains("0x0B"));
            QVERIFY(QString(e.what()).contains(name));
        }
    }

    void badRepliesAndRequestsAreRefused() {
        QVERIFY_THROWS_EXCEPTION(
            TelegramError, decodeReply(hex("02 06 00"), getBatteryLevel()));  // wrong echoed opcode
        QVERIFY_THROWS_EXCEPTION(
            TelegramError, decodeReply(hex("03 0B 00 28 23"), getBatteryLevel()));  // not a reply
        QVERIFY_THROWS_EXCEPTION(TelegramError,
                                 decodeReply(hex("02 0B"), getBatteryLevel()));  // too short
        QVERIFY_THROWS_EXCEPTION(TelegramError, decodeOutputState(decodeReply(hex("02 06 00 01 9C"),
                                                                              getOutputState(1))));
        QVERIFY_THROWS_EXCEPTION(TelegramError, setOutputState(3, 50, MotorOn, 0, 0, RunRunning, 0,
                                                               true));  // port 3 is no motor
        QVERIFY_THROWS_EXCEPTION(TelegramError,
                                 setOutputState(0, 101, MotorOn, 0, 0, RunRunning, 0, true));
        QVERIFY_THROWS_EXCEPTION(TelegramError, setInputMode(4, 1, 0x20, false));
        QVERIFY(setOutputState(0xFF, 0, Brake, 0, 0, RunIdle, 0, false).size() ==
                12);  // all motors
    }
};

QTEST_APPLESS_MAIN(TestNxtTelegram)
#include "test_nxt_telegram.moc"
