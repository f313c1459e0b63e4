// The window's experiment: the protocol panel shows what runs, its changes are run and
// saved, trials are copied and removed, settings that cannot run are refused naming the field;
// bad files and scenes are refused keeping the session; polygon files load into the scene.
#include "WindowFixture.h"

class TestWindowProtocol : public WindowFixture {
    Q_OBJECT

private slots:
    void initTestCase() { openWindow(); }

    void theProtocolPanelShowsWhatTheExperimentRunsWith() {
        // Untouched, the panels give the experiment exactly as the file says, defaults included,
        // with no value rounded on the way (paper_sequential's threshold is 1 - 1e-8).
        for (const char* file : {"experiments/paper_sequential.json", "experiments/paper.json"}) {
            QVERIFY(window_->openExperiment(sourceFile(file)));
            const ExperimentSpec fromFile = loadExperiment(sourceFile(file).toStdString());
            const ExperimentSpec shown = window_->experimentAsShown();
            const FollowingSettings &a = shown.following, &b = fromFile.following;
            QCOMPARE(a.followStep_mm, b.followStep_mm);
            QCOMPARE(a.repositionStep_mm, b.repositionStep_mm);
            QCOMPARE(a.airRetreatStep_mm, b.airRetreatStep_mm);
            QCOMPARE(a.planeRetreatStep_mm, b.planeRetreatStep_mm);
            QCOMPARE(a.orientationTrustMaxError_deg, b.orientationTrustMaxError_deg);
            QCOMPARE(a.edgeConfirmationTaps, b.edgeConfirmationTaps);
            QCOMPARE(a.beliefThreshold, b.beliefThreshold);
            QCOMPARE(a.maxTapsPerDecision, b.maxTapsPerDecision);
            QCOMPARE(a.lostInside_mm, b.lostInside_mm);
            QCOMPARE(a.tapCapPerimeters, b.tapCapPerimeters);
            QCOMPARE(shown.classifier.bins, fromFile.classifier.bins);
            QCOMPARE(shown.classifier.smoothing, fromFile.classifier.smoothing);
            QCOMPARE(shown.classifier.kernelSigma_bins, fromFile.classifier.kernelSigma_bins);
            QCOMPARE(shown.training.trainingSets, fromFile.training.trainingSets);
            QCOMPARE(shown.training.placementJitter_mm, fromFile.training.placementJitter_mm);
            QCOMPARE(shown.validRangeWidth, fromFile.validRangeWidth);
            QCOMPARE(shown.scene.seed, fromFile.scene.seed);
            QCOMPARE(shown.recognition.enabled, fromFile.recognition.enabled);
            QCOMPARE(shown.recognition.smoothingSigmaBins, fromFile.recognition.smoothingSigmaBins);
            QCOMPARE(shown.trials.size(), fromFile.trials.size());
            for (std::size_t i = 0; i < shown.trials.size(); ++i) {
                QCOMPARE(shown.trials[i].mode, fromFile.trials[i].mode);
                QCOMPARE(shown.trials[i].repeats, fromFile.trials[i].repeats);
                QCOMPARE(shown.trials[i].label, fromFile.trials[i].label);
            }
        }
        QCOMPARE(protocolField<QDoubleSpinBox>("following_belief_threshold")->value(), 0.0);
        QCOMPARE(trialMode(0)->currentText(), QString("passive"));
        QCOMPARE(trialMode(1)->currentText(), QString("active"));
    }

    void protocolSettingsChangedInThePanelAreRunAndSaved() {
        window_->setPace(Pace::Fastest);
        auto* follow = protocolField<QDoubleSpinBox>("following_follow_step_mm");
        auto* seed = protocolField<QSpinBox>("seed");
        QVERIFY(follow && seed && trialMode(1) && trialRepeats(1));
        // Type the step as a person does, and run without leaving the box; the active
        // rectangle (row 2) runs passively, once.
        follow->setFocus();
        follow->selectAll();
        QTest::keyClicks(follow, "3.5");
        QCOMPARE(follow->value(), 3.5);
        seed->setValue(4);
        trialMode(1)->setCurrentIndex(trialMode(1)->findText("passive"));
        trialRepeats(1)->setValue(1);
        QSignalSpy ended(window_.get(), &MainWindow::runEnded);
        QVERIFY(window_->startRun(RunController::What::Everything));
        endsSuccessfully(*window_, ended);
        const auto run = window_->lastRun();
        QCOMPARE(run->spec.scene.seed, std::uint64_t(4));
        int passiveRectangles = 0, activeRectangles = 0, followSteps = 0;
        for (const TrialRun& t : run->trials) {
            if (t.label == "rectangle")
                ++(t.result.mode == FollowingMode::Passive ? passiveRectangles : activeRectangles);
            for (const FollowedTap& tap : t.result.taps)
                if (tap.decision.rule == RuleId::FollowInRange ||
                    tap.decision.rule == RuleId::PassiveFollow) {
                    QCOMPARE(norm(tap.decision.follow), 3.5);
                    ++followSteps;
                }
        }
        QCOMPARE(passiveRectangles, 3);
        QCOMPARE(activeRectangles, 0);
        QVERIFY(followSteps > 0);
        const auto summary = readJson(window_->lastRunDirectory() + "/summary.json");
        QCOMPARE(summary["seed"].toInt(), 4);

        // Save as writes what the panels show; the saved file opens to the same settings.
        const QString saved = dir_.filePath("protocol_edited.json");
        QVERIFY(window_->saveExperiment(saved));
        const ExperimentSpec reread = loadExperiment(saved.toStdString());
        QCOMPARE(reread.following.followStep_mm, 3.5);
        QCOMPARE(reread.scene.seed, std::uint64_t(4));
        QCOMPARE(reread.trials[1].mode, FollowingMode::Passive);
        QCOMPARE(reread.trials[1].repeats, 1);
        QCOMPARE(reread.following.repositionStep_mm, 1.0);

        // A save that cannot be written whole (here files may not grow past 100 bytes, as on a
        // full disk) says so, naming the file and why, and leaves the saved file as it was.
        QFile before(saved);
        QVERIFY(before.open(QIODevice::ReadOnly));
        const QByteArray savedText = before.readAll();
        before.close();
        follow->setValue(2.5);
        {
            QSignalSpy errors(window_.get(), &MainWindow::errorShown);
            bool ok = true;
            {
                test::FileSizeLimit limit(100);
                ok = window_->saveExperiment(saved);
            }
            QVERIFY(!ok);
            QCOMPARE(errors.count(), 1);
            const QString message = errors.takeFirst().at(0).toString();
            QVERIFY2(message.contains(saved) && message.contains("the file is as it was"),
                     qPrintable(message));
            closeErrorDialogs(*window_);
        }
        QVERIFY(before.open(QIODevice::ReadOnly));
        QCOMPARE(before.readAll(), savedText);
        before.close();
        follow->setValue(3.5);

        // The file's own values come back at a click, and the next run uses them.
        auto* reset = window_->protocolPanel()->findChild<QPushButton*>("protocol_reset");
        QVERIFY(reset);
        QTest::mouseClick(reset, Qt::LeftButton);
        QCOMPARE(follow->value(), 2.0);
        QCOMPARE(trialMode(1)->currentText(), QString("active"));
        QCOMPARE(window_->experimentAsShown().following.followStep_mm, 2.0);
        QCOMPARE(window_->experimentAsShown().scene.seed, std::uint64_t(1));
    }

    void trialsAreCopiedAndRemovedInTheProtocolPanel() {
        // Follow the cross passively too: copy its trial, make the copy passive, once.
        auto* table = window_->protocolPanel()->findChild<QTableWidget*>("protocol_trials");
        auto* copy = window_->protocolPanel()->findChild<QPushButton*>("protocol_copy_trial");
        auto* remove = window_->protocolPanel()->findChild<QPushButton*>("protocol_remove_trial");
        QVERIFY(table && copy && remove);
        const int rows = table->rowCount();
        QCOMPARE(table->item(2, 0)->text(), QString("cross"));
        table->selectRow(2);
        QVERIFY(copy->isEnabled());
        QTest::mouseClick(copy, Qt::LeftButton);
        QCOMPARE(table->rowCount(), rows + 1);
        QCOMPARE(table->item(3, 0)->text(), QString("cross"));
        trialMode(3)->setCurrentIndex(trialMode(3)->findText("passive"));
        trialRepeats(3)->setValue(1);
        QSignalSpy ended(window_.get(), &MainWindow::runEnded);
        QVERIFY(window_->startRun(RunController::What::Everything));
        endsSuccessfully(*window_, ended);
        int passiveCrosses = 0, activeCrosses = 0;
        for (const TrialRun& t : window_->lastRun()->trials)
            if (t.label == "cross")
                ++(t.result.mode == FollowingMode::Passive ? passiveCrosses : activeCrosses);
        QCOMPARE(passiveCrosses, 1);
        QCOMPARE(activeCrosses, 2);
        QVERIFY(!window_->lastRun()->trials.empty());
        // Removing the copy gives the file's trials back.
        table->selectRow(3);
        QTest::mouseClick(remove, Qt::LeftButton);
        QCOMPARE(table->rowCount(), rows);
        const ExperimentSpec shown = window_->experimentAsShown();
        const ExperimentSpec file = loadExperiment(window_->experimentPath().toStdString());
        QCOMPARE(shown.trials.size(), file.trials.size());
        for (std::size_t i = 0; i < file.trials.size(); ++i) {
            QCOMPARE(shown.trials[i].label, file.trials[i].label);
            QCOMPARE(shown.trials[i].mode, file.trials[i].mode);
            QCOMPARE(shown.trials[i].repeats, file.trials[i].repeats);
        }
    }

    void runFollowingRefusesSettingsItsClassifierWasNotTrainedWith() {
        // The last run's classifier follows; a following setting changed in the panel is used, a
        // training setting is refused by name rather than shown as if it had been followed with.
        QVERIFY(window_->lastRun() && window_->lastRun()->classifier.trained());
        const auto trained = window_->lastRun();
        auto* smoothing = protocolField<QDoubleSpinBox>("classifier_smoothing");
        smoothing->setValue(0.5);
        expectRefused(RunController::What::FollowingOnly,
                      {"smoothing: 0.01 -> 0.5", "Run training & validation"});
        QCOMPARE(window_->lastRun(), trained);
        smoothing->setValue(0.01);
        auto* follow = protocolField<QDoubleSpinBox>("following_follow_step_mm");
        follow->setValue(3.0);
        QSignalSpy ended(window_.get(), &MainWindow::runEnded);
        QVERIFY(window_->startRun(RunController::What::FollowingOnly));
        endsSuccessfully(*window_, ended);
        QCOMPARE(window_->lastRun()->spec.following.followStep_mm, 3.0);
        QVERIFY(window_->lastRun()->taps.empty());  // no training taps: the trained classifier
        QVERIFY(!window_->lastRun()->trials.empty());
        follow->setValue(2.0);
    }

    void eightOrientationsAreSetByClicking() {
        // Eight orientations need a training object facing each: the rectangle is refused, naming
        // the scene panel; with the octagon loaded there, the run trains and follows with eight.
        auto* orientations = protocolField<QLineEdit>("classes_orientations_deg");
        QVERIFY(orientations);
        QCOMPARE(orientations->text(), QString("270, 0, 90, 180"));
        orientations->setText("270, 315, 0, 45, 90, 135, 180, 225");
        expectRefused(RunController::What::Everything,
                      {"scene panel", "the training object has no edge facing 315 deg"});
        QVERIFY(
            window_->scenePanel()->loadPolygonFrom(sourceFile("experiments/scenes/octagon.json")));
        QSignalSpy ended(window_.get(), &MainWindow::runEnded);
        QVERIFY(window_->startRun(RunController::What::Everything));
        endsSuccessfully(*window_, ended);
        const auto run = window_->lastRun();
        QCOMPARE(run->classes.orientationsDeg.size(), std::size_t(8));
        QCOMPARE(int(run->validation.byClass.size()), 8 * 18);
        orientations->setText("270, up");
        expectRefused(RunController::What::Everything,
                      {"Edge orientations (deg): 'up' is not an angle in degrees"});
        QVERIFY(window_->openExperiment(sourceFile("experiments/paper.json")));
        QCOMPARE(orientations->text(), QString("270, 0, 90, 180"));
    }

    void protocolSettingsThatCannotRunAreRefusedNamingTheField() {
        auto refused = [&](const QString& field, const QString& problem) {
            expectRefused(RunController::What::Everything, {"protocol panel", field, problem});
        };
        // Every trial passive leaves recognition of the active paths nothing to recognise.
        auto* table = window_->protocolPanel()->findChild<QTableWidget*>("protocol_trials");
        for (int row = 0; row < table->rowCount(); ++row)
            trialMode(row)->setCurrentIndex(trialMode(row)->findText("passive"));
        refused("Recognition: Of the trials", "no active trials to recognise");
        // Recognising the passive paths instead can run.
        auto* of = window_->protocolPanel()->findChild<QComboBox*>("protocol_recognition_of_mode");
        of->setCurrentIndex(of->findText("passive"));
        QCOMPARE(window_->experimentAsShown().recognition.ofMode, FollowingMode::Passive);
        auto* sets = protocolField<QLineEdit>("training_training_sets");
        QVERIFY(sets);
        sets->setText("1, two");
        refused("Training sets", "'two' is not a data set number");
        sets->setText("6");
        refused("Training and validation", "training set 6 does not exist (sets are 1..5)");
        sets->setText("1");
        auto* remove = window_->protocolPanel()->findChild<QPushButton*>("protocol_remove_trial");
        while (table->rowCount() > 0) {
            table->selectRow(0);
            QTest::mouseClick(remove, Qt::LeftButton);
        }
        refused("Recognition: Of the trials", "no passive trials to recognise");
        auto* recognition = window_->protocolPanel()->findChild<QGroupBox*>("protocol_recognition");
        clickCheckBox(recognition);
        QVERIFY(!recognition->isChecked());
        // Without trials or recognition the experiment is its training and validation alone.
        const ExperimentSpec trainingOnly = window_->experimentAsShown();
        QVERIFY(trainingOnly.trials.empty());
        QVERIFY(!trainingOnly.recognition.enabled);
        QTest::mouseClick(window_->protocolPanel()->findChild<QPushButton*>("protocol_reset"),
                          Qt::LeftButton);
        QCOMPARE(sets->text(), QString("1"));
        QVERIFY(recognition->isChecked());
        QCOMPARE(table->rowCount(), 5);  // the file's five trial entries
        QCOMPARE(window_->experimentAsShown().trials[1].mode, FollowingMode::Active);
    }

    void aSceneThatCannotTrainIsRefusedBeforeAnyTap() {
        auto* x = window_->findChild<QDoubleSpinBox*>("objectCentreX");
        QVERIFY(x);
        const double was = x->value();
        x->setValue(25);  // the object still fits the travel; its left edge's air side does not
        const auto run = window_->lastRun();
        QSignalSpy errors(window_.get(), &MainWindow::errorShown);
        QVERIFY(!window_->startRun(RunController::What::TrainingOnly));
        QCOMPARE(errors.count(), 1);
        const QString message = errors.takeFirst().at(0).toString();
        QVERIFY2(message.contains("scene panel") &&
                     message.contains("training on it: position 10 at the left edge taps at "
                                      "(0.5, 150) mm"),
                 qPrintable(message));
        QVERIFY(!window_->running());
        QCOMPARE(window_->lastRun(), run);
        closeErrorDialogs(*window_);
        x->setValue(was);
        QVERIFY(window_->startRun(RunController::What::TrainingOnly));
        QTRY_VERIFY_WITH_TIMEOUT(!window_->running(), 60000);
    }

    void badFilesShowTheProblemAndKeepTheSession_data() {
        QTest::addColumn<QString>("text");
        QTest::addColumn<QString>("problem");
        QTest::newRow("malformed experiment") << R"({"name": "x", "scene": )"
                                              << "not valid JSON";
        QTest::newRow("unknown effect")
            << QString(
                   R"({"name": "x", "scene": {"object": {"shape": "rectangle"}, "effects": [{"name": "wobble"}]}})")
            << "unknown effect 'wobble'";
        QTest::newRow("not an experiment") << R"({"object": {"shape": "rectangle"}})"
                                           << "not an experiment file";
    }

    void badFilesShowTheProblemAndKeepTheSession() {
        QFETCH(QString, text);
        QFETCH(QString, problem);
        const QString path = dir_.filePath("bad.json");
        QFile f(path);
        QVERIFY(f.open(QIODevice::WriteOnly | QIODevice::Truncate));
        f.write(text.toUtf8());
        f.close();
        const QString before = window_->experimentPath();
        const auto run = window_->lastRun();
        QSignalSpy errors(window_.get(), &MainWindow::errorShown);
        QVERIFY(!window_->openExperiment(path));
        QCOMPARE(errors.count(), 1);
        const QString message = errors.takeFirst().at(0).toString();
        QVERIFY2(message.contains(path), qPrintable(message));
        QVERIFY2(message.contains(problem), qPrintable(message));
        QVERIFY(window_->findChild<QMessageBox*>("errorDialog"));
        QCOMPARE(window_->experimentPath(), before);
        QCOMPARE(window_->lastRun(), run);
        closeErrorDialogs(*window_);
    }

    void edgesNoTrainedOrientationFacesAreCautionedOnOpening() {
        const QString path = dir_.filePath("turned.json");
        QFile f(path);
        QVERIFY(f.open(QIODevice::WriteOnly | QIODevice::Truncate));
        f.write(
            QString(
                R"({"extends": "%1", "name": "turned", "following": {"trials": [{"mode": "active", "object": {"shape": "rectangle", "rotation_deg": 30, "offset_mm": [150, 150]}}]}})")
                .arg(sourceFile("experiments/paper.json"))
                .toUtf8());
        f.close();
        auto* log = window_->findChild<QPlainTextEdit*>("log");
        QVERIFY(window_->openExperiment(path));
        const QString text = log->toPlainText();
        const QString opened = text.mid(text.lastIndexOf("opened"));
        QVERIFY2(opened.contains("caution: /following/trials/0 (rectangle): 4 of 4 edges face") &&
                     opened.contains("30 deg off"),
                 qPrintable(opened));
        QVERIFY(window_->openExperiment(sourceFile("experiments/paper.json")));
        QVERIFY(
            !log->toPlainText().mid(log->toPlainText().lastIndexOf("opened")).contains("caution"));
    }

    void polygonFilesLoadIntoTheScenePanel() {
        auto* panel = window_->findChild<ScenePanel*>();
        QVERIFY(panel);
        const SceneSpec before = window_->experimentAsShown().scene;
        QSignalSpy failed(panel, &ScenePanel::failed);
        // Not a polygon: the problem is shown with the file, the shown object stays as it was.
        const QString bad = dir_.filePath("number.json");
        QFile b(bad);
        QVERIFY(b.open(QIODevice::WriteOnly));
        b.write("42");
        b.close();
        QVERIFY(!panel->loadPolygonFrom(bad));
        QCOMPARE(failed.count(), 1);
        const QString message = failed.takeFirst().at(0).toString();
        QVERIFY2(message.startsWith(bad) && message.contains("expected a list of [x, y] vertices"),
                 qPrintable(message));
        closeErrorDialogs(*window_);
        QVERIFY(panel->polygon().empty());
        QCOMPARE(window_->experimentAsShown().scene.object.shape, before.object.shape);
        // A bare list of vertices is the object from then on.
        const QString good = dir_.filePath("square.json");
        QFile g(good);
        QVERIFY(g.open(QIODevice::WriteOnly));
        g.write("[[-20, -20], [20, -20], [20, 20], [-20, 20]]");
        g.close();
        QVERIFY(panel->loadPolygonFrom(good));
        QCOMPARE(failed.count(), 0);
        const SceneSpec after = window_->experimentAsShown().scene;
        QCOMPARE(after.object.shape, std::string("polygon"));
        QCOMPARE(after.object.outline().area(), 40.0 * 40.0);
        // Back to the paper's scene for the tests that follow.
        QVERIFY(window_->openExperiment(sourceFile("experiments/paper.json")));
    }

    void drawingsAndMeshesLoadAsOutlinesAndTheirUnresolvedFeaturesAreShown() {
        auto* panel = window_->findChild<ScenePanel*>();
        QVERIFY(panel);
        QSignalSpy failed(panel, &ScenePanel::failed);
        // The paper's rectangle: every part of it within the patch's reach, nothing said.
        QVERIFY(panel->reachNote().isEmpty());
        const SceneSpec base = window_->experimentAsShown().scene;
        // The lab's drawing: its largest closed outline becomes the object (one a run would
        // refuse to train on, its edges facing no trained orientation; it is shown all the same).
        QVERIFY(panel->loadOutlineFrom(sourceFile("experiments/objects/plate.svg")));
        QCOMPARE(panel->sceneFromPanel(base).object.shape, std::string("polygon"));
        QVERIFY(panel->sceneFromPanel(base).object.outline().area() > 1000.0);
        // A printed part: its units must be given; its height becomes the top height.
        const QString knob = sourceFile("experiments/objects/knob.stl");
        QVERIFY(!panel->loadOutlineFrom(knob));
        QVERIFY2(failed.takeFirst().at(0).toString().contains("does not say its units"),
                 "a mesh without units is refused");
        closeErrorDialogs(*window_);
        QVERIFY(!panel->loadOutlineFrom(knob, "mm"));  // drawn in metres: 0.01 mm high
        QVERIFY2(failed.takeFirst().at(0).toString().contains("the mesh is flat"), "too flat");
        closeErrorDialogs(*window_);
        QVERIFY(panel->loadOutlineFrom(knob, "m"));
        QVERIFY(std::abs(panel->sceneFromPanel(base).object.height_mm - 10.0) < 1e-3);
        // A comb whose teeth are narrower than the fingertip's patch: the panel says where.
        const QString comb = dir_.filePath("comb.json");
        QFile c(comb);
        QVERIFY(c.open(QIODevice::WriteOnly));
        c.write("[[-30,0],[30,0],[30,20],[5,20],[5,26],[3,26],[3,20],[1,20],[1,26],[-1,26],"
                "[-1,20],[-3,20],[-3,26],[-5,26],[-5,20],[-30,20]]");
        c.close();
        QVERIFY(panel->loadOutlineFrom(comb));
        const QString note = panel->reachNote();
        QVERIFY2(note.contains("cannot resolve") && note.contains("tooth"), qPrintable(note));
        QCOMPARE(failed.count(), 0);
        QVERIFY(window_->openExperiment(sourceFile("experiments/paper.json")));
        QVERIFY(panel->reachNote().isEmpty());
    }

    void cleanupTestCase() { closeWindow(); }
};

QTEST_MAIN(TestWindowProtocol)
#include "test_window_protocol.moc"
