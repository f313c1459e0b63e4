// The real drivers end to end over the emulated bench, through the real transports (QSerialPort
// on a pty, QTcpSocket on loopback; the NXT telegrams go to the emulated brick in process — the
// libusb path has its own test under umockdev): connect, home, tap with reflex stop, move, 50 Hz
// frames, a short active contour-following trial, mixed rigs, and the tapper's faults ending in
// a safe state with every finished tap kept.
#include <QtTest>
#include <chrono>
#include <functional>
#include <thread>

#include "app/run/ExperimentRun.h"
#include "devices/emulators/EmulatedBench.h"
#include "devices/rigs/RigAssembly.h"
#include "devices/simulated/SimulatedWorld.h"
#include "support/Paths.h"

using namespace activetouch;
using activetouch::emu::EmulatedBench;
using activetouch::emu::FakeNxtBrick;
using activetouch::emu::FakeNxtTransport;

namespace {

struct Emulated {
    ExperimentSpec spec;
    std::shared_ptr<const FingertipContactModel> model;
    std::unique_ptr<EmulatedBench> bench;
    std::vector<std::string> log;  // before the rig: the rig logs while it shuts down
    std::unique_ptr<AssembledRig> rig;
    explicit Emulated(rcx::Dialect dialect = rcx::Dialect::Rcx22x) {
        spec = loadExperiment(test::sourcePath("experiments/paper.json"));
        model = std::make_shared<const FingertipContactModel>(spec.scene.fingertip);
        emu::BenchSettings b;
        b.dialect = dialect;
        bench = std::make_unique<EmulatedBench>(spec.scene, model, b);
        bench->start();
    }
    RigConfig config() {
        RigConfig c;
        c.stage = RigConfig::StageKind::Yamaha;
        c.yamaha = bench->stageSettings();
        c.tapper = RigConfig::TapperKind::Nxt;
        c.nxt = bench->tapperSettings();
        c.nxtTransport = [this] { return std::make_unique<FakeNxtTransport>(bench->brick()); };
        c.yarp = bench->fingertipSettings();
        c.timeScale = bench->timeScale();
        return c;
    }
    void assemble() {
        rig = std::make_unique<AssembledRig>(
            spec.scene, model, config(),
            [this](const std::string& dev, const std::string& d, const std::string& t) {
                log.push_back(dev + " " + d + " " + t);
            });
        rig->brick()->setRawLog([this](const std::string& d, const std::string& t) {
            log.push_back("tapper " + d + " " + t);
        });
    }
    /// A point on the rectangle's lower edge, 9 mm in: where the paper's trials start.
    Vec2 onLowerEdge() const {
        const Polygon outline = spec.scene.object.outline();
        const Vec2 lo = outline.boundingBoxMin(), hi = outline.boundingBoxMax();
        return {0.5 * (lo.x + hi.x), lo.y + 9.0};
    }
    bool retracted() {
        qInfo("motor at %.1f degrees, %s", bench->brick().rotationDegrees(0),
              bench->brick().motorRunning(0) ? "running" : "stopped");
        return std::abs(bench->brick().rotationDegrees(0)) <= 10.0 &&
               !bench->brick().motorRunning(0);
    }
};

double peakOf(const TapRecord& r) {
    double peak = 0.0;
    for (double v : r.tap.samples) peak = std::max(peak, v);
    return peak;
}

}  // namespace

class TestEmulatedRig : public QObject {
    Q_OBJECT
    RunResult trained_;

    /// An active trial on the rectangle that calls `inject` after `afterTaps` taps.
    TrialResult trialWithFaultAfter(Emulated& e, int afterTaps,
                                    const std::function<void()>& inject) {
        Rig rig = e.rig->rig();
        const Polygon outline = e.spec.scene.object.outline();
        const TrialSetup setup =
            trialSetupFor(trained_, FollowingMode::Active, e.spec.following, outline, std::nullopt);
        int taps = 0;
        return runTrial(rig, trained_.classifier, trained_.classes, outline, setup,
                        [&](const FollowedTap&) {
                            if (++taps == afterTaps) inject();
                            return true;
                        });
    }

private slots:
    void initTestCase() {
        // The classifier comes from the simulated rig; the trial then runs on the emulated one.
        ExperimentSpec spec = loadExperiment(test::sourcePath("experiments/paper.json"));
        spec.trials.clear();
        spec.recognition.enabled = false;
        RunOptions options;
        options.seed = 1;
        trained_ = runExperiment(spec, options);
        QVERIFY(trained_.failure.empty());
    }

    void connectHomeTapAndMove() {
        Emulated e;
        e.assemble();
        Rig rig = e.rig->rig();
        QVERIFY(distance(rig.stage.position(), {0.0, 0.0}) <= 0.05);  // the origin search
        QVERIFY(e.rig->batteryMillivolts().value_or(0) > 7000);

        const TapRecord on = rig.tapAt(e.onLowerEdge());
        QCOMPARE(on.tap.sampleCount(), e.spec.scene.tap.samples);
        QCOMPARE(int(on.ending), int(TapEnding::ContactReflex));
        QVERIFY(peakOf(on) >= 0.5 * e.spec.scene.tap.contactThreshold / 12);
        QVERIFY(on.stopDepth_mm > 0.0 && on.stopDepth_mm < e.spec.scene.tap.stroke_mm);
        QVERIFY(e.retracted());
        QVERIFY(distance(e.bench->rcx().position(), e.onLowerEdge()) < 1e-6);

        const TapRecord off = rig.tapAt({20.0, 20.0});  // nothing under the tip
        QCOMPARE(int(off.ending), int(TapEnding::StrokeLimit));
        QCOMPARE(peakOf(off), 0.0);
        QVERIFY(e.retracted());
        QVERIFY(on.cycleTime_s > 0.5 && off.startTime_s > on.startTime_s);
    }

    void framesArriveAt50HzOfRobotTime() {
        Emulated e;
        e.assemble();
        Rig rig = e.rig->rig();
        const double t0 = rig.clock.now_s();
        const auto f0 = e.rig->fingertip()->framesReceived();
        const auto s0 = e.bench->yarp().framesSent();
        std::this_thread::sleep_for(std::chrono::milliseconds(400));
        const auto received = e.rig->fingertip()->framesReceived() - f0;
        const auto sent = e.bench->yarp().framesSent() - s0;
        const double rate = received / (rig.clock.now_s() - t0);
        qInfo(
            "fingertip frames: %.1f per robot second (the skin streams at 50 Hz); %d sent, %d "
            "received",
            rate, int(sent), int(received));
        // A busy machine may delay the publisher; the reader must still keep up with it.
        QVERIFY(rate > 30.0 && rate < 60.0);
        QVERIFY(received + 3 >= sent);
    }

    void aShortActiveTrialFollowsTheEdge() {
        Emulated e;
        e.assemble();
        Rig rig = e.rig->rig();
        FollowingSettings settings = e.spec.following;
        settings.tapCapPerimeters = 0.15;  // a short trial: about 16 taps
        const Polygon outline = e.spec.scene.object.outline();
        const TrialSetup setup =
            trialSetupFor(trained_, FollowingMode::Active, settings, outline, std::nullopt);
        int seen = 0;
        const TrialResult r = runTrial(rig, trained_.classifier, trained_.classes, outline, setup,
                                       [&](const FollowedTap&) { return ++seen > 0; });
        qInfo("emulated trial: %d taps, end %s, mean distance to the contour %.2f mm, %.1f robot s",
              int(r.taps.size()), trialEndName(r.end), r.meanContourDistance_mm, r.robotTime_s);
        QVERIFY2(r.end == TrialEnd::TapCap || r.end == TrialEnd::Completed, r.detail.c_str());
        QCOMPARE(seen, int(r.taps.size()));
        QVERIFY(r.taps.size() >= 10);
        QVERIFY(r.meanContourDistance_mm < 3.0);
        // It moved along the edge, not on the spot.
        const Vec2 first = r.taps.front().record.pose, last = r.taps.back().record.pose;
        QVERIFY(distance(first, last) > 8.0);
        QVERIFY(e.retracted());
    }

    void tapperFaultsEndInASafeState_data() {
        QTest::addColumn<int>("fault");
        QTest::addColumn<QString>("says");
        QTest::addColumn<bool>("returned");
        QTest::newRow("USB unplug mid-tap") << int(FakeNxtBrick::Fault::Unplug) << "gone" << false;
        QTest::newRow("reply timeout") << int(FakeNxtBrick::Fault::NoReply) << "no reply" << true;
        QTest::newRow("wrong echoed opcode")
            << int(FakeNxtBrick::Fault::WrongOpcode) << "out of step" << true;
        QTest::newRow("non-zero status")
            << int(FakeNxtBrick::Fault::Status) << "refused opcode 0x06: request failed" << true;
    }
    void tapperFaultsEndInASafeState() {
        QFETCH(int, fault);
        QFETCH(QString, says);
        QFETCH(bool, returned);
        Emulated e;
        e.assemble();
        Rig rig = e.rig->rig();
        rig.tapAt(e.onLowerEdge());  // one good tap first
        const double before = e.bench->brick().rotationDegrees(0);
        // Mid-tap: on the third motor-state poll of the next tap.
        e.bench->brick().injectFault(static_cast<FakeNxtBrick::Fault>(fault), nxt::GetOutputState,
                                     2);
        try {
            rig.tapAt(e.onLowerEdge());
            QFAIL("the fault was not reported");
        } catch (const RigError& err) {
            const std::string m = err.what();
            QVERIFY2(m.find(says.toStdString()) != std::string::npos, m.c_str());
            if (returned) QVERIFY2(m.find("braked and returned") != std::string::npos, m.c_str());
        }
        if (returned) {
            QVERIFY(e.retracted());
        } else {
            // Unplugged: the motor stops at its tacho limit on its own.
            QTest::qWait(100);
            qInfo("unplugged: motor at %.1f degrees", e.bench->brick().rotationDegrees(0));
            QVERIFY(!e.bench->brick().motorRunning(0));
            QVERIFY(e.bench->brick().rotationDegrees(0) <=
                    before + e.spec.scene.tap.stroke_mm * e.bench->tapperSettings().degreesPerMm +
                        10.0);
        }
    }

    void aDeviceFaultInATrialKeepsEveryFinishedTap() {
        Emulated e;
        e.assemble();
        const TrialResult r = trialWithFaultAfter(
            e, 4, [&] { e.bench->brick().injectFault(FakeNxtBrick::Fault::NoReply); });
        QCOMPARE(int(r.end), int(TrialEnd::DeviceError));
        QCOMPARE(int(r.taps.size()), 4);
        QVERIFY2(r.detail.find("NXT") != std::string::npos, r.detail.c_str());
        QVERIFY(e.retracted());
    }

    void aStalledFingertipStopsTheTapBeforeItGoesDeep() {
        Emulated e;
        e.assemble();
        Rig rig = e.rig->rig();
        rig.stage.moveTo(e.onLowerEdge());
        e.bench->yarp().setStalled(true);
        QTest::qWait(50);
        try {
            rig.tapper.tap();
            QFAIL("a stalled stream was not reported");
        } catch (const RigError& err) {
            QVERIFY2(std::string(err.what()).find("stalled") != std::string::npos, err.what());
        }
        QVERIFY(e.retracted());
    }

    void aStageFaultInATrialEndsItWithItsReason() {
        Emulated e;
        e.assemble();
        const TrialResult r = trialWithFaultAfter(
            e, 3, [&] { e.bench->rcx().injectFault(emu::FakeRcxController::Fault::Ng); });
        QCOMPARE(int(r.end), int(TrialEnd::DeviceError));
        QCOMPARE(int(r.taps.size()), 3);
        QVERIFY2(r.detail.find("emergency stop") != std::string::npos, r.detail.c_str());
    }

    void aRealStageWithTheSimulatedFingertipTapsLikeTheSimulatedRig() {
        Emulated e;
        RigConfig c = e.config();
        c.tapper = RigConfig::TapperKind::Simulated;
        AssembledRig mixed(e.spec.scene, e.model, c);
        SimulatedRig simulated(e.spec.scene, e.model);
        const Vec2 p = e.onLowerEdge();
        const TapRecord a = mixed.rig().tapAt(p);
        const TapRecord b = simulated.rig().tapAt(p);
        QVERIFY(distance(e.bench->rcx().position(), p) < 1e-6);
        QVERIFY(a.tap.samples == b.tap.samples);  // same world, same seed, same pose
        QVERIFY(peakOf(a) > 0.0);
    }

    void closingMidTapReturnsWithinTwoSeconds() {
        Emulated e;
        e.assemble();
        Rig rig = e.rig->rig();
        rig.stage.moveTo(e.onLowerEdge());
        std::string ended;
        std::thread tapping([&] {
            try {
                rig.tapper.tap();
                ended = "finished";
            } catch (const RigError& err) {
                ended = err.what();
            }
        });
        QTest::qWait(30);
        const auto t0 = std::chrono::steady_clock::now();
        e.rig.reset();  // what closing the window does
        tapping.join();
        const double s =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        qInfo("closed mid-tap in %.3f s (%s)", s, ended.c_str());
        QVERIFY(s < 2.0);
        QVERIFY(!e.bench->brick().motorRunning(0));
    }

    void anUnreachableDeviceIsNamedAndNothingStaysConnected() {
        Emulated e;
        RigConfig c = e.config();
        c.yarp.port = "/icub/skin/left_hand_comp";
        try {
            AssembledRig rig(e.spec.scene, e.model, c);
            QFAIL("a rig with an unknown YARP port was assembled");
        } catch (const RigError& err) {
            QVERIFY(std::string(err.what()).find("left_hand_comp is not registered") !=
                    std::string::npos);
        }
        QCOMPARE(e.bench->yarp().readers(), 0);
    }
};

QTEST_GUILESS_MAIN(TestEmulatedRig)
#include "test_emulated_rig.moc"
