// The window with recordings and devices: recordings analysed and runs replayed from the
// window; device panels to and from rig files, driving the simulated rig and the real drivers
// on the emulated bench; runs taking their taps on the connected devices, and stopped when the
// window closes mid-tap.
#include <QLabel>
#include <QLineEdit>
#include <QSpinBox>

#include "WindowFixture.h"

class TestWindowDevices : public WindowFixture {
    Q_OBJECT

private slots:
    void initTestCase() { openWindow(); }

    void recordingsAreAnalysedFromTheWindow() {
        // A run's recording, analysed with the same experiment:
        // the same validation from the taps alone, and no tap taken.
        QVERIFY(window_->openExperiment(sourceFile("experiments/paper.json")));
        {
            QSignalSpy ran(window_.get(), &MainWindow::runEnded);
            QVERIFY(window_->startRun(RunController::What::Everything));
            endsSuccessfully(*window_, ran);
        }
        const auto recordedRun = window_->lastRun();
        QVERIFY(recordedRun && recordedRun->rig == "simulated");
        QAction* analyse = window_->findChild<QAction*>("analyseRecording");
        QVERIFY(analyse && analyse->isEnabled());
        const QString recording = window_->lastRunDirectory() + "/data/taps.csv";
        QSignalSpy ended(window_.get(), &MainWindow::runEnded);
        QVERIFY(window_->analyseRecording(recording));
        QVERIFY(!analyse->isEnabled());
        endsSuccessfully(*window_, ended);
        if (QTest::currentTestFailed()) return;
        const auto analysed = window_->lastRun();
        QCOMPARE(analysed->rig, "recording " + recording.toStdString());
        QCOMPARE(analysed->taps.size(), recordedRun->taps.size());
        QCOMPARE(analysed->validation.angleError_deg, recordedRun->validation.angleError_deg);
        QCOMPARE(analysed->validation.positionError_mm, recordedRun->validation.positionError_mm);
        QVERIFY(analysed->trials.empty());
        QCOMPARE(window_->progressBar()->format(),
                 QString("finished: %1 taps").arg(analysed->taps.size()));
        QVERIFY(QFile::exists(window_->lastRunDirectory() + "/summary.json"));
        QVERIFY(window_->lastRunDirectory().contains("paper_analysis-"));
        // Its classifier follows the contours next.
        QVERIFY(window_->startRun(RunController::What::FollowingOnly));
        endsSuccessfully(*window_, ended);
        if (QTest::currentTestFailed()) return;
        QCOMPARE(int(window_->lastRun()->trials.size()), 10);
        QCOMPARE(window_->lastRun()->rig, std::string("simulated"));
        QCOMPARE(window_->lastRun()->validation.angleError_deg,
                 analysed->validation.angleError_deg);

        // What cannot be analysed is refused with the reason; the session stays as it was.
        const auto before = window_->lastRun();
        QSignalSpy errors(window_.get(), &MainWindow::errorShown);
        QVERIFY(!window_->analyseRecording(window_->lastRunDirectory() + "/summary.json"));
        QCOMPARE(errors.size(), 1);
        QVERIFY2(errors.first().at(0).toString().contains("unexpected columns"),
                 qPrintable(errors.first().at(0).toString()));
        QCOMPARE(window_->lastRun(), before);
        QVERIFY(!window_->running());
        closeErrorDialogs(*window_);

        // With sweeps: (c) is measured on the recorded taps; (a) says why it stays empty.
        const QString swept = paperVariant("swept.json", R"("sweeps": {
                                 "perception": {"belief_thresholds": [0.5]},
                                 "compute": {"bins": [20, 100], "samples_per_tap": [50]}})");
        QVERIFY(window_->openExperiment(swept));
        QVERIFY(window_->analyseRecording(recording));
        QVERIFY(ended.wait(60000));
        QTRY_VERIFY(!window_->running());
        QCOMPARE(int(window_->lastRun()->sweeps.compute.size()), 2);
        for (PlotPanel* p : window_->plotPanels()) {
            if (p->name() == "sweep_c_compute") QVERIFY(p->plot().plottableCount() > 0);
            if (p->name() == "sweep_a_sequential_perception") {
                QVERIFY(p->showsEmptyHint());
                QVERIFY2(p->emptyHint().contains("recording measures only the compute sweep"),
                         qPrintable(p->emptyHint()));
            }
        }
        QVERIFY(window_->openExperiment(sourceFile("experiments/paper.json")));
    }

    void runsAreReplayedFromTheWindow() {
        // A whole run, replayed with the same experiment: every trial retraces its recorded taps.
        QVERIFY(window_->openExperiment(sourceFile("experiments/paper.json")));
        QSignalSpy ended(window_.get(), &MainWindow::runEnded);
        QVERIFY(window_->startRun(RunController::What::Everything));
        QVERIFY(ended.wait(60000));
        QTRY_VERIFY(!window_->running());
        const auto recordedRun = window_->lastRun();
        const QString runDir = window_->lastRunDirectory();
        QAction* replay = window_->findChild<QAction*>("replayRun");
        QVERIFY(replay && replay->isEnabled());
        QVERIFY(window_->replayRun(runDir));
        QVERIFY(!replay->isEnabled());
        endsSuccessfully(*window_, ended);
        if (QTest::currentTestFailed()) return;
        const auto replayed = window_->lastRun();
        QCOMPARE(replayed->rig, "replay of " + runDir.toStdString());
        QVERIFY(window_->lastRunDirectory().contains("paper_replay-"));
        QCOMPARE(replayed->trials.size(), recordedRun->trials.size());
        for (std::size_t i = 0; i < replayed->trials.size(); ++i) {
            const TrialRun &a = replayed->trials[i], &b = recordedRun->trials[i];
            QCOMPARE(a.recordedTaps, int(b.result.taps.size()));
            QCOMPARE(a.result.path(), b.result.path());
            QVERIFY(a.result.end == b.result.end);
        }

        // Another smoothing on the same recording: the trials that decide otherwise leave it,
        // shown as such in the trials table.
        const QString smoother =
            paperVariant("smoother.json", R"("classifier": {"bins": 100, "smoothing": 0.1})");
        QVERIFY(window_->openExperiment(smoother));
        QVERIFY(window_->replayRun(runDir));
        QVERIFY(ended.wait(60000));
        QTRY_VERIFY(!window_->running());
        int left = 0;
        for (const TrialRun& t : window_->lastRun()->trials)
            left += t.result.end == TrialEnd::LeftRecording;
        QVERIFY(left > 0);
        auto* table = window_->findChild<QTableWidget*>("followingTrials");
        QVERIFY(table);
        int shown = 0;
        for (int r = 0; r < table->rowCount(); ++r)
            for (int c = 0; c < table->columnCount(); ++c)
                shown += table->item(r, c) && table->item(r, c)->text() == "left the recording";
        QCOMPARE(shown, left);
        // Each trial that did not complete says where it got furthest, as the CLI does.
        const int furthest = table->columnCount() - 1;
        QCOMPARE(table->horizontalHeaderItem(furthest)->text(),
                 QString("not completed:\ngot furthest"));
        for (int r = 0; r < table->rowCount(); ++r) {
            const TrialResult& t = window_->lastRun()->trials[std::size_t(r)].result;
            QCOMPARE(table->item(r, furthest)->text(),
                     t.completed() ? QString() : QString::fromStdString(describePlace(t.furthest)));
            if (!t.completed()) QVERIFY(!table->item(r, furthest)->text().isEmpty());
        }

        // A folder without a following recording is refused, the session kept.
        QVERIFY(window_->openExperiment(sourceFile("experiments/paper.json")));
        const auto before = window_->lastRun();
        QSignalSpy errors(window_.get(), &MainWindow::errorShown);
        const QString trainingOnly = dir_.filePath("training_only_run");
        QVERIFY(QDir().mkpath(trainingOnly + "/data"));
        QVERIFY(QFile::copy(runDir + "/data/taps.csv", trainingOnly + "/data/taps.csv"));
        QVERIFY(!window_->replayRun(trainingOnly));
        QCOMPARE(errors.size(), 1);
        QVERIFY2(errors.first().at(0).toString().contains("nothing to replay"),
                 qPrintable(errors.first().at(0).toString()));
        QCOMPARE(window_->lastRun(), before);
        QVERIFY(!window_->running());
        closeErrorDialogs(*window_);
    }

    void devicesGoToAndFromRigFiles() {
        // The devices set up in the window go to a file a headless run takes (run --rig), and
        // back, with what the panel does not show (the tapper's gearing, say) kept.
        auto* panel = window_->findChild<DevicesPanel*>();
        QVERIFY(panel);
        auto writeFile = [&](const QString& name, const QString& text) {
            QFile f(dir_.filePath(name));
            f.open(QIODevice::WriteOnly | QIODevice::Truncate);
            f.write(text.toUtf8());
            return f.fileName();
        };
        const QString lab = writeFile("lab_rig.json", R"({
            "stage": {"device": "yamaha", "port": "/dev/ttyUSB3", "baud": 19200, "parity": "even",
                      "dialect": "rcx340", "speed_percent": 35, "search_origin": false},
            "tapper": {"device": "nxt", "usb_bus": 2, "usb_address": 7, "motor_port": "B",
                       "degrees_per_mm": 31.5, "full_power_degrees_per_s": 700},
            "fingertip": {"device": "yarp", "name_server": "10.0.0.2", "name_server_port": 10002,
                          "port": "/icub/skin/left_hand_comp", "finger": "ring",
                          "carrier": "binary", "compensate_raw": true}})");
        QVERIFY(panel->openRigFile(lab));
        const RigConfig shown = panel->choice().config;
        QCOMPARE(shown.stage, RigConfig::StageKind::Yamaha);
        QCOMPARE(shown.yamaha.serial.portName, std::string("/dev/ttyUSB3"));
        QCOMPARE(shown.yamaha.serial.parity, 'E');
        QCOMPARE(shown.tapper, RigConfig::TapperKind::Nxt);
        QCOMPARE(shown.usbBus, 2);
        QCOMPARE(shown.usbAddress, 7);
        QCOMPARE(shown.nxt.degreesPerMm, 31.5);  // not on the panel, kept
        QCOMPARE(shown.yarp.finger, yarp::Finger::Ring);
        QVERIFY(shown.yarp.binaryCarrier && shown.yarp.compensateRaw);
        // The dock says which name server the fingertip will ask, and why; with the fields
        // emptied, the YARP conf file's (here, one written as `yarp conf` would).
        auto* asks = panel->findChild<QLabel*>("nameServerShown");
        QVERIFY(asks);
        QVERIFY2(asks->text().contains("10.0.0.2:10002 (set for the rig)"),
                 qPrintable(asks->text()));
        const QByteArray confHome = dir_.filePath("yarp_conf").toUtf8();
        QDir().mkpath(confHome);
        {
            QFile conf(confHome + "/yarp.conf");
            QVERIFY(conf.open(QIODevice::WriteOnly));
            conf.write("10.1.2.3 10007 yarp\n");
        }
        qputenv("YARP_CONFIG_HOME", confHome);
        panel->findChild<QLineEdit*>("nameServerHost")->clear();
        panel->findChild<QSpinBox*>("nameServerPort")->setValue(0);
        QVERIFY2(asks->text().contains("10.1.2.3:10007") && asks->text().contains("yarp.conf"),
                 qPrintable(asks->text()));
        QVERIFY(panel->choice().config.yarp.nameServerHost.empty());
        qunsetenv("YARP_CONFIG_HOME");
        QVERIFY(panel->openRigFile(lab));
        // Saved again, the file says the same.
        const QString saved = dir_.filePath("saved_rig.json");
        QVERIFY(panel->saveRigFile(saved));
        const SceneSpec scene = window_->experimentAsShown().scene;
        QCOMPARE(rigFileJson(readRigFile(saved.toStdString(), scene)).dump(),
                 rigFileJson(readRigFile(lab.toStdString(), scene)).dump());

        // A bad file is named with its place and the fix, and changes nothing.
        QSignalSpy errors(window_.get(), &MainWindow::errorShown);
        const QString bad = writeFile("bad_rig.json", R"({"tapper": {"device": "nxt"}})");
        QVERIFY(!panel->openRigFile(bad));
        QCOMPARE(errors.count(), 1);
        const QString message = errors.takeFirst().at(0).toString();
        QVERIFY2(message.contains(bad) && message.contains("/fingertip"), qPrintable(message));
        QCOMPARE(rigFileJson(panel->choice().config).dump(), rigFileJson(shown).dump());
        closeErrorDialogs(*window_);
        // The emulated bench is a demo, not devices a file can name.
        auto* tapperKind = window_->findChild<QComboBox*>("tapperKind");
        tapperKind->setCurrentIndex(2);
        QVERIFY(!panel->saveRigFile(dir_.filePath("bench_rig.json")));
        QCOMPARE(errors.count(), 1);
        QVERIFY(!QFile::exists(dir_.filePath("bench_rig.json")));
        closeErrorDialogs(*window_);

        // Back to the simulated devices for what follows.
        QVERIFY(
            panel->openRigFile(writeFile("sim_rig.json", R"({"stage": {"device": "simulated"}})")));
        QCOMPARE(panel->choice().config.stage, RigConfig::StageKind::Simulated);
        QCOMPARE(panel->choice().config.tapper, RigConfig::TapperKind::Simulated);
        QVERIFY(!panel->choice().emulatedBench);
    }

    void devicePanelsDriveTheSimulatedRig() {
        QPushButton* connectButton = window_->findChild<QPushButton*>("connectDevices");
        QTest::mouseClick(connectButton, Qt::LeftButton);
        QLabel* position = window_->findChild<QLabel*>("stagePosition");
        QTRY_VERIFY(position->text().startsWith("x "));
        QTest::mouseClick(window_->findChild<QPushButton*>("goTo"), Qt::LeftButton);
        QTRY_COMPARE(position->text(), QString("x 150.000 mm, y 121.000 mm"));
        QTest::mouseClick(window_->findChild<QPushButton*>("jog+x"), Qt::LeftButton);
        QTRY_COMPARE(position->text(), QString("x 151.000 mm, y 121.000 mm"));
        QLabel* tapper = window_->findChild<QLabel*>("tapperState");
        QTest::mouseClick(window_->findChild<QPushButton*>("testTap"), Qt::LeftButton);
        QTRY_VERIFY(tapper->text().contains("last tap"));
        QTest::mouseClick(connectButton, Qt::LeftButton);
        QTRY_COMPARE(tapper->text(), QString("disconnected"));
    }

    void devicePanelsDriveTheRealDriversOnTheEmulatedBench() {
        // The emulated bench: the Yamaha, NXT and YARP drivers over a pty, the brick emulator and
        // loopback TCP, in real time.
        auto* kind = window_->findChild<QComboBox*>("tapperKind");
        kind->setCurrentIndex(2);
        QPushButton* connectButton = window_->findChild<QPushButton*>("connectDevices");
        QTest::mouseClick(connectButton, Qt::LeftButton);
        QLabel* position = window_->findChild<QLabel*>("stagePosition");
        QTRY_COMPARE_WITH_TIMEOUT(position->text(), QString("x 0.000 mm, y 0.000 mm"), 10000);
        QTest::mouseClick(window_->findChild<QPushButton*>("goTo"), Qt::LeftButton);
        QTRY_COMPARE_WITH_TIMEOUT(position->text(), QString("x 150.000 mm, y 121.000 mm"), 15000);
        QLabel* tapper = window_->findChild<QLabel*>("tapperState");
        QTest::mouseClick(window_->findChild<QPushButton*>("testTap"), Qt::LeftButton);
        QTRY_VERIFY_WITH_TIMEOUT(tapper->text().contains("last tap"), 10000);
        const QString raw = window_->findChild<QPlainTextEdit*>("rawLog")->toPlainText();
        QVERIFY(raw.contains("stage     -> @SERVO ON"));
        QVERIFY(raw.contains("stage     -> @MOVE P, 150.000 121.000 0 0 0 0"));
        QVERIFY(raw.contains("tapper    -> 00 0D"));  // keep-alive
        QVERIFY(raw.contains("fingertip <- Welcome extern"));
        QTest::mouseClick(connectButton, Qt::LeftButton);
        QTRY_COMPARE(tapper->text(), QString("disconnected"));
        kind->setCurrentIndex(0);
    }

    void runsTakeTheirTapsOnTheConnectedDevices() {
        // A short following experiment: one active trial on the mounted rectangle.
        QJsonObject j = readJson(sourceFile("experiments/paper.json"));
        j["scene"] = sourceFile("experiments/scenes/paper_rectangle.json");
        QJsonObject following = j["following"].toObject();
        QJsonArray trials;
        QJsonObject trial = following["trials"].toArray().at(1).toObject();  // active rectangle
        trial["repeats"] = 1;
        trials.append(trial);
        following["trials"] = trials;
        following["tap_cap_perimeters"] = 0.1;  // the smallest allowed: about 10 taps
        j["following"] = following;
        j.remove("recognition");
        const QString path = dir_.filePath("short_following.json");
        writeJson(path, j);
        {  // the classifier the devices follow with, trained on the simulated rig
            QVERIFY(window_->openExperiment(sourceFile("experiments/paper.json")));
            QSignalSpy trained(window_.get(), &MainWindow::runEnded);
            QVERIFY(window_->startRun(RunController::What::TrainingOnly));
            endsSuccessfully(*window_, trained);
        }
        QVERIFY(window_->openExperiment(path));
        QVERIFY(window_->lastRun());

        auto* kind = window_->findChild<QComboBox*>("tapperKind");
        kind->setCurrentIndex(2);  // the emulated bench, in real time
        QPushButton* connectButton = window_->findChild<QPushButton*>("connectDevices");
        QTest::mouseClick(connectButton, Qt::LeftButton);
        QLabel* position = window_->findChild<QLabel*>("stagePosition");
        QTRY_COMPARE_WITH_TIMEOUT(position->text(), QString("x 0.000 mm, y 0.000 mm"), 10000);

        QSignalSpy ended(window_.get(), &MainWindow::runEnded);
        QVERIFY(window_->startRun(RunController::What::FollowingOnly));
        // While the run has the devices, the panels' commands are refused with the reason.
        QTest::mouseClick(window_->findChild<QPushButton*>("testTap"), Qt::LeftButton);
        auto* log = window_->findChild<QPlainTextEdit*>("log");
        QTRY_VERIFY(log->toPlainText().contains("A run is using the devices"));
        endsSuccessfully(*window_, ended);
        if (QTest::currentTestFailed()) return;
        const auto run = window_->lastRun();
        QVERIFY(QString::fromStdString(run->rig).startsWith("emulated bench: stage: Yamaha"));
        QCOMPARE(int(run->trials.size()), 1);
        const TrialResult& t = run->trials[0].result;
        qInfo("following on the emulated bench from the window: %d taps, %s, %.1f robot s",
              int(t.taps.size()), trialEndName(t.end), t.robotTime_s);
        QVERIFY2(t.end != TrialEnd::DeviceError, t.detail.c_str());
        QVERIFY(t.taps.size() >= 3);
        QCOMPARE(run->tapsSimulated, std::uint64_t(0));
        // The taps went through the drivers: one stage move per tap, in the raw log.
        const QString raw = window_->findChild<QPlainTextEdit*>("rawLog")->toPlainText();
        QVERIFY(raw.count("-> @MOVE P") >= int(t.taps.size()));
        QCOMPARE(linesIn(window_->lastRunDirectory() + "/data/following_taps.csv"),
                 int(t.taps.size()) * 50 + 1);
    }

    void closingTheWindowMidTapStopsTheRun() {
        // The devices are still connected from the previous test; a run is tapping on them.
        QVERIFY(window_->startRun(RunController::What::FollowingOnly));
        const QString out = window_->lastRunDirectory();
        QTest::qWait(2500);  // the first tap is done, the second under way
        QVERIFY(window_->running());
        QElapsedTimer closing;
        closing.start();
        window_->close();
        window_.reset();
        qInfo("closed mid-run in %lld ms", closing.elapsed());
        // Every tap finished before the close is in the recording, whole, and the close did not
        // wait for the trial's other taps (its cap is about ten, a tap every 2.5 s): the tap and
        // the stage move under way were stopped.
        const int lines = linesIn(out + "/data/following_taps.csv");
        QVERIFY2(lines >= 51 && (lines - 1) % 50 == 0, qPrintable(QString::number(lines)));
        QVERIFY2((lines - 1) / 50 <= 3, qPrintable(QString::number(lines)));
    }

    void cleanupTestCase() { closeWindow(); }
};

QTEST_MAIN(TestWindowDevices)
#include "test_window_devices.moc"
