// The window over seeds: rates over a range of seeds, a seed's row opening its run,
// cancelling and keeping every finished seed, and two experiments compared trial by trial.
#include <QDockWidget>

#include "WindowFixture.h"

class TestWindowSeeds : public WindowFixture {
    Q_OBJECT

private slots:
    void initTestCase() { openWindow(); }

    void twoExperimentsAreComparedTrialByTrialFromTheWindow() {
        // The paper as shown (A) against its kernel variant (B) on seeds 3 and 4: a row for each
        // trial the two ended differently, the same trials compare.csv says differ, and at the
        // end each side's rates with McNemar's p.
        ComparisonTab* tab = window_->comparisonTab();
        auto* compare = tab->findChild<QPushButton*>("compareWith");
        auto* first = tab->findChild<QSpinBox*>("compareFirstSeed");
        auto* last = tab->findChild<QSpinBox*>("compareLastSeed");
        QVERIFY(compare && first && last);
        QVERIFY(compare->isEnabled());
        QSignalSpy ended(window_.get(), &MainWindow::runEnded);
        // Chosen B, the window asks before running both over the seeds: No runs nothing.
        const QString kernel = sourceFile("experiments/paper_kernel.json");
        QString asked;
        auto answer = [&](QMessageBox::StandardButton button) {
            QTimer::singleShot(50, this, [&asked, button] {
                auto* box = qobject_cast<QMessageBox*>(QApplication::activeModalWidget());
                if (!box) return;
                asked = box->objectName() + ": " + box->text();
                box->button(button)->click();
            });
        };
        answer(QMessageBox::No);
        QVERIFY(!window_->confirmComparison(kernel, 3, 4));
        QVERIFY2(asked.startsWith("compareQuestion: Compare paper (A, as shown) with "
                                  "paper_kernel.json (B) on seeds 3-4?") &&
                     asked.contains("That is 4 whole runs"),
                 qPrintable(asked));
        QVERIFY(!window_->running());
        QVERIFY(compare->isEnabled());
        answer(QMessageBox::Yes);
        QVERIFY(window_->confirmComparison(kernel, 3, 4));
        QVERIFY(!compare->isEnabled());  // one run at a time
        QCOMPARE(window_->tabs()->currentWidget(), tab);
        QCOMPARE(first->value(), 3);  // the boxes show the seeds being compared
        QCOMPARE(last->value(), 4);
        endsSuccessfully(*window_, ended);
        QVERIFY(compare->isEnabled());
        const QString dir = window_->lastComparisonDirectory();
        QVERIFY(QFile::exists(dir + "/compare.json"));
        QFile csv(dir + "/compare.csv");
        QVERIFY(csv.open(QIODevice::ReadOnly));
        const QList<QByteArray> rows = csv.readAll().trimmed().split('\n');
        QCOMPARE(rows.size(), 1 + 2 * 10);
        int differ = 0;
        for (int i = 1; i < rows.size(); ++i) {
            const QList<QByteArray> f = rows[i].split(',');
            differ += f[4] != f[5] || f[6] != f[7];
        }
        QCOMPARE(tab->table()->rowCount(), differ);
        const QString summary = tab->summaryText();
        QVERIFY2(summary.contains("A = paper, B = paper_kernel, 2 seeds, trial by trial:") &&
                     summary.contains("McNemar p") && summary.contains("finished; results in"),
                 qPrintable(summary));
        // The differences with their intervals, and how each settled over the two seeds, on
        // screen and in the folder.
        QCustomPlot& plot = tab->plotPanel()->plot();
        QCOMPARE(plot.graphCount(), 4 + 4 * 3);  // a point per part; a line between band edges
        for (int i = 0; i < plot.graphCount(); ++i)
            QCOMPARE(plot.graph(i)->data()->size(), i < 4 ? 1 : 2);
        QVERIFY(QFileInfo(dir + "/figures/compare.png").size() > 0);

        // A trial the two ended differently, shown in both: its seed runs again in each
        // experiment as compared, and the two paths are drawn on the object.
        auto* showPair = tab->findChild<QPushButton*>("showTrialPair");
        QVERIFY(showPair);
        QVERIFY(!showPair->isEnabled());  // nothing selected yet
        QVERIFY(tab->pairPanel()->showsEmptyHint());
        QVERIFY(tab->table()->rowCount() > 0);
        tab->table()->selectRow(0);
        QVERIFY(showPair->isEnabled());
        const quint64 seed = tab->table()->item(0, 0)->text().toULongLong();
        const QString label = tab->table()->item(0, 2)->text();
        const int trial = tab->table()->item(0, 3)->text().toInt();
        const FollowingMode mode = tab->table()->item(0, 1)->text() == "active"
                                       ? FollowingMode::Active
                                       : FollowingMode::Passive;
        QTest::mouseClick(showPair, Qt::LeftButton);
        QVERIFY(window_->running());
        QVERIFY(!showPair->isEnabled() && !compare->isEnabled());
        endsSuccessfully(*window_, ended);
        if (QTest::currentTestFailed()) return;
        QVERIFY(showPair->isEnabled());
        const TrialPairRun direct = runTrialPair(
            simulatedRigs(), loadExperiment(sourceFile("experiments/paper.json").toStdString()),
            loadExperiment(sourceFile("experiments/paper_kernel.json").toStdString()), seed, mode,
            label.toStdString(), trial);
        // The row said they ended differently; so does the rerun.
        QVERIFY(trialOutcome(direct.a) != trialOutcome(direct.b) ||
                namedPath(direct.a) != namedPath(direct.b));
        QCOMPARE(QString::fromStdString(trialOutcome(direct.a)),
                 tab->table()->item(0, 4)->text().section(", named", 0, 0));
        for (int column : {4, 5})  // cut in their columns, whole in their tooltips
            QCOMPARE(tab->table()->item(0, column)->toolTip(),
                     tab->table()->item(0, column)->text());
        QCustomPlot& pairPlot = tab->pairPanel()->plot();
        QTRY_VERIFY(!tab->pairPanel()->showsEmptyHint());
        // Its tab comes forward beside the table.
        QCOMPARE(tab->findChild<QTabWidget*>("comparisonFigures")->currentWidget(),
                 tab->pairPanel());
        QStringList drawn;
        for (int i = 0; i < pairPlot.plottableCount(); ++i) {
            auto* curve = qobject_cast<QCPCurve*>(pairPlot.plottable(i));
            if (!curve || (!curve->name().startsWith(QString("A ")) &&
                           !curve->name().startsWith(QString("B "))))
                continue;
            drawn << curve->name().simplified();  // the reason an end had is on a line of its own
            const TrialRun& run = curve->name().startsWith("A ") ? direct.a : direct.b;
            QCOMPARE(curve->data()->size(), int(run.result.path().size()));
            QCOMPARE(curve->data()->at(0)->key, run.result.path().front().x);
            QCOMPARE((curve->data()->end() - 1)->value, run.result.path().back().y);
        }
        QCOMPARE(drawn.size(), 2);
        // A's legend entry says how its trial ended, its taps, and why where there is a reason.
        const QString outcomeA = QString::fromStdString(trialOutcome(direct.a));
        const qsizetype why = outcomeA.indexOf(" (");
        QVERIFY2(drawn[0].startsWith("A paper: " + outcomeA.left(why) + ", " +
                                     QString::number(direct.a.result.taps.size()) + " taps"),
                 qPrintable(drawn.join(" | ")));
        if (why >= 0) QVERIFY2(drawn[0].endsWith(outcomeA.mid(why)), qPrintable(drawn[0]));
        QVERIFY2(drawn[1].startsWith("B paper_kernel: "), qPrintable(drawn.join(" | ")));
        // Its table and figure are in the comparison's folder, as compare --show writes them.
        const QString stem = QString::fromStdString(trialPairFileStem(direct));
        int rowsA = 0, rowsB = 0;
        for (const QString& row : test::linesOf(dir + "/" + stem + ".csv").mid(1)) {
            rowsA += row.startsWith("a,\"paper\",");
            rowsB += row.startsWith("b,\"paper_kernel\",");
        }
        QCOMPARE(rowsA, int(direct.a.result.taps.size()));
        QCOMPARE(rowsB, int(direct.b.result.taps.size()));
        for (const char* format : {"png", "pdf", "svg"})
            QVERIFY(QFileInfo(dir + "/figures/" + stem + "." + format).size() > 0);
        QVERIFY2(window_->findChild<QPlainTextEdit*>("log")->toPlainText().contains(stem +
                                                                                    ".* in " + dir),
                 qPrintable(stem));
        // A disk that cannot take them: the pair is drawn all the same and the error names the
        // table.
        QVERIFY(tab->table()->rowCount() > 1);
        tab->table()->selectRow(1);
        const quint64 seed1 = tab->table()->item(1, 0)->text().toULongLong();
        QSignalSpy writeErrors(window_.get(), &MainWindow::errorShown);
        {
            test::FileSizeLimit limit(100);
            QTest::mouseClick(showPair, Qt::LeftButton);
            endsSuccessfully(*window_, ended);
        }
        if (QTest::currentTestFailed()) return;
        QCOMPARE(writeErrors.count(), 1);
        const QString writeError = writeErrors.first().at(0).toString();
        QVERIFY2(writeError.contains("Could not write the trial's table and figure") &&
                     writeError.contains(QString("trial_pair_seed%1_").arg(seed1)) &&
                     writeError.contains(".csv"),
                 qPrintable(writeError));
        QVERIFY2(pairPlot.plotLayout()->elementCount() > 0 &&
                     qobject_cast<QCPTextElement*>(pairPlot.plotLayout()->element(0, 0)) &&
                     qobject_cast<QCPTextElement*>(pairPlot.plotLayout()->element(0, 0))
                         ->text()
                         .startsWith(QString("seed %1:").arg(seed1)),
                 "the second pair is drawn");
        closeErrorDialogs(*window_);

        // A file that shares no trial with the paper is refused before any run, naming why.
        const QString other = paperVariant(
            "other_trials.json",
            R"("name": "other_trials", "following": {"trials": [{"label": "mine", "object":
               {"shape": "rectangle", "width_mm": 48, "height_mm": 58, "offset_mm": [150, 150]}}]})");
        QSignalSpy errors(window_.get(), &MainWindow::errorShown);
        QVERIFY(!window_->startComparison(other, 1, 2));
        QCOMPARE(errors.count(), 1);
        QVERIFY2(errors.first().at(0).toString().contains("has a namesake in 'paper'"),
                 qPrintable(errors.first().at(0).toString()));
        QVERIFY(!window_->running());
        QCOMPARE(window_->lastComparisonDirectory(), dir);
        closeErrorDialogs(*window_);
    }

    void aComparisonShowsEachSeedAsItFinishes() {
        // Two seeds planned, one in: its row, the comparison so far and its figure are on
        // screen; a stop keeps them and says so.
        ComparisonTab tab;
        tab.setRunnable(true);
        tab.begin("paper", "variant", 5, 6);
        PairedComparison soFar;
        soFar.nameA = "paper";
        soFar.nameB = "variant";
        for (int i = 0; i < 8; ++i) soFar.activeCompleted.add(i > 0, true);
        soFar.seeds = 1;
        soFar.soFar.push_back(soFar);
        PairedTrial lostInA{
            5,      FollowingMode::Active, "cross", 2, "lost at a corner (lost)", "completed", "",
            "cross"};
        PairedTrial alike{5, FollowingMode::Active, "C", 1, "completed", "completed", "C", "C"};
        tab.addSeed(5, {lostInA, alike}, soFar);
        QCOMPARE(tab.table()->rowCount(), 1);
        QCOMPARE(tab.table()->item(0, 2)->text(), QString("cross"));
        QCOMPARE(tab.table()->item(0, 5)->text(), QString("completed, named cross"));
        QVERIFY2(tab.summaryText().contains("A = paper, B = variant, 1 seeds, trial by trial:") &&
                     tab.summaryText().contains("running: 1 of 2 seeds compared, 1 trials "
                                                "ended differently"),
                 qPrintable(tab.summaryText()));
        QCustomPlot& plot = tab.plotPanel()->plot();
        QCOMPARE(plot.graph(0)->name(), QString("B - A: active trials completed"));
        QCOMPARE(plot.graph(0)->data()->at(0)->value, 12.5);
        QVERIFY(!tab.findChild<QPushButton*>("compareWith")->isEnabled());
        tab.interrupted();
        QVERIFY(tab.summaryText().endsWith("stopped: the seeds shown are all there are"));
        QCOMPARE(plot.graph(0)->data()->at(0)->value, 12.5);
        QVERIFY(tab.findChild<QPushButton*>("compareWith")->isEnabled());
    }

    void ratesOverSeedsRunFromTheWindow() {
        SeedsTab* tab = window_->seedsTab();
        auto* first = tab->findChild<QSpinBox*>("firstSeed");
        auto* last = tab->findChild<QSpinBox*>("lastSeed");
        auto* run = tab->findChild<QPushButton*>("runSeeds");
        QVERIFY(first && last && run);
        first->setValue(3);
        last->setValue(1);  // a range cannot be given backwards
        QCOMPARE(first->value(), 1);
        first->setValue(2);
        last->setValue(4);
        QSignalSpy ended(window_.get(), &MainWindow::runEnded);
        QTest::mouseClick(run, Qt::LeftButton);
        QVERIFY(window_->running());
        QVERIFY(!run->isEnabled());
        endsSuccessfully(*window_, ended, 120000);
        if (QTest::currentTestFailed()) return;
        QVERIFY(run->isEnabled());

        // Each row is that seed's whole run, as the headless runner computes it.
        const SeedRates direct = runSeeds(simulatedRigs(), window_->experimentAsShown(), 2, 4, "");
        QTableWidget* table = tab->table();
        QCOMPARE(table->rowCount(), 3);
        for (int i = 0; i < 3; ++i) {
            const SeedOutcome& o = direct.seeds[std::size_t(i)];
            QCOMPARE(table->item(i, 0)->text(), QString::number(2 + i));
            QCOMPARE(table->item(i, 1)->text(),
                     QString("%1 / %2").arg(o.passiveLost).arg(o.passiveTrials));
            QCOMPARE(table->item(i, 2)->text(),
                     QString("%1 / %2").arg(o.activeCompleted).arg(o.activeTrials));
            QCOMPARE(table->item(i, 6)->text(),
                     QString("%1-%2").arg(o.validRange.first).arg(o.validRange.last));
            QCOMPARE(table->item(i, 7)->text(), QString(o.paperResult() ? "yes" : "no"));
            QCOMPARE(table->item(i, 8)->text(), shortfallsOf(o));
        }
        for (const Rate& r : {direct.activeCompleted(), direct.passiveLost()})
            QVERIFY2(tab->summaryText().contains(QString("%1 / %2").arg(r.count).arg(r.total)),
                     qPrintable(tab->summaryText()));
        QVERIFY(tab->summaryText().contains("finished, 3 seeds"));
        QVERIFY(tab->ratesPanel()->plot().plottableCount() > 0);
        // The files: a row per seed, the rates, the figure.
        const QString dir = window_->lastSeedsDirectory();
        QCOMPARE(linesIn(dir + "/rates.csv"), 4);
        QCOMPARE(readJson(dir + "/rates.json")["runs"].toInt(), 3);
        QVERIFY(QFileInfo(dir + "/figures/seed_rates.png").size() > 0);
    }

    void aSeedsRowOpensThatSeedsRun() {
        // A row of the seeds run (2-4, above) that lost an active trial: selecting it and clicking
        // the button runs that very seed again and opens the replay on the lost trial's end.
        SeedsTab* tab = window_->seedsTab();
        QTableWidget* table = tab->table();
        auto* runSeed = tab->findChild<QPushButton*>("runSelectedSeed");
        QVERIFY(runSeed);
        table->clearSelection();
        QVERIFY(!runSeed->isEnabled());
        int row = 0;
        while (row < table->rowCount() && table->item(row, 2)->text() == "8 / 8") ++row;
        QVERIFY2(row < table->rowCount(), "seeds 2-4 of paper.json lose an active trial");
        table->selectRow(row);
        QVERIFY(runSeed->isEnabled());
        const std::uint64_t seed = table->item(row, 0)->text().toULongLong();
        // The row stands for the seeds run's experiment, not for what the panel shows since.
        QGroupBox* noise = window_->findChild<QGroupBox*>("effect_taxel_noise");
        QVERIFY(noise && noise->isChecked());
        clickCheckBox(noise);
        QVERIFY(!noise->isChecked());
        QSignalSpy ended(window_.get(), &MainWindow::runEnded);
        QTest::mouseClick(runSeed, Qt::LeftButton);
        QVERIFY(window_->running());
        QVERIFY(!runSeed->isEnabled());
        QCOMPARE(window_->tabs()->currentWidget(), window_->followingTab());
        QVERIFY(ended.wait(120000));
        QTRY_VERIFY(!window_->running());
        clickCheckBox(noise);
        QVERIFY(noise->isChecked());
        const auto run = window_->lastRun();
        QCOMPARE(run->spec.scene.seed, seed);
        const auto& effects = run->activeEffects;
        QVERIFY(std::find(effects.begin(), effects.end(), "taxel_noise") != effects.end());
        QVERIFY(window_->lastRunDirectory().contains(QString("_seed%1-").arg(seed)));
        const SeedOutcome again = seedOutcome(*run);
        QCOMPARE(QString("%1 / %2").arg(again.activeCompleted).arg(again.activeTrials),
                 table->item(row, 2)->text());
        QCOMPARE(table->item(row, 8)->text(), shortfallsOf(again));
        std::size_t lost = 0;
        while (run->trials[lost].result.mode != FollowingMode::Active ||
               run->trials[lost].result.completed())
            ++lost;
        FollowingTab* following = window_->followingTab();
        QCOMPARE(following->replayedTrial(), int(lost));
        QCOMPARE(following->replayedTap(), int(run->trials[lost].result.taps.size()) - 1);
        QVERIFY2(following->replayText().startsWith(
                     QString("Tap %1 of %1 ").arg(run->trials[lost].result.taps.size())),
                 qPrintable(following->replayText()));
        // The lost trial's replay says where it got furthest along the contour.
        QVERIFY2(following->replayText().contains(
                     QString::fromStdString(describePlace(run->trials[lost].result.furthest))),
                 qPrintable(following->replayText()));

        // Double-clicking another row runs its seed.
        const int other = row == 0 ? 1 : 0;
        showTab(tab);
        QCoreApplication::processEvents();
        table->scrollToItem(table->item(other, 0));
        const QRect cellRect = table->visualItemRect(table->item(other, 0));
        // A person's double-click: a press and release, then the double-click.
        QTest::mouseClick(table->viewport(), Qt::LeftButton, Qt::NoModifier, cellRect.center());
        QTest::mouseDClick(table->viewport(), Qt::LeftButton, Qt::NoModifier, cellRect.center());
        QVERIFY(ended.wait(120000));
        QTRY_VERIFY(!window_->running());
        QCOMPARE(window_->lastRun()->spec.scene.seed, table->item(other, 0)->text().toULongLong());
    }

    void cancellingSeedsKeepsEveryFinishedSeed() {
        SeedsTab* tab = window_->seedsTab();
        QSignalSpy ended(window_.get(), &MainWindow::runEnded);
        QVERIFY(window_->startSeeds(1, 1000));
        QTRY_VERIFY_WITH_TIMEOUT(tab->table()->rowCount() >= 2, 60000);
        click(*window_, "cancel");
        QVERIFY(ended.wait(30000));
        QCOMPARE(ended.takeFirst().at(0).toBool(), false);
        QTRY_VERIFY(!window_->running());
        const int rows = tab->table()->rowCount();
        QVERIFY(rows >= 2 && rows < 1000);
        const QString dir = window_->lastSeedsDirectory();
        QCOMPARE(linesIn(dir + "/rates.csv"), 1 + rows);
        QCOMPARE(readJson(dir + "/rates.json")["runs"].toInt(), rows);
        QVERIFY(tab->summaryText().contains(QString("cancelled after %1 seeds").arg(rows)));
        QVERIFY(window_->progressBar()->format().startsWith("seeds cancelled"));
    }

    void theFilledWindowStillFitsALaptop() {
        // After runs over seeds and comparisons have filled their tabs (tables, summaries and
        // plots), the window still fits a 1280x720 screen with every dock shown.
        for (QDockWidget* dock : window_->findChildren<QDockWidget*>()) dock->show();
        QCoreApplication::processEvents();
        const QSize least = window_->layout()->minimumSize().expandedTo(window_->minimumSize());
        for (int i = 0; i < window_->tabs()->count(); ++i) {
            const QSize page = window_->tabs()->widget(i)->minimumSizeHint();
            qInfo("%s: %dx%d", qPrintable(window_->tabs()->tabText(i)), page.width(),
                  page.height());
        }
        QVERIFY2(least.width() <= 1280 && least.height() <= 720,
                 qPrintable(QString("%1x%2").arg(least.width()).arg(least.height())));
    }

    void cleanupTestCase() { closeWindow(); }
};

QTEST_MAIN(TestWindowSeeds)
#include "test_window_seeds.moc"
