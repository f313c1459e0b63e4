// run --rig takes its taps on the devices a rig file names (on the emulated bench); Ctrl-C
// stops an origin search; an unreachable stage, rig-file mistakes and trials on other objects
// are refused naming what to do.
#include "CliFixture.h"

class TestCliRig : public CliFixture {
    Q_OBJECT

private slots:
    void runTakesItsTapsOnTheDevicesARigFileNames() {
        // The Yamaha controller emulated on a pseudo-terminal, byte for byte; the tapper and
        // fingertip simulated on the stage's reported pose. Twenty times faster than real time.
        emu::FakeRcxSettings settings;
        settings.timeScale = 20.0;
        emu::FakeRcxController controller(settings);
        controller.start();
        const QString rig =
            write("stage_rig.json",
                  QString(R"({"stage": {"device": "yamaha", "port": "%1"}, "time_scale": 20})")
                      .arg(QString::fromStdString(controller.portName())));
        const Outcome checked = runCli({"check", rig});
        QCOMPARE(checked.exitCode, 0);
        QVERIFY2(checked.out.contains("ok (rig: stage: Yamaha RCX on " +
                                      QString::fromStdString(controller.portName())),
                 qPrintable(checked.out));
        const QString experiment = rectangleOnTheRig();
        const QString out = dir_.filePath("on_the_stage");
        const Outcome o = runCli({"run", experiment, "--rig", rig, "--out", out, "--no-figures"});
        QVERIFY2(o.exitCode == 0, qPrintable(o.out + o.err));
        const QJsonObject s = readJson(out + "/summary.json");
        QVERIFY2(s["rig"].toString().startsWith("stage: Yamaha RCX on " +
                                                QString::fromStdString(controller.portName())),
                 qPrintable(s["rig"].toString()));
        QCOMPARE(s["run_finished"].toBool(), true);
        // Every training and test tap went through the controller: the servo on, the origin
        // searched, then a move for each tap.
        const auto commands = controller.commands();
        QCOMPARE(commands.at(0), std::string("SERVO ON"));
        QCOMPARE(commands.at(1), std::string("ORIGIN"));
        const int moves = int(std::count_if(commands.begin(), commands.end(),
                                            [](const auto& c) { return c.rfind("MOVE", 0) == 0; }));
        const QJsonObject trial = s["following"].toArray().at(0).toObject();
        QVERIFY2(moves >= 2 * 72 + trial["taps"].toInt(), qPrintable(QString::number(moves)));
        QCOMPARE(linesIn(out + "/data/taps.csv"), 1 + 2 * 72 * 50);
        QVERIFY2(trial["taps"].toInt() > 20, qPrintable(o.out));
        QVERIFY(!controller.moving());

        // Ctrl-C part-way: the run stops after the tap in flight, the stage comes to rest, and
        // every tap taken is kept, the summary saying the run did not finish.
        const QString stopped = dir_.filePath("stopped");
        QProcess p;
        p.start(qEnvironmentVariable("ACTIVETOUCH_CLI"),
                {"run", experiment, "--rig", rig, "--out", stopped, "--no-figures"});
        QVERIFY(p.waitForStarted());
        QTRY_VERIFY_WITH_TIMEOUT(linesIn(stopped + "/data/taps.csv") > 20 * 50, 60000);
        ::kill(static_cast<pid_t>(p.processId()), SIGINT);
        QVERIFY(p.waitForFinished(30000));
        QCOMPARE(p.exitStatus(), QProcess::NormalExit);
        QCOMPARE(p.exitCode(), 1);
        QVERIFY(QString(p.readAllStandardError()).contains("stopped before the end"));
        const QJsonObject partial = readJson(stopped + "/summary.json");
        QCOMPARE(partial["run_finished"].toBool(), false);
        const int kept = linesIn(stopped + "/data/taps.csv");
        QVERIFY2(kept > 20 * 50 && kept < 1 + 2 * 72 * 50 && (kept - 1) % 50 == 0,
                 qPrintable(QString::number(kept)));
        QVERIFY(!controller.moving());
    }

    void ctrlCWhileTheStageSearchesItsOriginStopsIt() {
        // A stage half a metre from its origin, in real time: the search takes a minute.
        emu::FakeRcxSettings settings;
        settings.start = {300.0, 150.0};
        settings.origin_s = 60.0;
        emu::FakeRcxController controller(settings);
        controller.start();
        const QString rig =
            write("homing_rig.json", QString(R"({"stage": {"device": "yamaha",
            "port": "%1"}})")
                                         .arg(QString::fromStdString(controller.portName())));
        const QString experiment = rectangleOnTheRig();
        const QString out = dir_.filePath("homing");
        QProcess p;
        p.start(qEnvironmentVariable("ACTIVETOUCH_CLI"),
                {"run", experiment, "--rig", rig, "--out", out, "--no-figures"});
        QVERIFY(p.waitForStarted());
        auto searching = [&] {
            const auto c = controller.commands();
            return std::find(c.begin(), c.end(), "ORIGIN") != c.end() && controller.moving();
        };
        QTRY_VERIFY_WITH_TIMEOUT(searching(), 20000);
        ::kill(static_cast<pid_t>(p.processId()), SIGINT);
        QVERIFY(p.waitForFinished(10000));  // not the minute the search would take
        QCOMPARE(p.exitStatus(), QProcess::NormalExit);
        QCOMPARE(p.exitCode(), 1);
        const QString err = p.readAllStandardError();
        QVERIFY2(err.contains("stopped while connecting") &&
                     err.contains("'@ORIGIN' was stopped") && err.contains("Nothing was recorded"),
                 qPrintable(err));
        // The controller was told to stop (ETX) and the stage is still, short of its origin: the
        // stop left the process before it ended (the emulator reads it from the pty in its own
        // time).
        auto stopped = [&] {
            const auto c = controller.commands();
            return std::find(c.begin(), c.end(), "<ETX>") != c.end();
        };
        QTRY_VERIFY_WITH_TIMEOUT(stopped(), 5000);
        QTRY_VERIFY_WITH_TIMEOUT(!controller.moving(), 5000);
        QVERIFY(!QFile::exists(out + "/data/taps.csv"));
    }

    void aStageThatCannotBeReachedIsNamedAndNothingIsRecorded() {
        const QString rig = write("absent_rig.json",
                                  R"({"stage": {"device": "yamaha", "port": "/dev/ttyNOSUCH9"}})");
        const QString experiment = rectangleOnTheRig();
        const QString out = dir_.filePath("absent");
        const Outcome o = runCli({"run", experiment, "--rig", rig, "--out", out, "--no-figures"});
        QCOMPARE(o.exitCode, 1);
        QVERIFY2(o.err.contains("could not connect") && o.err.contains("/dev/ttyNOSUCH9") &&
                     o.err.contains("Nothing was recorded"),
                 qPrintable(o.err));
        QVERIFY(!QFile::exists(out + "/data/taps.csv"));
    }

    void rigFileMistakesAreNamedBeforeAnythingConnects_data() {
        QTest::addColumn<QString>("rig");
        QTest::addColumn<QString>("message");
        QTest::newRow("stage without a port") << R"({"stage": {"device": "yamaha"}})"
                                              << "/stage/port: missing required text 'port'";
        QTest::newRow("unknown device") << R"({"stage": {"device": "cnc"}})"
                                        << "/stage/device: 'cnc' is not one of";
        QTest::newRow("misspelt key")
            << R"({"stage": {"device": "yamaha", "port": "/dev/ttyUSB0", "speed": 30}})"
            << "/stage/speed: unknown key 'speed'";
        QTest::newRow("NXT without the real fingertip")
            << R"({"tapper": {"device": "nxt"}})"
            << "/fingertip: the NXT tapper stops on the real";
        QTest::newRow("real fingertip on the simulated tapper")
            << R"({"fingertip": {"device": "yarp"}})"
            << "/tapper: the simulated tapper taps with";
        QTest::newRow("port name without a slash")
            << R"({"tapper": {"device": "nxt"}, "fingertip": {"device": "yarp", "port": "skin"}})"
            << "/fingertip/port: a YARP port name starts with '/'";
    }

    void rigFileMistakesAreNamedBeforeAnythingConnects() {
        QFETCH(QString, rig);
        QFETCH(QString, message);
        const QString path = write("bad_rig.json", rig);
        const QString out = dir_.filePath("bad_rig_out");
        const Outcome o = runCli({"run", sourceFile("experiments/paper.json"), "--rig", path,
                                  "--out", out, "--no-figures"});
        QCOMPARE(o.exitCode, 2);
        QVERIFY2(o.err.contains(path) && o.err.contains(message), qPrintable(o.err));
        QVERIFY(!o.out.contains("connecting"));
        QVERIFY(!QDir(out).exists());
        const Outcome c = runCli({"check", path});
        QCOMPARE(c.exitCode, 2);
        QVERIFY2(c.err.contains(message), qPrintable(c.err));
    }

    void aRigRunRefusesTrialsOnOtherObjectsBeforeAnyTap() {
        // The paper's trials are on five objects; one object is mounted on a real rig.
        const QString rig = write("sim_rig.json", R"({"stage": {"device": "simulated"}})");
        const QString out = dir_.filePath("five_objects");
        const Outcome o = runCli({"run", sourceFile("experiments/paper.json"), "--rig", rig,
                                  "--out", out, "--no-figures"});
        QCOMPARE(o.exitCode, 2);
        QVERIFY2(o.err.contains("is not the object on the connected rig") ||
                     o.err.contains("at another place than the object on the connected rig"),
                 qPrintable(o.err));
        QVERIFY(!QDir(out).exists());
    }
};

QTEST_GUILESS_MAIN(TestCliRig)
#include "test_cli_rig.moc"
