// The YARP fingertip client through QTcpSocket on loopback, against the emulated name server and
// skin publisher: the emulator's bytes against real captures, text carrier ('d', 'do', 'D', with
// and without envelope), binary carrier (Vector and Bottle layouts, both tags, with and without a
// Stamp), compensation of a raw stream, and every stream fault.
#include <QTcpSocket>
#include <QtTest>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <climits>
#include <cstring>

#include "devices/emulators/FakeYarp.h"
#include "devices/yarp/YarpFingertip.h"

using namespace activetouch;
using namespace activetouch::yarp;
using activetouch::emu::FakeYarp;
using activetouch::emu::FakeYarpSettings;

namespace {

std::vector<double> ramp() {
    std::vector<double> v(12);
    for (int i = 0; i < 12; ++i) v[i] = 10.0 * i + 1.5;
    return v;
}

YarpFingertipSettings clientFor(const FakeYarp& yarp, const FakeYarpSettings& s) {
    YarpFingertipSettings c;
    c.nameServerHost = "127.0.0.1";
    c.nameServerPort = yarp.nameServerPort();
    c.port = s.portName;
    c.finger = static_cast<Finger>(s.fingerOffset);
    c.connectTimeoutMs = 1000;
    return c;
}

/// The fault `tip` ends in within 100 waits of 100 ms each; empty if it is still reading.
QString faultOf(YarpFingertip& tip) {
    double frame[12];
    try {
        for (int i = 0; i < 100; ++i) tip.waitFrame(tip.framesReceived(), 100, frame);
    } catch (const RigError& e) {
        return QString::fromUtf8(e.what());
    }
    return {};
}

/// An emulated publisher of ramp() at `rate_hz` with a client connected to it.
struct Connected {
    FakeYarpSettings settings;
    FakeYarp yarp;
    YarpFingertip tip;
    explicit Connected(double rate_hz)
        : settings(withRate(rate_hz)),
          yarp(settings, ramp),
          tip((yarp.start(), clientFor(yarp, settings))) {
        tip.connect();
    }
    static FakeYarpSettings withRate(double rate_hz) {
        FakeYarpSettings s;
        s.rate_hz = rate_hz;
        return s;
    }
};

}  // namespace

class TestYarpFingertip : public QObject {
    Q_OBJECT
private slots:
    void readsTheChosenFingertipOverTheTextCarrier_data() {
        QTest::addColumn<QString>("header");
        QTest::addColumn<bool>("envelope");
        QTest::addColumn<int>("finger");
        QTest::newRow("d, index") << "d" << false << 0;
        QTest::newRow("do with envelope, middle") << "do" << true << 12;
        QTest::newRow("D, thumb") << "D" << false << 48;
    }
    void readsTheChosenFingertipOverTheTextCarrier() {
        QFETCH(QString, header);
        QFETCH(bool, envelope);
        QFETCH(int, finger);
        FakeYarpSettings s;
        s.header = header.toStdString();
        s.envelope = envelope;
        s.fingerOffset = finger;
        s.rate_hz = 200;
        FakeYarp yarp(s, ramp);
        yarp.start();
        std::vector<std::string> log;
        auto c = clientFor(yarp, s);
        c.binaryCarrier = false;
        YarpFingertip tip(
            c, [&](const std::string& d, const std::string& t) { log.push_back(d + t); });
        tip.connect();
        double frame[12];
        std::uint64_t seq = 0;
        for (int i = 0; i < 20; ++i) {
            const std::uint64_t next = tip.waitFrame(seq, 1000, frame);
            QVERIFY(next > seq);
            seq = next;
        }
        for (int i = 0; i < 12; ++i) QCOMPARE(frame[i], ramp()[i]);
        QCOMPARE(tip.badMessages(), 0);
        QVERIFY(std::find(log.begin(), log.end(), "->CONNACK extern") != log.end());
        QVERIFY(std::find(log.begin(), log.end(), "<-Welcome extern") != log.end());
    }

    void readsTheBinaryCarrierInEveryLayout_data() {
        QTest::addColumn<bool>("bottle");
        QTest::addColumn<int>("tag");
        QTest::addColumn<bool>("floats");
        QTest::addColumn<bool>("stamp");
        QTest::newRow("Vector 0x114 (skinManager)") << false << 0x114 << false << false;
        QTest::newRow("Vector 0x114 with a Stamp") << false << 0x114 << false << true;
        QTest::newRow("Bottle 0x114") << true << 0x114 << false << false;
        QTest::newRow("Bottle 0x114 with a Stamp") << true << 0x114 << false << true;
        QTest::newRow("Vector 0x10A doubles (YARP 3)") << false << 0x10A << false << false;
        QTest::newRow("Vector 0x10A floats (YARP 4)") << false << 0x10A << true << false;
    }
    void readsTheBinaryCarrierInEveryLayout() {
        QFETCH(bool, bottle);
        QFETCH(int, tag);
        QFETCH(bool, floats);
        QFETCH(bool, stamp);
        FakeYarpSettings s;
        s.binaryLayout = bottle ? BinaryLayout::Bottle : BinaryLayout::Vector;
        s.binaryTag = static_cast<std::uint32_t>(tag);
        s.binaryFloats = floats;
        s.envelope = stamp;
        s.rate_hz = 200;
        FakeYarp yarp(s, ramp);
        yarp.start();
        std::vector<std::string> log;
        YarpFingertip tip(clientFor(yarp, s), [&](const std::string& d, const std::string& t) {
            log.push_back(d + t);
        });
        QVERIFY(tip.settings().binaryCarrier);  // the default
        tip.connect();
        double frame[12];
        QVERIFY(tip.waitFrame(0, 1000, frame) > 0);
        QVERIFY(tip.waitFrame(1, 1000, frame) > 1);
        for (int i = 0; i < 12; ++i) QCOMPARE(frame[i], ramp()[i]);
        QCOMPARE(tip.badMessages(), 0);
        // A Stamp arrives as "count time"; without one there is no envelope.
        const std::string envelope = tip.lastEnvelope();
        QCOMPARE(envelope.empty(), !stamp);
        if (stamp) QVERIFY2(envelope.find(" 17956") != std::string::npos, envelope.c_str());
        QVERIFY(std::find(log.begin(), log.end(),
                          "<-header reply, port " + std::to_string(yarp.dataPort())) != log.end());
    }

    void theEmulatorSpeaksTheCapturedBytes() {
        // The bytes a real YARP 4 port sent (docs/protocols.md §3): the reply to the connection
        // header, then each frame's start, for skinManager's Vector and for a Bottle.
        const QByteArray vectorStart = QByteArray::fromHex(
            "59410a0000005250 0301 ffffffffffffffff 08000000 08000000 00060000 00000000"
            " 00000000 7e440001 14010000 c0000000");
        const QByteArray bottleStart = QByteArray::fromHex(
            "59410a0000005250 0201 ffffffffffffffff 08000000 08060000 00000000"
            " 00000000 7e440001 14010000 c0000000");
        for (const bool bottle : {false, true}) {
            FakeYarpSettings s;
            s.binaryLayout = bottle ? BinaryLayout::Bottle : BinaryLayout::Vector;
            s.rate_hz = 200;
            FakeYarp yarp(s, ramp);
            yarp.start();
            QTcpSocket raw;
            raw.connectToHost("127.0.0.1", static_cast<quint16>(yarp.dataPort()));
            QVERIFY(raw.waitForConnected(2000));
            raw.write(QByteArray::fromHex("594164"
                                          "1e00005250 14000000") +
                      QByteArray("/activetouch/reader", 20));
            raw.write(QByteArray::fromHex(
                "59410a0000005250 0101 ffffffffffffffff 08000000 00000000 00000000 7e720001"));
            QByteArray got;
            const std::size_t frameBytes = (bottle ? 18 + 12 : 18 + 16) + 8 + 8 + 192 * 8;
            while (got.size() < static_cast<qsizetype>(8 + frameBytes) &&
                   raw.waitForReadyRead(2000))
                got += raw.readAll();
            QVERIFY(got.size() >= static_cast<qsizetype>(8 + frameBytes));
            QByteArray reply(8, 0);
            reply[0] = 'Y';
            reply[1] = 'A';
            const std::int32_t port = yarp.dataPort();
            std::memcpy(reply.data() + 2, &port, 4);
            reply[6] = 'R';
            reply[7] = 'P';
            QCOMPARE(got.left(8).toHex(' '), reply.toHex(' '));
            const QByteArray frame = got.mid(8, static_cast<qsizetype>(frameBytes));
            const QByteArray start = bottle ? bottleStart : vectorStart;
            QCOMPARE(frame.left(start.size()).toHex(' '), start.toHex(' '));
            // The whole frame: the hand vector's doubles, little-endian, after the start.
            std::vector<double> hand(192, 0.0);
            for (int i = 0; i < 12; ++i) hand[static_cast<std::size_t>(i)] = ramp()[i];
            QCOMPARE(frame.mid(start.size()),
                     QByteArray(reinterpret_cast<const char*>(hand.data()), 192 * 8));
        }
    }

    void aBareReverseRequestNeverStreams() {
        // As on a real port: "~r\n" instead of a message leaves the connection an input of the
        // port; the header is answered but no frame ever comes.
        FakeYarpSettings s;
        s.rate_hz = 200;
        FakeYarp yarp(s, ramp);
        yarp.start();
        QTcpSocket raw;
        raw.connectToHost("127.0.0.1", static_cast<quint16>(yarp.dataPort()));
        QVERIFY(raw.waitForConnected(2000));
        raw.write(QByteArray::fromStdString(binaryConnectionHeader("/probe") + "~r\n"));
        QByteArray got;
        while (raw.waitForReadyRead(300)) got += raw.readAll();
        QCOMPARE(got.size(), qsizetype(8));  // the header reply, nothing more
        QCOMPARE(yarp.readers(), 0);
    }

    void framesArriveAtTheStreamRate() {
        FakeYarpSettings s;  // 50 Hz, as the skin
        FakeYarp yarp(s, ramp);
        yarp.start();
        YarpFingertip tip(clientFor(yarp, s));
        tip.connect();
        double frame[12];
        std::uint64_t seq = tip.waitFrame(0, 1000, frame);
        int frames = 0;
        const auto t0 = std::chrono::steady_clock::now();
        while (frames < 25) {
            const auto next = tip.waitFrame(seq, 1000, frame);
            QVERIFY(next == seq + 1);  // every frame, none skipped
            seq = next;
            ++frames;
        }
        const double s25 =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        qInfo("25 frames in %.3f s (50 Hz: 0.5 s)", s25);
        // Each frame the reader hands out is one the stream sent: none made up or handed out twice.
        QVERIFY2(
            seq <= yarp.framesSent(),
            qPrintable(QString("frame %1 handed out, %2 sent").arg(seq).arg(yarp.framesSent())));
    }

    void aRawStreamIsCompensatedAfterCalibration() {
        std::atomic<bool> touching{false};
        FakeYarpSettings s;
        s.rate_hz = 500;
        FakeYarp yarp(s, [&] {
            std::vector<double> raw(12, 235.0);
            if (touching) raw[3] = 135.0;  // lower = more pressure
            return raw;
        });
        yarp.start();
        auto c = clientFor(yarp, s);
        c.compensateRaw = true;
        c.calibrationFrames = 20;
        YarpFingertip tip(c);
        tip.connect();
        double frame[12];
        QVERIFY(tip.waitFrame(0, 2000, frame) > 0);  // the first frame after calibration
        for (double v : frame) QCOMPARE(v, 0.0);
        touching = true;
        // Frames sent before the touch may still be on their way: read on until the touch shows,
        // for at most a second of the 500 Hz stream.
        std::uint64_t seq = tip.waitFrame(0, 1000, frame);
        for (int n = 0; n < 500 && seq > 0 && frame[3] == 0.0; ++n)
            seq = tip.waitFrame(seq, 1000, frame);
        QVERIFY(seq > 0);
        QVERIFY2(frame[3] > 95.0 && frame[3] <= 100.0, qPrintable(QString::number(frame[3])));
        QCOMPARE(frame[0], 0.0);
    }

    void aNameServerThatIsDownIsNamed() {
        FakeYarpSettings s;
        FakeYarp yarp(s, ramp);
        yarp.start();
        auto c = clientFor(yarp, s);
        yarp.setNameServerUp(false);
        QTest::qWait(20);
        YarpFingertip tip(c);
        try {
            tip.connect();
            QFAIL("connected through a name server that is down");
        } catch (const RigError& e) {
            const std::string m = e.what();
            QVERIFY2(m.find("name server at 127.0.0.1:" + std::to_string(c.nameServerPort) +
                            " (set for the rig) cannot be reached") != std::string::npos,
                     m.c_str());
        }
    }

    void anUnknownPortIsNamed() {
        FakeYarpSettings s;
        FakeYarp yarp(s, ramp);
        yarp.start();
        yarp.setPortRegistered(false);
        YarpFingertip tip(clientFor(yarp, s));
        try {
            tip.connect();
            QFAIL("connected to an unknown port");
        } catch (const RigError& e) {
            QVERIFY(std::string(e.what()).find("/icub/skin/right_hand_comp is not registered") !=
                    std::string::npos);
        }
    }

    void aStalledStreamTimesOutAndRecovers() {
        Connected c(200);
        auto& [s, yarp, tip] = c;
        double frame[12];
        std::uint64_t seq = tip.waitFrame(0, 1000, frame);
        QVERIFY(seq > 0);
        yarp.setStalled(true);
        QTest::qWait(50);
        seq = std::max(seq, tip.framesReceived());
        QCOMPARE(tip.waitFrame(seq, 200, frame), std::uint64_t(0));  // bounded, no frame
        QVERIFY(tip.secondsSinceFrame() >= 0.2);
        // Silent past its report bound, the stream is reported stalled; frames clear it.
        QTRY_VERIFY_WITH_TIMEOUT(tip.stalled(), 5000);
        QVERIFY2(tip.lastProblem().find("stalled") != std::string::npos, tip.lastProblem().c_str());
        yarp.setStalled(false);
        QVERIFY(tip.waitFrame(seq, 1000, frame) > seq);
        QTRY_VERIFY_WITH_TIMEOUT(!tip.stalled(), 5000);
    }

    void malformedLinesAndWrongSizesAreSkippedAndCounted() {
        Connected c(200);
        auto& [s, yarp, tip] = c;
        double frame[12];
        std::uint64_t seq = tip.waitFrame(0, 1000, frame);
        yarp.injectMalformedLine();
        QTest::qWait(30);
        yarp.injectWrongSize(100);
        QTest::qWait(30);
        seq = tip.waitFrame(tip.framesReceived(), 1000, frame);
        QVERIFY(seq > 0);
        QCOMPARE(tip.badMessages(), 2);
        QVERIFY2(tip.lastProblem().find("100") != std::string::npos, tip.lastProblem().c_str());
        for (int i = 0; i < 12; ++i) QCOMPARE(frame[i], ramp()[i]);
    }

    void aStreamOfGarbageFailsTheSensor() {
        FakeYarpSettings s;
        s.rate_hz = 500;
        FakeYarp yarp(s, ramp);
        yarp.start();
        auto c = clientFor(yarp, s);
        c.finger = Finger::Index;
        YarpFingertip tip(c);
        tip.connect();
        double frame[12];
        QVERIFY(tip.waitFrame(0, 1000, frame) > 0);
        yarp.setWrongSize(7);
        const QString fault = faultOf(tip);
        QVERIFY2(!fault.isEmpty(), "a stream of wrong-size vectors did not fail the sensor");
        QVERIFY2(fault.contains("could not be read"), qPrintable(fault));
    }

    void hostileFramingEndsInAFault_data() {
        QTest::addColumn<bool>("binary");
        QTest::addColumn<QByteArray>("bytes");
        QTest::addColumn<QString>("says");
        auto binaryHeader = [](std::vector<std::int32_t> lengths) {
            // A message index: YA 10 RP, the data and reply block counts, eight 0xFF, lengths.
            QByteArray m = QByteArray::fromHex("59410a0000005250");
            m.append(static_cast<char>(lengths.size()));
            m.append('\1');
            m.append(8, '\xFF');
            for (auto l : lengths) m.append(reinterpret_cast<const char*>(&l), 4);
            const std::int32_t reply = 0;
            m.append(reinterpret_cast<const char*>(&reply), 4);
            return m;
        };
        QTest::newRow("a negative block length")
            << true << binaryHeader({-1000, 100}) << "a block of -1000 bytes";
        QTest::newRow("an oversized block length")
            << true << binaryHeader({8, 5 << 20}) << "a block of 5242880 bytes";
        QTest::newRow("a block length of INT32_MAX")
            << true << binaryHeader({8, 2147483647}) << "a block of 2147483647 bytes";
        QTest::newRow("the port closing (~q)")
            << true << QByteArray::fromStdString(binaryMessage({portCommandWithText("q")}))
            << "closed its port";
        QTest::newRow("a text line without end")
            << false << QByteArray("d\n") + QByteArray(200000, '7') << "a text line runs past";
    }
    void hostileFramingEndsInAFault() {
        // Lengths the stream claims are checked before they are trusted: the fingertip faults
        // with a message, every wait reports it, and disconnect() returns.
        QFETCH(bool, binary);
        QFETCH(QByteArray, bytes);
        QFETCH(QString, says);
        FakeYarpSettings s;
        s.rate_hz = 200;
        FakeYarp yarp(s, ramp);
        yarp.start();
        auto c = clientFor(yarp, s);
        c.binaryCarrier = binary;
        YarpFingertip tip(c);
        tip.connect();
        double frame[12];
        QVERIFY(tip.waitFrame(0, 1000, frame) > 0);
        yarp.injectRawBytes(bytes.toStdString());
        const QString fault = faultOf(tip);
        QVERIFY2(!fault.isEmpty(), "the hostile framing did not fault the fingertip");
        QVERIFY2(fault.contains(says) && fault.contains(s.portName.c_str()), qPrintable(fault));
        tip.disconnect();  // returns: a hang fails the test at ctest's limit
        QTRY_COMPARE_WITH_TIMEOUT(yarp.readers(), 0, 5000);
    }

    void aPublisherThatNeverStreamsFailsTheConnect_data() {
        QTest::addColumn<bool>("binary");
        QTest::newRow("binary") << true;
        QTest::newRow("text") << false;
    }
    void aPublisherThatNeverStreamsFailsTheConnect() {
        // The port accepts the reader and answers every handshake, then sends nothing: connect()
        // ends in a fault naming its bound, not in "connected".
        QFETCH(bool, binary);
        FakeYarpSettings s;
        FakeYarp yarp(s, ramp);
        yarp.start();
        yarp.setStalled(true);
        auto c = clientFor(yarp, s);
        c.binaryCarrier = binary;
        c.firstFrameTimeoutMs = 400;
        YarpFingertip tip(c);
        const auto t0 = std::chrono::steady_clock::now();
        try {
            tip.connect();
            QFAIL("connected to a port that never streams");
        } catch (const RigError& e) {
            qInfo("faulted after %.3f s (bound 0.4 s)",
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
            QVERIFY2(QString(e.what()).contains("no frame came within 400 ms") &&
                         QString(e.what()).contains(s.portName.c_str()),
                     e.what());
        }
        QVERIFY(!tip.connected());
        QTRY_COMPARE_WITH_TIMEOUT(yarp.readers(), 0, 5000);  // the connection is closed
    }

    void aPortThatClosesIsReported() {
        Connected c(100);
        double frame[12];
        QVERIFY(c.tip.waitFrame(0, 1000, frame) > 0);
        c.yarp.closePort();
        const QString fault = faultOf(c.tip);
        QVERIFY2(!fault.isEmpty(), "a closed port went unreported");
        QVERIFY2(fault.contains("the publisher closed its port"), qPrintable(fault));
    }

    void aStreamThatDropsFaultsTheFingertip() {
        Connected c(100);
        double frame[12];
        QVERIFY(c.tip.waitFrame(0, 1000, frame) > 0);
        c.yarp.dropReaders();
        const QString fault = faultOf(c.tip);
        QVERIFY2(!fault.isEmpty(), "a dropped stream went unreported");
        QVERIFY2(fault.contains("closed the connection"), qPrintable(fault));
        c.tip.disconnect();
    }

    void disconnectReturnsPromptly() {
        FakeYarpSettings s;
        FakeYarp yarp(s, ramp);
        yarp.start();
        YarpFingertip tip(clientFor(yarp, s));
        tip.connect();
        QTRY_COMPARE_WITH_TIMEOUT(yarp.readers(), 1, 5000);
        const auto t0 = std::chrono::steady_clock::now();
        tip.disconnect();  // returns: a hang fails the test at ctest's limit
        qInfo("disconnected in %.3f s",
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
        QTRY_COMPARE_WITH_TIMEOUT(yarp.readers(), 0,
                                  5000);  // the connection is closed, not left open
        double frame[12];
        QVERIFY_THROWS_EXCEPTION(RigError, tip.waitFrame(0, 10, frame));
    }
};

QTEST_GUILESS_MAIN(TestYarpFingertip)
#include "test_yarp_fingertip.moc"
