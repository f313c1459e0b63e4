// The Yamaha stage driver through QSerialPort on a pseudo-terminal, against the emulated RCX
// controller in both dialects: connect, origin, moves confirmed by position, and every serial
// fault ending with the stage stopped and a sentence naming the problem.
#include <QtTest>
#include <atomic>
#include <chrono>
#include <thread>

#include "devices/emulators/FakeRcxController.h"
#include "devices/yamaha/YamahaStage.h"

using namespace activetouch;
using namespace activetouch::rcx;
using activetouch::emu::FakeRcxController;
using activetouch::emu::FakeRcxSettings;

namespace {

struct Bench {
    FakeRcxController controller;
    std::vector<std::string> log;
    std::unique_ptr<YamahaStage> stage;
    explicit Bench(Dialect dialect) : controller(settings(dialect)) {
        controller.start();
        YamahaStageSettings s;
        s.serial.portName = controller.portName();
        s.dialect = dialect;
        s.timeScale = 10.0;
        s.speedPercent = 20;
        s.replyTimeoutMs = 2000;  // the default: a loaded machine may be slow to answer
        stage = std::make_unique<YamahaStage>(
            s, [this](const std::string& d, const std::string& t) { log.push_back(d + " " + t); });
    }
    static FakeRcxSettings settings(Dialect dialect) {
        FakeRcxSettings f;
        f.dialect = dialect;
        f.timeScale = 10.0;
        f.start = {40.0, 30.0};
        return f;
    }
    bool logged(const std::string& text) const {
        for (const auto& l : log)
            if (l.find(text) != std::string::npos) return true;
        return false;
    }
};

/// A controller in real time and stage settings that reach it: for tests that stop motion
/// part-way.
struct RealTimeController {
    FakeRcxController controller;
    YamahaStageSettings stage;
    RealTimeController(Dialect dialect, double origin_s) : controller(realTime(dialect, origin_s)) {
        controller.start();
        stage.serial.portName = controller.portName();
        stage.dialect = dialect;
    }
    static FakeRcxSettings realTime(Dialect dialect, double origin_s) {
        FakeRcxSettings f = Bench::settings(dialect);
        f.timeScale = 1.0;
        f.origin_s = origin_s;
        return f;
    }
};

}  // namespace

class TestYamahaStage : public QObject {
    Q_OBJECT
private slots:
    void connectHomeAndMoveInBothDialects_data() {
        QTest::addColumn<int>("dialect");
        QTest::newRow("rcx22x") << int(Dialect::Rcx22x);
        QTest::newRow("rcx340") << int(Dialect::Rcx340);
    }
    void connectHomeAndMoveInBothDialects() {
        QFETCH(int, dialect);
        Bench b(static_cast<Dialect>(dialect));
        b.stage->connect(true);
        QCOMPARE(b.stage->position().x, 0.0);
        QCOMPARE(b.controller.commands().at(0), std::string("SERVO ON"));
        QCOMPARE(b.controller.commands().at(1), std::string("ORIGIN"));
        b.stage->moveTo({150.0, 121.0});
        QVERIFY(distance(b.controller.position(), {150.0, 121.0}) < 1e-9);
        QVERIFY(distance(b.stage->position(), {150.0, 121.0}) <= 0.05);
        QVERIFY(!b.controller.moving());
        QVERIFY(b.logged("-> @MOVE P, 150.000 121.000 0 0 0 0, S=20"));
        QVERIFY(b.logged(dialect == int(Dialect::Rcx340) ? "<- END" : "<- [POS] 150.000"));
    }

    void aMoveBeyondTheSoftLimitsIsRefusedBeforeItIsSent() {
        Bench b(Dialect::Rcx22x);
        b.stage->connect(true);
        const auto before = b.controller.commands().size();
        try {
            b.stage->moveTo({700.0, 10.0});
            QFAIL("a move beyond the soft limits was accepted");
        } catch (const RigError& e) {
            QVERIFY(std::string(e.what()).find("outside the soft limits") != std::string::npos);
            QVERIFY(std::string(e.what()).find("nothing was sent") != std::string::npos);
        }
        QCOMPARE(b.controller.commands().size(), before);
    }

    void anNgReplyStopsTheStageAndSaysWhy() {
        Bench b(Dialect::Rcx22x);
        b.stage->connect(true);
        b.controller.injectFault(FakeRcxController::Fault::Ng);
        try {
            b.stage->moveTo({100.0, 100.0});
            QFAIL("an NG reply was not reported");
        } catch (const RigError& e) {
            const std::string m = e.what();
            QVERIFY2(m.find("refused '@MOVE P") != std::string::npos, m.c_str());
            QVERIFY(m.find("error 12: emergency stop") != std::string::npos);
            QVERIFY(m.find("sent a stop") != std::string::npos);
        }
        QVERIFY(!b.controller.moving());
        b.stage->moveTo({100.0, 100.0});  // the next command works again
        QVERIFY(distance(b.controller.position(), {100.0, 100.0}) < 1e-9);
    }

    void garbageLinesAreLoggedAndSkipped() {
        Bench b(Dialect::Rcx22x);
        b.stage->connect(true);
        b.controller.injectFault(FakeRcxController::Fault::Garbage);
        b.stage->moveTo({60.0, 70.0});
        QVERIFY(distance(b.controller.position(), {60.0, 70.0}) < 1e-9);
        QVERIFY(b.logged("!! ignored a line"));
    }

    void aDroppedEndIsCoveredByThePosition() {
        Bench b(Dialect::Rcx340);
        b.stage->connect(true);
        b.controller.injectFault(FakeRcxController::Fault::DropEnd);
        b.stage->moveTo({80.0, 20.0});
        QVERIFY(distance(b.stage->position(), {80.0, 20.0}) <= 0.05);
        QVERIFY(b.logged("END did not come"));
    }

    void noReplyTimesOutWithABoundAndStops() {
        Bench b(Dialect::Rcx22x);
        b.stage->connect(true);
        b.controller.injectFault(FakeRcxController::Fault::NoReply);
        const auto t0 = std::chrono::steady_clock::now();
        QVERIFY_THROWS_EXCEPTION(RigError, b.stage->moveTo({90.0, 90.0}));
        qInfo("a silent controller timed out in %.3f s",
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
        QVERIFY(b.controller.commands().back() == "<ETX>" || !b.controller.moving());
    }

    void aVanishingPortFailsEveryLaterCallClearly() {
        Bench b(Dialect::Rcx22x);
        b.stage->connect(true);
        b.controller.injectFault(FakeRcxController::Fault::Vanish);
        try {
            b.stage->moveTo({50.0, 50.0});
            QFAIL("a vanished port was not reported");
        } catch (const RigError& e) {
            const std::string m = e.what();
            QVERIFY2(
                m.find("serial port " + b.controller.portName() + " vanished") != std::string::npos,
                m.c_str());
            QVERIFY(m.find("could not be sent a stop") != std::string::npos);
        }
        QVERIFY_THROWS_EXCEPTION(RigError, b.stage->moveTo({10.0, 10.0}));
    }

    void aMissingPortIsAClearError() {
        YamahaStageSettings s;
        s.serial.portName = "/dev/does-not-exist-rcx";
        YamahaStage stage(s);
        try {
            stage.connect();
            QFAIL("a missing port was accepted");
        } catch (const RigError& e) {
            QVERIFY(std::string(e.what()).find("/dev/does-not-exist-rcx") != std::string::npos);
        }
    }

    void anOriginSearchIsStoppedWhenAskedTo_data() { connectHomeAndMoveInBothDialects_data(); }
    void anOriginSearchIsStoppedWhenAskedTo() {
        // Ctrl-C in the headless runner while the stage homes: ETX, and home() says so.
        QFETCH(int, dialect);
        RealTimeController rt(static_cast<Dialect>(dialect), 60.0);
        FakeRcxController& controller = rt.controller;
        std::atomic<bool> stopNow{false};
        rt.stage.stopOriginSearch = &stopNow;
        YamahaStage stage(rt.stage);
        std::thread ctrlC([&] {
            for (int waited = 0; waited < 10000 && !controller.moving(); waited += 5)
                std::this_thread::sleep_for(std::chrono::milliseconds(5));
            stopNow = true;
        });
        try {
            stage.connect(true);
            ctrlC.join();
            QFAIL("the origin search ran to its end");
        } catch (const RigError& e) {
            ctrlC.join();
            QVERIFY2(std::string(e.what()).find("'@ORIGIN' was stopped (ETX)") != std::string::npos,
                     e.what());
        }
        // The stop has left the stage's port; the emulator reads it in its own time.
        QTRY_VERIFY_WITH_TIMEOUT(controller.commands().back() == "<ETX>", 5000);
        QTRY_VERIFY_WITH_TIMEOUT(!controller.moving(), 5000);
        QVERIFY(distance(controller.position(), {0.0, 0.0}) > 1.0);  // short of the origin
    }

    void anInterruptEndsAMoveInProgressAndRefusesLaterCommands_data() {
        connectHomeAndMoveInBothDialects_data();
    }
    void anInterruptEndsAMoveInProgressAndRefusesLaterCommands() {
        // Closing the window mid-move: ETX, the move in progress ends with that reason instead of
        // waiting out its bound, and the stage takes no further command.
        QFETCH(int, dialect);
        RealTimeController rt(static_cast<Dialect>(dialect), 0.05);
        FakeRcxController& controller = rt.controller;
        rt.stage.speedPercent = 1;  // a move of several seconds
        YamahaStage stage(rt.stage);
        stage.connect(true);
        const Vec2 target{100.0, 80.0};
        std::string moveError;
        std::thread move([&] {
            try {
                stage.moveTo(target);
            } catch (const RigError& e) {
                moveError = e.what();
            }
        });
        for (int waited = 0; waited < 10000 && !controller.moving(); waited += 5)
            std::this_thread::sleep_for(std::chrono::milliseconds(5));
        QVERIFY(controller.moving());
        stage.interrupt();
        move.join();
        QVERIFY2(moveError.find("stopped (ETX; the application is closing)") != std::string::npos,
                 moveError.c_str());
        QTRY_VERIFY_WITH_TIMEOUT(!controller.moving(), 5000);
        QVERIFY(distance(controller.position(), target) > 1.0);  // short of the target
        const auto commands = controller.commands();
        QVERIFY(std::find(commands.begin(), commands.end(), "<ETX>") != commands.end());
        try {
            stage.moveTo({10.0, 10.0});
            QFAIL("a move after the interrupt was accepted");
        } catch (const RigError& e) {
            QVERIFY2(std::string(e.what()).find("takes no further commands") != std::string::npos,
                     e.what());
        }
        const auto after = controller.commands();
        QVERIFY(std::none_of(after.begin() + static_cast<std::ptrdiff_t>(commands.size()),
                             after.end(),
                             [](const std::string& c) { return c.rfind("MOVE", 0) == 0; }));
    }

    void movesBeforeTheOriginSearchAreRefusedByTheController() {
        Bench b(Dialect::Rcx22x);
        b.stage->connect(false);
        try {
            b.stage->moveTo({10.0, 10.0});
            QFAIL("a move before the origin search was accepted");
        } catch (const RigError& e) {
            QVERIFY(std::string(e.what()).find("origin incomplete") != std::string::npos);
        }
    }
};

QTEST_GUILESS_MAIN(TestYamahaStage)
#include "test_yamaha_stage.moc"
