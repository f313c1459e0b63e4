// The workbench window driven as a person drives it, offscreen: run the paper experiment and
// watch the progress reach the end; cancel half-way and find every finished tap kept; toggle an
// effect and see the next run use it; export every figure in every format; open bad files and
// keep the session; drive the simulated devices from their panel; run the experiment over a range
// of seeds, open one seed's run from its row, and cancel such a run, keeping every finished seed;
// change the protocol in its panel, run it and save it, and be refused naming the field when it
// cannot run; analyse a run's recording; resize the window and find paths and histograms still
// drawn at one scale on both axes, and no legend hiding a value.
#include <sys/resource.h>

#include <QComboBox>
#include <QDoubleSpinBox>
#include <QElapsedTimer>
#include <QFontMetricsF>
#include <QGroupBox>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QLabel>
#include <QLineEdit>
#include <QMessageBox>
#include <QPlainTextEdit>
#include <QProgressBar>
#include <QPushButton>
#include <QSpinBox>
#include <QStandardPaths>
#include <QStyleOptionGroupBox>
#include <QTabWidget>
#include <QTableWidget>
#include <QTemporaryDir>
#include <QToolButton>
#include <QtTest>
#include <csignal>
#include <thread>
#if defined(__x86_64__)
#include <cpuid.h>
#include <immintrin.h>
#endif

#include "app/gui/ComparisonTab.h"
#include "app/gui/DevicesPanel.h"
#include "app/gui/FollowingTab.h"
#include "app/gui/LiveView.h"
#include "app/gui/MainWindow.h"
#include "app/gui/PlotPanel.h"
#include "app/gui/ProtocolPanel.h"
#include "app/gui/ScenePanel.h"
#include "app/gui/SeedsTab.h"
#include "core/common/VectorState.h"
#include "core/fingertip/FingertipContactModel.h"
#include "devices/rigs/RigFile.h"
#include "qcustomplot.h"
#include "support/FigureChecks.h"
#include "support/FileSizeLimit.h"
#include "support/Files.h"
#include "support/Paths.h"
#include "support/SimulatedRun.h"

using namespace activetouch;
using test::linesIn;
using test::readJson;
using test::sourceFile;

namespace {
/// What a seeds row lists as falling short: the active trials lost, then the paths misnamed.
QString shortfallsOf(const SeedOutcome& o) {
    QStringList items;
    for (const auto& f : o.passiveShortfalls) items << QString::fromStdString(f);
    for (const auto& f : o.failures) items << QString::fromStdString(f);
    for (const auto& m : o.misnamed()) items << QString::fromStdString(m);
    return items.join("; ");
}

void click(QMainWindow& w, const char* actionName) {
    QAction* action = w.findChild<QAction*>(actionName);
    QVERIFY2(action, actionName);
    for (QToolButton* b : w.findChildren<QToolButton*>())
        if (b->defaultAction() == action) {
            QTest::mouseClick(b, Qt::LeftButton);
            return;
        }
    QFAIL("no button for the action");
}

void writeJson(const QString& path, const QJsonObject& j) {
    QFile f(path);
    if (f.open(QIODevice::WriteOnly | QIODevice::Truncate)) f.write(QJsonDocument(j).toJson());
}

/// Clicks the check box in a checkable group box's title, as a person would.
void clickCheckBox(QGroupBox* box) {
    box->window()->raise();
    for (QWidget* w = box; w; w = w->parentWidget()) w->show();
    box->ensurePolished();
    QStyleOptionGroupBox option;
    option.initFrom(box);
    option.text = box->title();
    option.subControls =
        QStyle::SC_GroupBoxCheckBox | QStyle::SC_GroupBoxLabel | QStyle::SC_GroupBoxFrame;
    option.features = QStyleOptionFrame::None;
    option.state |= box->isChecked() ? QStyle::State_On : QStyle::State_Off;
    const QRect r = box->style()->subControlRect(QStyle::CC_GroupBox, &option,
                                                 QStyle::SC_GroupBoxCheckBox, box);
    QTest::mouseClick(box, Qt::LeftButton, Qt::NoModifier, r.center());
}

/// Whether a single run fills the panel (sweeps and seeds have their own runs).
bool filledByARun(const PlotPanel* p) {
    return !p->name().startsWith("sweep") && p->name() != "seed_rates" &&
           !p->name().startsWith("compare");
}

/// Whether the plot draws any axis (after a redraw): an empty figure shows its hint alone.
bool drawsAnAxis(PlotPanel* p) {
    p->plot().replot(QCustomPlot::rpImmediateRefresh);
    for (QCPAxisRect* r : p->plot().axisRects())
        for (QCPAxis* a : r->axes())
            if (a->realVisibility()) return true;
    return false;
}

/// Brings the tab holding `w` to the front, as a person clicking its tabs would.
void showTab(QWidget* w) {
    for (; w && w->parentWidget(); w = w->parentWidget())
        if (auto* tabs = qobject_cast<QTabWidget*>(w->parentWidget()->parentWidget()))
            if (tabs->indexOf(w) >= 0) tabs->setCurrentWidget(w);
}

void showAt(PlotPanel* panel, QSize size) {
    panel->window()->resize(size);
    QCoreApplication::processEvents();
    panel->plot().replot(QCustomPlot::rpImmediateRefresh);
    QCoreApplication::processEvents();
}

#if defined(__x86_64__)
/// XINUSE: the register state components the thread has in use (bit 2: the AVX upper halves).
__attribute__((target("xsave"))) unsigned long long vectorStateInUse() {
    return _xgetbv(1);
}
constexpr unsigned long long kUpperHalvesInUse = 1ull << 2;
/// Leaves the upper halves of the vector registers in use, as some libraries' AVX code does
/// (written out, since a compiler ends its own AVX functions by clearing them). Only where the
/// CPU has AVX.
__attribute__((naked)) void markUpperHalvesInUse() {
    asm volatile("vcmpps $15, %ymm0, %ymm0, %ymm0\n\tret");
}
#endif

void closeErrorDialogs(QWidget& w) {
    for (QMessageBox* box : w.findChildren<QMessageBox*>("errorDialog")) box->close();
}

/// The run the window has just started ends within `timeout_ms`, successfully, and leaves the
/// window idle. `ended` spies on MainWindow::runEnded; its latest signal is taken.
void endsSuccessfully(MainWindow& w, QSignalSpy& ended, int timeout_ms = 60000) {
    QVERIFY(ended.wait(timeout_ms));
    QCOMPARE(ended.takeLast().at(0).toBool(), true);
    QTRY_VERIFY(!w.running());
}
}  // namespace

class TestMainWindow : public QObject {
    Q_OBJECT
    QTemporaryDir dir_;
    std::unique_ptr<MainWindow> window_;

    /// Writes `name` in the test folder: the paper experiment with `keys` patched on top (an
    /// experiment that extends it); returns its path.
    QString paperVariant(const QString& name, const QString& keys) {
        const QString path = dir_.filePath(name);
        writeJson(path, QJsonDocument::fromJson(QString(R"({"extends": "%1", %2})")
                                                    .arg(sourceFile("experiments/paper.json"), keys)
                                                    .toUtf8())
                            .object());
        return path;
    }

    /// The protocol panel's widget for the experiment key `name` ("following_follow_step_mm").
    template <class W>
    W* protocolField(const char* name) {
        return window_->protocolPanel()->findChild<W*>(QString("protocol_") + name);
    }
    QComboBox* trialMode(int row) {
        auto* table = window_->protocolPanel()->findChild<QTableWidget*>("protocol_trials");
        return table ? qobject_cast<QComboBox*>(table->cellWidget(row, 1)) : nullptr;
    }
    QSpinBox* trialRepeats(int row) {
        auto* table = window_->protocolPanel()->findChild<QTableWidget*>("protocol_trials");
        return table ? qobject_cast<QSpinBox*>(table->cellWidget(row, 2)) : nullptr;
    }

    /// Starting `what` is refused with one error saying each of `parts`: nothing runs and the
    /// last run stays the last run.
    void expectRefused(RunController::What what, const QStringList& parts) {
        const auto before = window_->lastRun();
        QSignalSpy errors(window_.get(), &MainWindow::errorShown);
        QVERIFY(!window_->startRun(what));
        QCOMPARE(errors.count(), 1);
        const QString message = errors.takeFirst().at(0).toString();
        for (const QString& part : parts) QVERIFY2(message.contains(part), qPrintable(message));
        QVERIFY(!window_->running());
        QCOMPARE(window_->lastRun(), before);
        closeErrorDialogs(*window_);
    }

private slots:
    void initTestCase() {
        QStandardPaths::setTestModeEnabled(true);  // settings go to a test location
        QCoreApplication::setOrganizationName("ActiveTouchTest");
        window_ = std::make_unique<MainWindow>();
        window_->setOutputBase(dir_.filePath("runs"));
        window_->resize(1600, 1000);
        window_->show();
        QVERIFY(window_->openExperiment(sourceFile("experiments/paper.json")));
    }

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
            QSKIP("on this machine a new thread starts with the upper halves clear, so there is "
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
        auto* bars = qobject_cast<QCPBars*>(live->barsPanel()->plot().plottable(0));
        QVERIFY(bars);
        const auto shownValues = [&] {
            std::vector<double> v;
            for (auto it = bars->data()->constBegin(); it != bars->data()->constEnd(); ++it)
                v.push_back(it->value);
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
            for (QSize size : {QSize(1900, 700), QSize(900, 1100), QSize(1300, 900)}) {
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
        QVERIFY(window_->startComparison(sourceFile("experiments/paper_kernel.json"), 3, 4));
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
        const TrialPairRun direct =
            runTrialPair(simulatedRigs(), loadExperiment(sourceFile("experiments/paper.json").toStdString()),
                         loadExperiment(sourceFile("experiments/paper_kernel.json").toStdString()),
                         seed, mode, label.toStdString(), trial);
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
        QStringList drawn;
        for (int i = 0; i < pairPlot.plottableCount(); ++i) {
            auto* curve = qobject_cast<QCPCurve*>(pairPlot.plottable(i));
            if (!curve || (!curve->name().startsWith(QString("A ")) &&
                           !curve->name().startsWith(QString("B "))))
                continue;
            drawn << curve->name();
            const TrialRun& run = curve->name().startsWith("A ") ? direct.a : direct.b;
            QCOMPARE(curve->data()->size(), int(run.result.path().size()));
            QCOMPARE(curve->data()->at(0)->key, run.result.path().front().x);
            QCOMPARE((curve->data()->end() - 1)->value, run.result.path().back().y);
        }
        QCOMPARE(drawn.size(), 2);
        QVERIFY2(drawn[0].startsWith("A paper: " + QString::fromStdString(trialOutcome(direct.a))),
                 qPrintable(drawn.join(" | ")));
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
        for (QSize size : {QSize(1900, 700), QSize(1300, 900), QSize(1100, 800)}) {
            showAt(seeds, size);
            test::checkLabelsFitTheirPanels(
                seeds->plot(),
                QString("%1 at %2 x %3").arg(seeds->name()).arg(size.width()).arg(size.height()));
            if (QTest::currentTestFailed()) return;
        }
        showAt(seeds, start);
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

    void recordingsAreAnalysedFromTheWindow() {
        // The last run's recording (a seed's run, above), analysed with the same experiment:
        // the same validation from the taps alone, and no tap taken.
        QVERIFY(window_->openExperiment(sourceFile("experiments/paper.json")));
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
        QVERIFY(window_->openExperiment(path));
        QVERIFY(window_->lastRun());  // trained on the simulated rig by the first test

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

    void cleanupTestCase() {
        if (!window_) return;
        window_->close();
        window_.reset();
    }
};

QTEST_MAIN(TestMainWindow)
#include "test_main_window.moc"
