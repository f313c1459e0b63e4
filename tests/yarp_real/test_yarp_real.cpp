// The fingertip client against a real YARP: a real yarpserver on loopback (found, as a lab's
// client finds it, through the YARP conf file), and a real publisher of a skin port, as a
// yarp::sig::Vector (skinManager's type) and as a Bottle, with and without a Stamp; both
// carriers at 50 Hz, a killed publisher, a stalled one, one that never writes.
#include <QProcess>
#include <QTcpServer>
#include <QTcpSocket>
#include <QTemporaryDir>
#include <QtTest>
#include <chrono>
#include <memory>

#include "devices/yarp/YarpFingertip.h"

using namespace activetouch;
using namespace activetouch::yarp;

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

int freePort() {
    QTcpServer probe;
    probe.listen(QHostAddress::LocalHost, 0);
    return probe.serverPort();
}

/// The publisher's frame count in a Stamp envelope "count time".
long stampCount(const std::string& envelope) {
    return std::strtol(envelope.c_str(), nullptr, 10);
}

}  // namespace

class TestYarpReal : public QObject {
    Q_OBJECT
    QTemporaryDir home_;
    QProcess server_;
    std::vector<std::unique_ptr<QProcess>> publishers_;
    int serverPort_ = 0;
    int portCount_ = 0;

    QProcessEnvironment environment() const {
        QProcessEnvironment e = QProcessEnvironment::systemEnvironment();
        e.insert("YARP_CONFIG_HOME", home_.path());
        return e;
    }

    /// A publisher of a port of its own; waits until it says it publishes.
    QString startPublisher(const QString& layout, bool stamp, long stallAfter = -1) {
        const QString name = QString("/activetouch_test/skin%1/right_hand_comp").arg(++portCount_);
        auto p = std::make_unique<QProcess>();
        p->setProcessEnvironment(environment());
        p->setProcessChannelMode(QProcess::ForwardedErrorChannel);
        p->start(SKIN_PUBLISHER, {name, layout, stamp ? "stamp" : "plain", "50",
                                  QString::number(stallAfter)});
        if (!p->waitForStarted(5000)) return {};
        const auto t0 = Clock::now();
        QByteArray said;
        while (!said.contains("publishing") && secondsSince(t0) < 10 && p->waitForReadyRead(500))
            said += p->readAllStandardOutput();
        publishers_.push_back(std::move(p));
        return said.contains("publishing") ? name : QString();
    }

    YarpFingertipSettings settingsFor(const QString& port, bool binary, Finger finger) const {
        YarpFingertipSettings s;  // the name server from the conf file: host and port left unset
        s.port = port.toStdString();
        s.binaryCarrier = binary;
        s.finger = finger;
        return s;
    }

private slots:
    void initTestCase() {
        qInfo("YARP %s: %s", YARP_VERSION_SEEN, YARPSERVER);
        QVERIFY(home_.isValid());
        qputenv("YARP_CONFIG_HOME", home_.path().toUtf8());
        serverPort_ = freePort();
        QProcess conf;
        conf.setProcessEnvironment(environment());
        conf.start(YARP_TOOL, {"conf", "127.0.0.1", QString::number(serverPort_)});
        QVERIFY(conf.waitForFinished(10000));
        QVERIFY(QFile::exists(home_.filePath("yarp.conf")));
        server_.setProcessEnvironment(environment());
        server_.setWorkingDirectory(home_.path());
        server_.setProcessChannelMode(QProcess::ForwardedChannels);
        // --read: the address from the conf file, loopback kept (the port still has to be named).
        server_.start(YARPSERVER, {"--read", "--socket", QString::number(serverPort_)});
        QVERIFY(server_.waitForStarted(5000));
        const auto t0 = Clock::now();
        bool up = false;
        while (!up && secondsSince(t0) < 20) {
            QTcpSocket probe;
            probe.connectToHost("127.0.0.1", static_cast<quint16>(serverPort_));
            up = probe.waitForConnected(200);
            if (!up) QTest::qWait(200);
        }
        QVERIFY2(up, "yarpserver did not come up");
    }

    void cleanupTestCase() {
        for (auto& p : publishers_) {
            p->kill();
            p->waitForFinished(3000);
        }
        server_.terminate();
        if (!server_.waitForFinished(5000)) server_.kill();
    }

    void readsEveryPublisherOverBothCarriers_data() {
        QTest::addColumn<QString>("layout");
        QTest::addColumn<bool>("stamp");
        QTest::addColumn<bool>("binary");
        QTest::addColumn<int>("finger");
        QTest::newRow("Vector, binary, index") << "vector" << false << true << 0;
        QTest::newRow("Vector with Stamp, binary, thumb") << "vector" << true << true << 48;
        QTest::newRow("Bottle, binary, index") << "bottle" << false << true << 0;
        QTest::newRow("Bottle with Stamp, binary, middle") << "bottle" << true << true << 12;
        QTest::newRow("Bottle, text, index") << "bottle" << false << false << 0;
        QTest::newRow("Bottle with Stamp, text, thumb") << "bottle" << true << false << 48;
    }
    void readsEveryPublisherOverBothCarriers() {
        QFETCH(QString, layout);
        QFETCH(bool, stamp);
        QFETCH(bool, binary);
        QFETCH(int, finger);
        const QString port = startPublisher(layout, stamp);
        QVERIFY(!port.isEmpty());
        YarpFingertip tip(settingsFor(port, binary, static_cast<Finger>(finger)));
        tip.connect();
        QCOMPARE(tip.nameServer().source, home_.filePath("yarp.conf").toStdString());
        double frame[12];
        std::uint64_t seq = tip.waitFrame(0, 1000, frame);
        QVERIFY(seq > 0);
        const std::uint64_t first = seq;
        const long firstCount = stampCount(tip.lastEnvelope());
        const auto t0 = Clock::now();
        while (secondsSince(t0) < 2.0) {
            const std::uint64_t next = tip.waitFrame(seq, 1000, frame);
            QVERIFY2(next == seq + 1, "a frame went missing in the client");
            seq = next;
            for (int k = 0; k < 12; ++k) QCOMPARE(frame[k], 100.0 + finger + k);
        }
        const double rate = static_cast<double>(seq - first) / secondsSince(t0);
        const long lastCount = stampCount(tip.lastEnvelope());
        qInfo("%s: %.1f frames/s; values %g..%g; envelope '%s'", QTest::currentDataTag(), rate,
              frame[0], frame[11], tip.lastEnvelope().c_str());
        QCOMPARE(tip.badMessages(), 0);
        QCOMPARE(tip.lastEnvelope().empty(), !stamp);
        // With a Stamp, the publisher's own count says no frame was lost on the way.
        if (stamp) QCOMPARE(static_cast<std::uint64_t>(lastCount - firstCount), seq - first);
    }

    void aKilledPublisherIsReported_data() {
        QTest::addColumn<bool>("binary");
        QTest::newRow("binary") << true;
        QTest::newRow("text") << false;
    }
    void aKilledPublisherIsReported() {
        QFETCH(bool, binary);
        const QString port = startPublisher("bottle", false);
        QVERIFY(!port.isEmpty());
        YarpFingertip tip(settingsFor(port, binary, Finger::Index));
        tip.connect();
        double frame[12];
        QVERIFY(tip.waitFrame(0, 1000, frame) > 0);
        publishers_.back()->kill();
        const auto t0 = Clock::now();
        try {
            for (int i = 0; i < 100; ++i) tip.waitFrame(tip.framesReceived(), 100, frame);
            QFAIL("a killed publisher went unreported");
        } catch (const RigError& e) {
            qInfo("reported %.3f s after the kill: %s", secondsSince(t0), e.what());
            QVERIFY2(QString(e.what()).contains("closed"), e.what());
        }
    }

    void aStalledPublisherIsReportedAfterItsBound() {
        const QString port = startPublisher("vector", true, 100);  // 2 s of frames, then none
        QVERIFY(!port.isEmpty());
        auto s = settingsFor(port, true, Finger::Index);
        s.stallReportMs = 500;
        YarpFingertip tip(s);
        tip.connect();
        double frame[12];
        std::uint64_t seq = tip.waitFrame(0, 1000, frame);
        while (const std::uint64_t next = tip.waitFrame(seq, 300, frame)) seq = next;
        QVERIFY(!tip.stalled() || tip.secondsSinceFrame() >= 0.5);
        QTRY_VERIFY_WITH_TIMEOUT(tip.stalled(), 5000);
        qInfo("stalled after frame %llu, reported %.3f s after the last frame (bound 0.5 s)",
              static_cast<unsigned long long>(seq), tip.secondsSinceFrame());
        QVERIFY(tip.secondsSinceFrame() >= 0.5);
        QCOMPARE(tip.waitFrame(seq, 300, frame), std::uint64_t(0));  // and waits stay bounded
    }

    void aPublisherThatNeverWritesFailsTheConnect() {
        const QString port = startPublisher("vector", false, 0);
        QVERIFY(!port.isEmpty());
        auto s = settingsFor(port, true, Finger::Index);
        s.firstFrameTimeoutMs = 1000;
        YarpFingertip tip(s);
        try {
            tip.connect();
            QFAIL("connected to a port that never writes");
        } catch (const RigError& e) {
            qInfo("%s", e.what());
            QVERIFY2(QString(e.what()).contains("no frame came within 1000 ms"), e.what());
        }
    }
};

QTEST_GUILESS_MAIN(TestYarpReal)
#include "test_yarp_real.moc"
