// The window runs the paper experiment by clicking, watches the progress reach the end,
// cancels half-way keeping every finished tap, uses a toggled effect in the next run, exports
// every figure in every format, keeps paths and histograms at one scale through resizes and no
// legend over a value, draws the live view only in front, and runs sweeps.
#include <QSpinBox>
#include <QTabWidget>

#include "WindowFixture.h"
#include "app/gui/PlotPanel.h"
#include "app/gui/SeedsTab.h"

class TestWindowRuns : public WindowFixture {
    Q_OBJECT

public:
    // Part of the sweeps test: the curves of (a) carry their intervals and the paper's point;
    // clicking a point of (a) or (b) shows its setting, and the button follows with it.
    void clickingAPointShowsItsSettingAndRunsIt() {
        auto* tab = window_->findChild<SweepsTab*>();
        QVERIFY(tab);
        const auto& sw = window_->lastRun()->sweeps;
        PlotPanel* a = tab->perceptionPanel();
        int bars = 0, stars = 0;
        for (int i = 0; i < a->plot().plottableCount(); ++i) {
            bars += qobject_cast<QCPErrorBars*>(a->plot().plottable(i)) != nullptr;
            stars += a->plot().plottable(i)->name().startsWith("paper: single tap");
        }
        QCOMPARE(bars, 2);   // angle and position, each with its 95 % intervals
        QCOMPARE(stars, 2);  // the paper's single tap on the same taps, in both panels
        // Click the second point of (a)'s first series where it is drawn.
        auto clickPoint = [](PlotPanel* panel, int point) {
            showTab(panel);
            showAt(panel, QSize(1366, 768));
            for (int i = 0; i < panel->plot().graphCount(); ++i) {
                QCPGraph* g = panel->plot().graph(i);
                if (g->property(kSweepRowsProperty).toList().size() <= point) continue;
                const auto it = g->data()->at(point);
                const QPoint at(int(std::lround(g->keyAxis()->coordToPixel(it->key))),
                                int(std::lround(g->valueAxis()->coordToPixel(it->value))));
                QTest::mouseClick(&panel->plot(), Qt::LeftButton, {}, at);
                return g->property(kSweepRowsProperty).toList()[point].toInt();
            }
            return -1;
        };
        const int rowA = clickPoint(a, 1);
        QCOMPARE(rowA, 1);
        QVERIFY(tab->picked());
        QCOMPARE(tab->picked()->beliefThreshold, sw.perception[1].threshold);
        QVERIFY2(tab->pickedText().contains("belief threshold 0.999999"),
                 qPrintable(tab->pickedText()));
        // A point of (b): its follow step.
        const int rowB = clickPoint(tab->followingPanel(), 1);
        QVERIFY(rowB >= 0);
        const FollowingSweepRow& b = sw.following[std::size_t(rowB)];
        QCOMPARE(tab->picked()->followStep_mm, b.followStep_mm);
        const SweepSetting picked = *tab->picked();
        QVERIFY2(tab->pickedText().contains(QString("follow %1 mm").arg(b.followStep_mm)),
                 qPrintable(tab->pickedText()));
        // The button follows with that setting, on the classifier just trained.
        QTRY_VERIFY(!window_->running());
        auto* run = tab->findChild<QPushButton*>("sweepRunPicked");
        QVERIFY(run && run->isEnabled());
        QSignalSpy ended(window_.get(), &MainWindow::runEnded);
        QTest::mouseClick(run, Qt::LeftButton);
        QVERIFY(window_->running());
        QVERIFY(ended.wait(120000));
        const ExperimentSpec& followed = window_->lastRun()->spec;
        QCOMPARE(followed.following.followStep_mm, picked.followStep_mm);
        QCOMPARE(followed.following.repositionStep_mm, picked.repositionStep_mm);
        QCOMPARE(followed.following.beliefThreshold, picked.beliefThreshold);
        // Following alone measures no sweeps: the curves stay.
        QVERIFY(!a->showsEmptyHint() && a->plot().plottableCount() > 0);
        QTRY_VERIFY(!window_->running());
    }

private slots:
    void initTestCase() { openWindow(); }

    void runThePaperExperimentByClicking() {
        // Before any run, every empty figure says what fills it, naming the button to click.
        int hinted = 0;
        for (PlotPanel* p : window_->plotPanels()) {
            if (p->plot().plottableCount() > 0) continue;  // the live plots draw from the start
            QVERIFY2(p->showsEmptyHint(), qPrintable(p->name()));
            QVERIFY2(p->emptyHint().contains("Run") || p->emptyHint().contains("trial") ||
                         p->emptyHint().contains("Compare with"),
                     qPrintable(p->name()));
            QVERIFY2(!drawsAnAxis(p), qPrintable(p->name()));
            ++hinted;
        }
        QCOMPARE(hinted, window_->plotPanels().size() - 2);
        window_->setPace(Pace::Fastest);
        QSignalSpy ended(window_.get(), &MainWindow::runEnded);
        click(*window_, "runAll");
        QVERIFY(window_->running());
        endsSuccessfully(*window_, ended, 120000);
        if (QTest::currentTestFailed()) return;
        QProgressBar* bar = window_->progressBar();
        QCOMPARE(bar->value(), bar->maximum());
        QVERIFY(bar->format().startsWith("finished"));
        const auto run = window_->lastRun();
        QVERIFY(run);
        QCOMPARE(int(run->trials.size()), 10);
        QVERIFY(QFile::exists(window_->lastRunDirectory() + "/summary.json"));
        // The tabs show the run: traces, error maps, paths, histograms, a replay.
        for (PlotPanel* p : window_->plotPanels())
            if (filledByARun(p))
                QVERIFY2(p->plot().plottableCount() > 0 && !p->showsEmptyHint() && drawsAnAxis(p),
                         qPrintable(p->name()));
        // The recognition tab's confusion, for each rule: a row per shape traced, a column per
        // shape named, each recognised trial in one cell.
        for (const bool smoothed : {false, true}) {
            auto* table = window_->findChild<QTableWidget*>(smoothed ? "confusionSmoothed"
                                                                     : "confusionPaperRule");
            QVERIFY(table);
            QCOMPARE(table->rowCount(), 4);
            int recognised = 0;
            for (int a = 0; a < 4; ++a)
                for (int b = 0; b < 4; ++b) {
                    const std::string traced = table->verticalHeaderItem(a)->text().toStdString(),
                                      named = table->horizontalHeaderItem(b)->text().toStdString();
                    int n = 0;
                    for (const auto& t : run->trials)
                        n += t.recognised && t.label == traced &&
                             (smoothed ? t.recognition.predictedSmoothed
                                       : t.recognition.predicted) == named;
                    QCOMPARE(table->item(a, b)->text().toInt(), n);
                    recognised += n;
                }
            QCOMPARE(recognised, 8);
        }
        FollowingTab* following = window_->followingTab();
        following->replay(3, 10);
        QVERIFY(following->replayText().contains("Rule '"));
        // Play runs the replay on to the trial's last tap and stops there.
        const int last = int(run->trials[3].result.taps.size()) - 1;
        following->replay(3, last - 4);
        auto* play = following->findChild<QPushButton*>("replayPlay");
        QVERIFY(play);
        QTest::mouseClick(play, Qt::LeftButton);
        QVERIFY(following->playing());
        QCOMPARE(play->text(), QString("Pause"));
        QTRY_VERIFY_WITH_TIMEOUT(!following->playing(), 10000);
        QCOMPARE(following->replayedTrial(), 3);
        QCOMPARE(following->replayedTap(), last);
        QCOMPARE(play->text(), QString("Play"));
        QVERIFY(following->replayText().startsWith(QString("Tap %1 of %1 ").arg(last + 1)));
        QVERIFY(window_->liveView()->framesDrawn() > 0);
    }

    void calibrateFitsARunsTapsAndSavesTheScene() {
        // The last run's training and test taps (runThePaperExperimentByClicking) fitted from the
        // experiment's scene, in the Calibrate dialog the Run menu opens.
        QAction* action = window_->findChild<QAction*>("calibrate");
        QVERIFY(action && action->isEnabled());
        const QString recording = window_->lastRunDirectory() + "/data/taps.csv";
        QVERIFY(QFile::exists(recording));
        CalibrationDialog* dialog = window_->calibrateRecording(recording);
        QVERIFY(dialog);
        QSignalSpy done(dialog, &CalibrationDialog::fitFinished);
        QVERIFY(done.wait(180000));
        QCOMPARE(done.front().front().toBool(), true);
        QMap<QString, QString> listed;
        QTableWidget* choices = dialog->choicesTable();
        for (int r = 0; r < choices->rowCount(); ++r)
            listed[choices->item(r, 0)->text()] = choices->item(r, 1)->text();
        QCOMPARE(listed["taxel_noise"], "yes");
        QCOMPARE(listed["adc_quantisation"], "yes");
        QCOMPARE(listed["taxel_gain"], "no");
        QCOMPARE(listed["viscoelastic_memory"], "yes");  // the paper scene's pad remembers
        QCOMPARE(listed["contact_latency"], "yes");      // read from the stop depths
        QCOMPARE(listed["stage_error"], "kept");
        bool sigma = false;
        QTableWidget* estimates = dialog->estimatesTable();
        for (int r = 0; r < estimates->rowCount(); ++r)
            if (estimates->item(r, 1)->text() == "sigma_counts") {
                sigma = true;
                QVERIFY2(std::abs(estimates->item(r, 2)->text().toDouble() - 1.5) < 0.15,
                         qPrintable(estimates->item(r, 2)->text()));
            }
        QVERIFY(sigma);
        QCOMPARE(dialog->taxelsTable()->rowCount(), 12);
        QVERIFY(dialog->findChild<QPushButton*>("saveFittedScene")->isEnabled());
        const QString saved = dir_.filePath("fitted_scene.json");
        QCOMPARE(dialog->saveFittedScene(saved), QString());
        const SceneSpec fitted = loadScene(saved.toStdString());
        QCOMPARE(fitted.effects.size(), window_->lastRun()->spec.scene.effects.size());
        dialog->close();

        // A fitted scene's measured gains pass through the scene panel as they are.
        SceneSpec withGains = window_->lastRun()->spec.scene;
        EffectSpec gain;
        gain.name = "taxel_gain";
        const std::vector<double> gains{1.2, 0.8, 1, 1, 1, 1, 1, 1, 1, 1, 1, 0.6};
        gain.parameters = Json{{"gains", gains}};
        withGains.effects.push_back(gain);
        window_->scenePanel()->showScene(withGains);
        const SceneSpec shown = window_->scenePanel()->sceneFromPanel(withGains);
        bool found = false;
        for (const auto& e : shown.effects)
            if (e.name == "taxel_gain") {
                found = true;
                QCOMPARE(e.parameters.at("gains").get<std::vector<double>>(), gains);
                QVERIFY(!e.parameters.contains("spread"));
            }
        QVERIFY(found);
        window_->scenePanel()->showScene(window_->lastRun()->spec.scene);

        // A file that is no recording is said in the dialog; nothing is fitted.
        CalibrationDialog* bad = window_->calibrateRecording(dir_.filePath("nowhere.csv"));
        QSignalSpy failed(bad, &CalibrationDialog::fitFinished);
        QVERIFY(failed.wait(30000));
        QCOMPARE(failed.front().front().toBool(), false);
        QVERIFY(!bad->fit());
        QVERIFY(bad->findChild<QLabel*>("calibrationStatus")->text().contains("nowhere.csv"));
        bad->close();
    }

    void engineWorkStartsFromACleanVectorState() {
        // Once the toolkit has drawn, threads may start with the upper halves of the vector
        // registers in use, which makes libm's exp some thirty times slower (VectorState.h). A
        // thread that starts so has them cleared once the contact model, thousands of exp calls,
        // is built. Earlier runs in this process may have cleared the main thread's state, so it
        // is put back as the drawing code leaves it, and cleared again after.
#if defined(__x86_64__)
        unsigned eax = 0, ebx = 0, ecx = 0, edx = 0;
        if (!__get_cpuid_count(0xD, 1, &eax, &ebx, &ecx, &edx) || !(eax & (1u << 2)) ||
            !__builtin_cpu_supports("avx"))
            QSKIP("this CPU cannot say which register state is in use (XGETBV with ECX = 1)");
        const FingertipSpec fingertip =
            loadExperiment(sourceFile("experiments/paper.json").toStdString()).scene.fingertip;
        bool dirtyBefore = false, dirtyAfter = true;
        markUpperHalvesInUse();
        std::thread([&] {
            dirtyBefore = (vectorStateInUse() & kUpperHalvesInUse) != 0;
            const FingertipContactModel model(fingertip);
            dirtyAfter = (vectorStateInUse() & kUpperHalvesInUse) != 0;
        }).join();
        clearUpperVectorState();
        if (!dirtyBefore)
            QSKIP(
                "on this machine a new thread starts with the upper halves clear, so there is "
                "nothing for the model to clear");
        QVERIFY(!dirtyAfter);
#else
        QSKIP("the vector state in question is x86-64's");
#endif
    }

    void theLiveViewDrawsOnlyWhileInFront() {
        LiveFeed feed;
        QTabWidget tabs;
        auto* live = new LiveView(feed);
        tabs.addTab(live, "Live");
        tabs.addTab(new QLabel("another tab"), "Other");
        tabs.resize(900, 600);
        tabs.show();
        QVERIFY(QTest::qWaitForWindowExposed(&tabs));
        // One bar per taxel, each in the taxel's colour.
        QCOMPARE(live->barsPanel()->plot().plottableCount(), kFingertipTaxels);
        const auto shownValues = [&] {
            std::vector<double> v;
            for (int k = 0; k < kFingertipTaxels; ++k) {
                auto* bars = qobject_cast<QCPBars*>(live->barsPanel()->plot().plottable(k));
                for (auto it = bars->data()->constBegin(); it != bars->data()->constEnd(); ++it)
                    v.push_back(it->value);
            }
            return v;
        };
        std::vector<double> frame(kFingertipTaxels);
        const auto publish = [&](double base) {
            for (int k = 0; k < kFingertipTaxels; ++k) frame[k] = base + k;
            feed.publishFrame(frame.data(), kFingertipTaxels);
        };
        publish(10);
        QTRY_COMPARE(shownValues(), frame);
        QTRY_VERIFY(live->framesDrawn() > 0);
        // Behind another tab it keeps the newest frame in its data but draws nothing.
        tabs.setCurrentIndex(1);
        const std::uint64_t drawn = live->framesDrawn();
        for (int i = 0; i < 5; ++i) {
            publish(100 + i);
            QTest::qWait(30);
        }
        QTRY_COMPARE(shownValues(), frame);
        QCOMPARE(live->framesDrawn(), drawn);
        // Brought back, it draws what changed meanwhile without waiting for another frame.
        tabs.setCurrentIndex(0);
        QTRY_COMPARE(live->framesDrawn(), drawn + 1);
        QTest::qWait(100);
        QCOMPARE(live->framesDrawn(), drawn + 1);  // and nothing again until the feed moves
        QCOMPARE(shownValues(), frame);
    }

    void exportingLeavesThePlotOnScreenAsItWas() {
        // Each figure of a run, shown on its tab, exported at a single column and at a pixel size
        // of another shape: the plot on screen keeps its size, viewport and buffers, and is pixel
        // for pixel what it was before.
        auto* tabs = window_->findChild<QTabWidget*>();
        QVERIFY(tabs);
        QDir().mkpath(dir_.filePath("unchanged"));
        int compared = 0;
        double figure6Single = 0.0;
        for (PlotPanel* p : window_->plotPanels()) {
            if (!filledByARun(p)) continue;
            for (QWidget* w = p; w; w = w->parentWidget())
                if (const int i = tabs->indexOf(w); i >= 0) tabs->setCurrentIndex(i);
            if (!p->isVisible() || p->plot().width() < 50) continue;
            QTest::qWait(100);
            const QSize shown = p->plot().size();
            const QImage before = p->plot().grab().toImage();
            const double ratio = p->plot().bufferDevicePixelRatio();
            const QString base = dir_.filePath("unchanged/" + p->name());
            p->exportTo(base, {"png", "pdf"}, FigureSize::physical(kSingleColumn_mm, 75, 300));
            p->exportTo(base + "_px", {"png"}, {700, 1100, 100});
            // The export dialog's presets ask the figure's own height at a width: off screen too.
            const double single = p->ownHeightAt(kSingleColumn_mm);
            QVERIFY2(single > 20.0, qPrintable(p->name()));
            if (p->name() == "figure6_errors") figure6Single = single;
            QTest::qWait(100);
            QCOMPARE(p->plot().size(), shown);
            QCOMPARE(p->plot().viewport(), p->plot().rect());
            QCOMPARE(p->plot().bufferDevicePixelRatio(), ratio);
            const QImage after = p->plot().grab().toImage();
            QCOMPARE(after.size(), before.size());
            QVERIFY2(after == before, qPrintable(p->name() + " changed on screen"));
            ++compared;
        }
        QVERIFY(compared >= 4);
        // Figure 6's own height: its usual 115 mm at a double column; taller at a single column,
        // where its panels go one to a line; the same whatever the window's shape.
        PlotPanel* errors = nullptr;
        for (PlotPanel* p : window_->plotPanels())
            if (p->name() == "figure6_errors") errors = p;
        QVERIFY(errors && figure6Single > 0.0);
        QCOMPARE(errors->ownHeightAt(kDoubleColumn_mm), 115.0);
        QVERIFY2(figure6Single > 150.0, qPrintable(QString::number(figure6Single)));
        const QSize windowSize = window_->size();
        window_->resize(900, 1000);
        QTest::qWait(100);
        QCOMPARE(errors->ownHeightAt(kSingleColumn_mm), figure6Single);
        window_->resize(windowSize);
        QTest::qWait(100);
        // The export dialogs start in the results folder, not where the workbench was launched.
        const QString folder = QDir(window_->outputBase()).absolutePath();
        for (PlotPanel* p : window_->plotPanels())
            QCOMPARE(QFileInfo(p->suggestedPath("pdf")).absolutePath(), folder);
    }

    void everyFigureExportsInEveryFormat() {
        for (PlotPanel* p : window_->plotPanels()) {
            const QString base = dir_.filePath("export/" + p->name());
            QDir().mkpath(dir_.filePath("export"));
            const QStringList files = p->exportTo(base, {"png", "pdf", "svg"}, {1200, 800, 120});
            QCOMPARE(files.size(), 3);
            QFile png(base + ".png"), pdf(base + ".pdf"), svg(base + ".svg");
            QVERIFY(png.open(QIODevice::ReadOnly) && pdf.open(QIODevice::ReadOnly) &&
                    svg.open(QIODevice::ReadOnly));
            QVERIFY(png.read(8) == QByteArray("\x89PNG\r\n\x1a\n", 8));
            QVERIFY(pdf.read(5) == "%PDF-");
            QVERIFY(svg.readAll().contains("<svg"));
            QImage image(base + ".png");
            QCOMPARE(image.width(), 1200);
            p->exportCsv(base + ".csv");
            if (filledByARun(p)) QVERIFY2(linesIn(base + ".csv") > 1, qPrintable(p->name()));
        }
        // A plot's data that the disk cannot take whole is refused, naming the file and why, and
        // leaves the file as it was.
        PlotPanel* first = window_->plotPanels().front();
        const QString kept = dir_.filePath("export/" + first->name() + ".csv");
        QFile before(kept);
        QVERIFY(before.open(QIODevice::ReadOnly));
        const QByteArray keptText = before.readAll();
        before.close();
        QVERIFY(keptText.size() > 100);
        {
            QString message;
            try {
                test::FileSizeLimit limit(100);
                first->exportCsv(kept);
            } catch (const std::exception& e) {
                message = e.what();
            }
            QVERIFY2(message.contains(kept) && message.contains("could not write"),
                     qPrintable(message));
        }
        QVERIFY(before.open(QIODevice::ReadOnly));
        QCOMPARE(before.readAll(), keptText);
        before.close();

        const QStringList all = window_->exportAllFigures(dir_.filePath("all"));
        QVERIFY(all.size() >= 6);
        for (const QString& f : all) QVERIFY(QFileInfo(f).size() > 0);
    }

    void pathsAndHistogramsKeepEqualAspectThroughResizes() {
        // Outlines and path histograms are drawn one unit per pixel on both axes, whatever shape
        // the window takes, and going back to a size gives back the same view.
        const QSize start = window_->size();
        for (const QString name : {"figure8_active_paths", "figure9_recognition"}) {
            PlotPanel* panel = nullptr;
            for (PlotPanel* p : window_->plotPanels())
                if (p->name() == name) panel = p;
            QVERIFY2(panel, qPrintable(name));
            showTab(panel);
            QMap<int, QPair<QCPRange, QCPRange>> first, again;
            showAt(panel, start);
            test::checkEqualAspect(panel->plot(), panel->name(), first);
            if (QTest::currentTestFailed()) return;
            QVERIFY2(first.size() >= 4, qPrintable(name));
            for (QSize size : {QSize(1900, 700), QSize(1280, 1100), QSize(1300, 900)}) {
                showAt(panel, size);
                QMap<int, QPair<QCPRange, QCPRange>> views;
                test::checkEqualAspect(panel->plot(), panel->name(), views);
                if (QTest::currentTestFailed()) return;
                test::checkLegendsClearOfData(panel->plot(), panel->name());
                if (QTest::currentTestFailed()) return;
                test::checkLabelsFitTheirPanels(panel->plot(), panel->name());
                if (QTest::currentTestFailed()) return;
            }
            showAt(panel, start);
            test::checkEqualAspect(panel->plot(), panel->name(), again);
            if (QTest::currentTestFailed()) return;
            QCOMPARE(again.keys(), first.keys());
            for (int k : first.keys()) {
                const QString what = QString("%1 panel %2").arg(name).arg(k);
                QVERIFY2(std::abs(again[k].first.lower - first[k].first.lower) < 1e-6 &&
                             std::abs(again[k].first.upper - first[k].first.upper) < 1e-6 &&
                             std::abs(again[k].second.lower - first[k].second.lower) < 1e-6 &&
                             std::abs(again[k].second.upper - first[k].second.upper) < 1e-6,
                         qPrintable(what));
            }
        }
    }

    void cancelHalfWayKeepsTheFinishedTaps() {
        window_->setPace(Pace::LiveFrames);  // one tap a second
        QSignalSpy ended(window_.get(), &MainWindow::runEnded);
        QVERIFY(window_->startRun(RunController::What::Everything));
        const QString taps = window_->lastRunDirectory() + "/data/taps.csv";
        QTRY_VERIFY_WITH_TIMEOUT(linesIn(taps) >= 1 + 3 * 50, 30000);
        click(*window_, "cancel");
        QVERIFY(ended.wait(10000));
        QCOMPARE(ended.takeFirst().at(0).toBool(), false);
        const auto run = window_->lastRun();
        QVERIFY(run->cancelled);
        QVERIFY(run->taps.size() >= 3);
        QVERIFY(run->taps.size() < 360);
        QCOMPARE(linesIn(taps), 1 + int(run->taps.size()) * 50);  // every finished tap, whole
        QVERIFY(window_->progressBar()->format().startsWith("cancelled"));
        QTRY_VERIFY(!window_->running());
    }

    void toggledEffectIsUsedByTheNextRun() {
        window_->setPace(Pace::Fastest);
        QGroupBox* crosstalk = window_->findChild<QGroupBox*>("effect_crosstalk");
        QVERIFY(crosstalk);
        QVERIFY(!crosstalk->isChecked());
        clickCheckBox(crosstalk);
        QVERIFY(crosstalk->isChecked());
        QSignalSpy ended(window_.get(), &MainWindow::runEnded);
        QVERIFY(window_->startRun(RunController::What::TrainingOnly));
        QVERIFY(ended.wait(60000));
        const auto& active = window_->lastRun()->activeEffects;
        QVERIFY(std::find(active.begin(), active.end(), "crosstalk") != active.end());
        QFile summary(window_->lastRunDirectory() + "/summary.json");
        QVERIFY(summary.open(QIODevice::ReadOnly));
        QVERIFY(summary.readAll().contains("\"crosstalk\""));
        clickCheckBox(crosstalk);
        QVERIFY(!crosstalk->isChecked());
        QTRY_VERIFY(!window_->running());
        QVERIFY(window_->startRun(RunController::What::TrainingOnly));
        QVERIFY(ended.wait(60000));
        const auto& again = window_->lastRun()->activeEffects;
        QVERIFY(std::find(again.begin(), again.end(), "crosstalk") == again.end());
        QTRY_VERIFY(!window_->running());
    }

    void sweepsRunFromTheWindowAndShowTheirPlots() {
        // The accuracy-versus-time experiment, trimmed to small sweeps, run from the window.
        const QString path = dir_.filePath("sweeps.json");
        QFile f(path);
        QVERIFY(f.open(QIODevice::WriteOnly));
        f.write(QString(R"({"name": "sweeps", "scene": "%1",
            "following": {"trials": [{"object": {"shape": "rectangle", "width_mm": 48, "height_mm": 58, "offset_mm": [150, 150]}}]},
            "sweeps": {"perception": {"belief_thresholds": [0.5, 0.999999]},
                       "following": {"follow_steps_mm": [2, 3], "reposition_steps_mm": [1], "modes": ["active"]},
                       "compute": {"bins": [50, 100], "samples_per_tap": [25, 50]}}})")
                    .arg(sourceFile("experiments/scenes/paper_rectangle.json"))
                    .toUtf8());
        f.close();
        QVERIFY(window_->openExperiment(path));
        // Until a run measures them, the sweep plots say how to get them.
        for (PlotPanel* p : window_->plotPanels())
            if (p->name().startsWith("sweep")) {
                QVERIFY2(p->showsEmptyHint(), qPrintable(p->name()));
                QVERIFY(p->emptyHint().contains("accuracy_vs_time.json"));
            }
        window_->setPace(Pace::Fastest);
        QSignalSpy ended(window_.get(), &MainWindow::runEnded);
        QVERIFY(window_->startRun(RunController::What::Everything));
        QVERIFY(ended.wait(120000));
        const auto& sw = window_->lastRun()->sweeps;
        QCOMPARE(int(sw.perception.size()), 2);
        QCOMPARE(int(sw.following.size()), 2);
        QCOMPARE(int(sw.compute.size()), 4);
        for (PlotPanel* p : window_->plotPanels())
            if (p->name().startsWith("sweep"))
                QVERIFY2(p->plot().plottableCount() > 0 && !p->showsEmptyHint(),
                         qPrintable(p->name()));
        clickingAPointShowsItsSettingAndRunsIt();
        if (QTest::currentTestFailed()) return;
        // This experiment recognises nothing: the recognition tab says so and claims no accuracy.
        for (PlotPanel* p : window_->plotPanels())
            if (p->name() == "figure9_recognition") {
                QVERIFY(p->showsEmptyHint());
                QVERIFY2(p->emptyHint().contains("no recognition step"),
                         qPrintable(p->emptyHint()));
                auto* title = qobject_cast<QCPTextElement*>(p->plot().plotLayout()->element(0, 0));
                QVERIFY(title);
                QVERIFY2(!title->text().contains('%'), qPrintable(title->text()));
            }
        QTRY_VERIFY(!window_->running());
        QVERIFY(window_->openExperiment(sourceFile("experiments/paper.json")));
    }

    void legendsLeaveEveryValueInSight() {
        // After a run, a sweep and a seeds run every figure in the window has data: no legend
        // drawn inside a panel hides a point, a path or a bar of it.
        int checked = 0;
        for (PlotPanel* panel : window_->plotPanels()) {
            showTab(panel);
            showAt(panel, window_->size());
            test::checkLegendsClearOfData(panel->plot(), panel->name());
            if (QTest::currentTestFailed()) return;
            test::checkLabelsFitTheirPanels(panel->plot(), panel->name());
            if (QTest::currentTestFailed()) return;
            checked += panel->plot().plottableCount() > 0;
        }
        QVERIFY(checked >= 6);
        // The rates over seeds sit beside their table: narrower windows narrow the figure, and
        // its legends still show every entry whole.
        PlotPanel* seeds = nullptr;
        for (PlotPanel* p : window_->plotPanels())
            if (p->name() == "seed_rates") seeds = p;
        QVERIFY(seeds);
        showTab(seeds);
        const QSize start = window_->size();
        for (QSize size : {QSize(1900, 700), QSize(1300, 900), QSize(1280, 720)}) {
            showAt(seeds, size);
            test::checkLabelsFitTheirPanels(
                seeds->plot(),
                QString("%1 at %2 x %3").arg(seeds->name()).arg(size.width()).arg(size.height()));
            if (QTest::currentTestFailed()) return;
        }
        showAt(seeds, start);
    }

    void standardSweepsAreOfferedOnAnExperimentWithout() {
        const QString path = dir_.filePath("no_sweeps.json");
        QFile f(path);
        QVERIFY(f.open(QIODevice::WriteOnly));
        f.write(QString(R"({"name": "no_sweeps", "scene": "%1",
            "following": {"trials": [{"object": {"shape": "rectangle", "width_mm": 48, "height_mm": 58, "offset_mm": [150, 150]}}]}})")
                    .arg(sourceFile("experiments/scenes/paper_rectangle.json"))
                    .toUtf8());
        f.close();
        QTRY_VERIFY(!window_->running());
        QVERIFY(window_->openExperiment(path));
        window_->setPace(Pace::Fastest);
        auto* tab = window_->findChild<SweepsTab*>();
        auto* offer = tab->findChild<QPushButton*>("sweepRunStandard");
        QVERIFY(offer);
        QSignalSpy ended(window_.get(), &MainWindow::runEnded);
        QVERIFY(window_->startRun(RunController::What::TrainingOnly));
        QVERIFY(ended.wait(60000));
        QVERIFY(!offer->isHidden());
        QTRY_VERIFY(!window_->running());
        // It runs the experiment shown with the standard sweeps; stopped at once here.
        QTest::mouseClick(offer, Qt::LeftButton);
        QVERIFY(window_->running());
        window_->cancelRun();
        QVERIFY(ended.wait(120000));
        QTRY_VERIFY(!window_->running());
        QVERIFY2(window_->lastRunDirectory().contains("no_sweeps_sweeps"),
                 qPrintable(window_->lastRunDirectory()));
        QVERIFY(window_->lastRun()->spec.sweeps.any());
        const SweepSpec standard = standardSweeps();
        const SweepSpec file =
            loadExperiment(sourceFile("experiments/accuracy_vs_time.json").toStdString()).sweeps;
        QVERIFY(standard.beliefThresholds == file.beliefThresholds);
        QVERIFY(standard.followSteps_mm == file.followSteps_mm);
        QVERIFY(standard.followingBeliefThresholds == file.followingBeliefThresholds);
        QVERIFY(standard.bins == file.bins && standard.samplesPerTap == file.samplesPerTap);
        QCOMPARE(standard.tapsPerClass, file.tapsPerClass);
        QVERIFY(window_->openExperiment(sourceFile("experiments/paper.json")));
    }

    void sweepsOverSeedsAreShownAfterASeedsRun() {
        // A small experiment with sweeps run over seeds 1-3 from the Seeds tab: the Accuracy vs
        // time tab shows (a) over the seeds with its intervals and (b)'s Pareto front.
        const QString path = dir_.filePath("small_sweeps.json");
        QFile f(path);
        QVERIFY(f.open(QIODevice::WriteOnly));
        f.write(QString(R"({"name": "small_sweeps", "scene": "%1",
            "training": {"data_sets": 3, "training_sets": [1]},
            "following": {"trials": [{"object": {"shape": "rectangle", "width_mm": 48, "height_mm": 58, "offset_mm": [150, 150]}}]},
            "sweeps": {"perception": {"belief_thresholds": [0.9, 0.99], "taps_per_class": 3, "max_taps_per_decision": 6},
                       "following": {"follow_steps_mm": [2, 3], "reposition_steps_mm": [1], "belief_thresholds": [0], "modes": ["active"], "repeats": 1}}})")
                    .arg(sourceFile("experiments/scenes/paper_rectangle.json"))
                    .toUtf8());
        f.close();
        QTRY_VERIFY(!window_->running());
        QVERIFY(window_->openExperiment(path));
        auto* tab = window_->findChild<SweepsTab*>();
        QVERIFY(tab->perceptionOverSeedsPanel()->showsEmptyHint());
        SeedsTab* seeds = window_->seedsTab();
        seeds->findChild<QSpinBox*>("firstSeed")->setValue(1);
        seeds->findChild<QSpinBox*>("lastSeed")->setValue(3);
        QSignalSpy ended(window_.get(), &MainWindow::runEnded);
        QTest::mouseClick(seeds->findChild<QPushButton*>("runSeeds"), Qt::LeftButton);
        QVERIFY(ended.wait(120000));
        QVERIFY(ended.takeFirst().at(0).toBool());
        QTRY_VERIFY(!window_->running());
        for (PlotPanel* panel : {tab->perceptionOverSeedsPanel(), tab->paretoOverSeedsPanel()}) {
            QVERIFY2(!panel->showsEmptyHint(), qPrintable(panel->name()));
            QVERIFY(panel->plot().plottableCount() > 0);
            QVERIFY(panel->plot().plotLayout()->elementCount() > 0);
        }
        // (a): one point per threshold, its x the mean taps over the seeds.
        const QCPGraph* curve = tab->perceptionOverSeedsPanel()->plot().graph(0);
        QCOMPARE(curve->dataCount(), 2);
        QVERIFY(curve->data()->at(1)->key >= curve->data()->at(0)->key);
        QVERIFY(QFileInfo(window_->lastSeedsDirectory() + "/figures/sweeps_following_pareto.png")
                    .size() > 0);
        QVERIFY(window_->openExperiment(sourceFile("experiments/paper.json")));
    }

    void cleanupTestCase() {
        closeWindow();
    }
};

QTEST_MAIN(TestWindowRuns)
#include "test_window_runs.moc"
