// Every figure the workbench writes, laid out at a single column (89 mm), 120 mm and a double
// column (178 mm) as a journal prints them and at the plot sizes the window gives them at
// 1280x720 and 1920x1080, checked from its laid-out items: no two texts overlap, no text or legend
// covers plotted data, nothing runs off the page, and an export's text is 7-9 pt. A failure names
// the figure, the size and the two items that collide; the check itself is shown to fail on a
// figure with its legend moved over the data.
#include <QDir>
#include <QProcess>
#include <QRegularExpression>
#include <QSettings>
#include <QStackedWidget>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QtTest>
#include <functional>

#include "app/figures/CalibrationFigures.h"
#include "app/figures/ComparisonFigures.h"
#include "app/figures/FigureExport.h"
#include "app/figures/FingertipFigures.h"
#include "app/figures/FollowingFigures.h"
#include "app/figures/SeedFigures.h"
#include "app/figures/SweepFigures.h"
#include "app/gui/MainWindow.h"
#include "app/gui/PlotPanel.h"
#include "core/analysis/PairedComparison.h"
#include "core/analysis/SeedRates.h"
#include "core/analysis/SweepRates.h"
#include "core/run/ExperimentRun.h"
#include "qcustomplot.h"
#include "support/Cli.h"
#include "support/FigureAudit.h"
#include "support/FigureRuns.h"
#include "support/Paths.h"
#include "support/SimulatedRun.h"

using namespace activetouch;

namespace {
using Build = std::function<bool(QCustomPlot&, const FigureSize&)>;

struct NamedFigure {
    QString name;
    Build build;
    FigureSize doubleColumn;  ///< the size it is written at by default
};

/// Each problem on a line of the test's output, the first of them in the failure's message.
void reportEach(const QStringList& problems) {
    for (const QString& p : problems) qWarning("%s", qPrintable(p));
}

/// The size each plot of the window gets (by its name) with fresh settings at `window`: every
/// tab holding a plot brought to the front in turn.
QMap<QString, QSize> windowPlotSizes(QSize window) {
    QStandardPaths::setTestModeEnabled(true);  // fresh settings, in a test location
    QCoreApplication::setOrganizationName("ActiveTouchFigureCheck");
    QSettings().clear();
    MainWindow w;
    w.resize(window);
    w.show();
    QCoreApplication::processEvents();
    QMap<QString, QSize> sizes;
    for (PlotPanel* panel : w.findChildren<PlotPanel*>()) {
        for (QWidget* child = panel; child && child != &w; child = child->parentWidget())
            if (auto* stack = qobject_cast<QStackedWidget*>(child->parentWidget()))
                stack->setCurrentWidget(child);
        QCoreApplication::processEvents();
        sizes[panel->name()] = panel->plot().size();
    }
    return sizes;
}

/// The window's plot a figure is shown in; a figure the window does not show is taken at the
/// size of Figure 6's.
QSize plotFor(const QMap<QString, QSize>& sizes, const QString& figure) {
    static const QMap<QString, QString> shownAs{
        {"trial pair", "compare_trial_pair"},
        {"sweeps_perception", "seeds_sweep_a_perception"},
        {"sweeps_following_pareto", "seeds_sweep_b_pareto_front"}};
    const QString name = figure.section(' ', 0, 0);
    if (shownAs.contains(figure)) return sizes.value(shownAs[figure]);
    return sizes.value(name, sizes.value("figure6_errors"));
}
}  // namespace

class TestFigureCheck : public QObject {
    Q_OBJECT
    std::vector<RunResult> runs_;
    SeedRates seeds_;
    std::vector<NamedFigure> figures_;

    /// The figure at `widthMm` wide (its own height there), or at a window's pixels.
    QStringList check(const NamedFigure& f, double widthMm, QSize pixels, const QString& where) {
        QCustomPlot plot;
        FigureSize size{pixels.width(), pixels.height(), 96};
        if (widthMm > 0) size = FigureSize::physical(widthMm, f.doubleColumn.height_mm, kFigureDpi);
        plot.resize(layoutSize(plot, size));
        if (!f.build(plot, size)) return {};
        if (widthMm > 0) size = figureSizeFor(plot, f.doubleColumn, widthMm);
        layOutAt(plot, size);
        if (widthMm <= 0) {
            // As the window's plot panel does: a figure that needs more room than the panel
            // has keeps the room its layout needs, and scrolls.
            const QSize least = plot.plotLayout()->minimumOuterSizeHint();
            if (least.width() > size.width_px || least.height() > size.height_px) {
                size.width_px = std::max(size.width_px, least.width());
                size.height_px = std::max(size.height_px, least.height());
                layOutAt(plot, size);
            }
        }
        const QString name = f.name + " " + where;
        const QStringList problems =
            test::auditFigure(test::readFigureItems(plot), name, size.isPhysical());
        // Set ACTIVETOUCH_FIGURE_CHECK_DIR to keep a picture of each figure that fails.
        const QString keep = qEnvironmentVariable("ACTIVETOUCH_FIGURE_CHECK_DIR");
        if (!problems.isEmpty() && !keep.isEmpty())
            plot.savePng(QString("%1/%2.png").arg(keep, QString(name).replace(' ', '_')),
                         plot.width(), plot.height());
        return problems;
    }

private slots:
    void initTestCase() {
        runs_ = test::figureRuns();
        seeds_ = runSeeds(simulatedRigs(),
                          loadExperiment(test::sourcePath("experiments/paper.json")), 1, 3, "");

        for (const RunFigure& figure : runFigures())
            for (std::size_t r = 0; r < runs_.size(); ++r)
                figures_.push_back({QString("%1 (%2)")
                                        .arg(figure.file)
                                        .arg(QString::fromStdString(runs_[r].spec.name)),
                                    [this, figure, r](QCustomPlot& plot, const FigureSize&) {
                                        return figure.build(plot, runs_[r]);
                                    },
                                    figure.size});
        figures_.push_back({"seed_rates",
                            [this](QCustomPlot& plot, const FigureSize&) {
                                return buildSeedRatesFigure(plot, seeds_, "paper");
                            },
                            kSeedFigureSize});
        addComparisonFigures();
        addSweepFigures();
        addCalibrationFigure();
        addFingertipFigure();
    }

    void everyFigureHoldsAtEveryJournalWidth() {
        QStringList problems;
        for (const NamedFigure& f : figures_)
            for (double width : {89.0, 120.0, 178.0})
                problems << check(f, width, {}, QString("at %1 mm").arg(width));
        reportEach(problems);
        QVERIFY2(
            problems.isEmpty(),
            qPrintable(
                QString("%1 problems, the first: %2").arg(problems.size()).arg(problems.value(0))));
    }

    void everyFigureHoldsInTheWindow() {
        QStringList problems;
        for (const QSize window : {QSize(1280, 720), QSize(1920, 1080)}) {
            const QMap<QString, QSize> sizes = windowPlotSizes(window);
            QVERIFY(sizes.contains("figure6_errors"));
            for (const NamedFigure& f : figures_) {
                const QSize s = plotFor(sizes, f.name);
                QVERIFY2(s.width() > 100 && s.height() > 100, qPrintable(f.name));
                problems << check(f, 0.0, s,
                                  QString("in a %1x%2 window (%3x%4 px)")
                                      .arg(window.width())
                                      .arg(window.height())
                                      .arg(s.width())
                                      .arg(s.height()));
            }
        }
        reportEach(problems);
        QVERIFY2(
            problems.isEmpty(),
            qPrintable(
                QString("%1 problems, the first: %2").arg(problems.size()).arg(problems.value(0))));
    }

    void aSingleColumnRunWritesEveryFigureReadably() {
        // `run --figure-width-mm 89`: every PDF a page 89 mm wide, and as a reader's PDF tool
        // (poppler's pdftotext) places its words, none under 7 pt and no two overlapping.
        QTemporaryDir dir;
        // A width that is no column's is refused by name, nothing written.
        for (const char* bad : {"abc", "20", "89mm", "1e9"}) {
            const test::CliOutcome refused = test::runCli(
                {"run", QString::fromStdString(test::sourcePath("experiments/paper.json")), "--out",
                 dir.filePath("refused"), "--figure-width-mm", bad});
            QCOMPARE(refused.exitCode, 2);
            QVERIFY2(refused.err.contains("--figure-width-mm"), qPrintable(refused.err));
            QVERIFY(!QDir(dir.filePath("refused")).exists());
        }
        const test::CliOutcome run =
            test::runCli({"run", QString::fromStdString(test::sourcePath("experiments/paper.json")),
                          "--out", dir.filePath("run"), "--figure-width-mm", "89"});
        QVERIFY2(run.exitCode == 0, qPrintable(run.err));
        const QStringList pdfs =
            QDir(dir.filePath("run/figures")).entryList({"*.pdf"}, QDir::Files, QDir::Name);
        QCOMPARE(pdfs.size(), 5);  // Figures 5 to 9: the paper has no sweeps
        for (const QString& pdf : pdfs) {
            QProcess words;
            words.start("pdftotext", {"-bbox", dir.filePath("run/figures/" + pdf), "-"});
            QVERIFY(words.waitForFinished(30000) && words.exitCode() == 0);
            const QString html = words.readAllStandardOutput();
            static const QRegularExpression page(R"re(<page width="([0-9.]+)")re");
            const double widthMm = page.match(html).captured(1).toDouble() / 72.0 * 25.4;
            QVERIFY2(std::abs(widthMm - 89.0) < 0.5, qPrintable(pdf));
            static const QRegularExpression word(
                R"re(<word xMin="([0-9.]+)" yMin="([0-9.]+)" xMax="([0-9.]+)" yMax="([0-9.]+)">([^<]*)<)re");
            QList<QPair<QRectF, QString>> boxes;
            for (auto it = word.globalMatch(html); it.hasNext();) {
                const QRegularExpressionMatch w = it.next();
                const QRectF box(QPointF(w.captured(1).toDouble(), w.captured(2).toDouble()),
                                 QPointF(w.captured(3).toDouble(), w.captured(4).toDouble()));
                // A word's size is its box across its line: the height of a word set level,
                // the width of one set sideways (the y labels); a word of one or two letters
                // is no wider than its size either way.
                const double size = w.captured(5).size() <= 2 ? std::max(box.width(), box.height())
                                                              : std::min(box.width(), box.height());
                QVERIFY2(
                    size >= 7.0 - 0.05,
                    qPrintable(QString("%1: '%2' is %3 pt").arg(pdf, w.captured(5)).arg(size)));
                for (const auto& [other, text] : boxes) {
                    const QRectF both = other.intersected(box);
                    QVERIFY2(both.width() < 0.3 || both.height() < 0.3,
                             qPrintable(
                                 QString("%1: '%2' overlaps '%3'").arg(pdf, w.captured(5), text)));
                }
                boxes.append({box, w.captured(5)});
            }
            QVERIFY2(boxes.size() > 30, qPrintable(pdf));
        }
    }

    void aFigureLooksTheSameWhateverSizesItHadBefore() {
        // A plot resized (a window made smaller, then larger again; an export laid out on a
        // page of its own) draws what a plot laid out at its size from the start draws.
        const QSize final(1100, 760);
        QStringList differ;
        for (const NamedFigure& f : figures_) {
            QCustomPlot direct, resized;
            const FigureSize at{final.width(), final.height(), 96};
            if (!f.build(direct, at)) continue;
            layOutAt(direct, at);
            QVERIFY(f.build(resized, at));
            layOutAt(resized, FigureSize{360, 260, 96});
            QTemporaryDir dir;
            exportFigure(resized, dir.filePath("narrow"), {"pdf"},
                         FigureSize::physical(89.0, 120.0, kFigureDpi));
            layOutAt(resized, at);
            if (direct.toPixmap().toImage() != resized.toPixmap().toImage()) {
                differ << f.name;
                const QString keep = qEnvironmentVariable("ACTIVETOUCH_FIGURE_CHECK_DIR");
                if (!keep.isEmpty()) {
                    direct.savePng(keep + "/" + QString(f.name).replace(' ', '_') + "_direct.png");
                    resized.savePng(keep + "/" + QString(f.name).replace(' ', '_') +
                                    "_resized.png");
                }
            }
        }
        QVERIFY2(differ.isEmpty(), qPrintable(differ.join(", ")));
    }

    void theCheckFailsOnALegendOverTheData() {
        // Figure 8's legend moved from its clear corner onto the first path's first tap.
        const RunFigure& paths =
            *std::find_if(runFigures().begin(), runFigures().end(),
                          [](auto& f) { return QString(f.file) == "figure8_active_paths"; });
        QCustomPlot plot;
        const FigureSize size = paths.size;
        plot.resize(layoutSize(plot, size));
        QVERIFY(paths.build(plot, runs_.front()));
        layOutAt(plot, size);
        QVERIFY(test::auditFigure(test::readFigureItems(plot), "figure 8", true).isEmpty());
        QCPAxisRect* rect = plot.axisRect(0);
        QCPLegend* legend = nullptr;
        for (QCPLayoutElement* e : rect->insetLayout()->elements(false))
            if (auto* l = qobject_cast<QCPLegend*>(e)) legend = l;
        QVERIFY(legend);
        const auto* curve = qobject_cast<QCPCurve*>(rect->plottables().at(1));
        QVERIFY(curve && !curve->data()->isEmpty());
        const QPointF tap =
            curve->coordsToPixels(curve->data()->begin()->key, curve->data()->begin()->value);
        const QSize needs = legend->minimumOuterSizeHint();
        rect->insetLayout()->setInsetPlacement(0, QCPLayoutInset::ipFree);
        rect->insetLayout()->setInsetRect(
            0,
            QRectF((tap.x() - rect->left() - needs.width() / 2.0) / rect->width(),
                   (tap.y() - rect->top() - needs.height() / 2.0) / rect->height(),
                   needs.width() / double(rect->width()), needs.height() / double(rect->height())));
        plot.replot();
        const QStringList problems =
            test::auditFigure(test::readFigureItems(plot), "figure 8", true);
        QVERIFY(!problems.isEmpty());
        QVERIFY2(problems.front().startsWith("figure 8: the legend at") &&
                     problems.front().contains(" covers a plotted"),
                 qPrintable(problems.front()));
    }

private:
    void addComparisonFigures() {
        // Three made-up seeds of ten trials each way, a difference in every part.
        auto compared = [] {
            PairedComparison c;
            c.nameA = "paper";
            c.nameB = "variant";
            for (int onlyB : {2, 0, 3}) {
                for (int i = 0; i < 10; ++i) {
                    c.activeCompleted.add(i >= onlyB, true);
                    c.passiveLostAtCorner.add(true, i >= onlyB);
                    c.recognisedRaw.add(i % 3 != 0, i % 4 != 0);
                }
                c.paperResult.add(onlyB == 0, true);
                ++c.seeds;
                c.soFar.push_back(c);
            }
            return c;
        }();
        figures_.push_back({"compare",
                            [compared](QCustomPlot& plot, const FigureSize&) {
                                return buildComparisonFigure(plot, compared);
                            },
                            kComparisonFigureSize});
        const ExperimentSpec a = loadExperiment(test::sourcePath("experiments/paper.json"));
        const ExperimentSpec b = loadExperiment(test::sourcePath("experiments/paper_kernel.json"));
        const auto pair = std::make_shared<TrialPairRun>(
            runTrialPair(simulatedRigs(), a, b, 2, FollowingMode::Active, "L", 1));
        figures_.push_back({"trial pair",
                            [pair](QCustomPlot& plot, const FigureSize&) {
                                return buildTrialPairFigure(plot, *pair);
                            },
                            kTrialPairFigureSize});
    }

    void addSweepFigures() {
        const SeedRates sweeps = runSeeds(
            simulatedRigs(), loadExperiment(test::sourcePath("experiments/accuracy_vs_time.json")),
            1, 2, "");
        const auto rates = std::make_shared<SweepRates>(sweepRates(sweeps.seeds));
        for (auto [build, name] :
             {std::pair{&buildPerceptionSweepOverSeedsFigure, "sweeps_perception"},
              std::pair{&buildFollowingParetoFigure, "sweeps_following_pareto"},
              std::pair{&buildRobustnessFigure, "sweeps_robustness"}})
            figures_.push_back({name,
                                [rates, build = build](QCustomPlot& plot, const FigureSize&) {
                                    return build(plot, *rates);
                                },
                                FigureSize::physical(kDoubleColumn_mm, 120, kFigureDpi)});
    }

    void addCalibrationFigure() {
        // The paper's validation as the recording, the other runs' as simulated ones.
        auto figure6 = std::make_shared<Figure6Comparison>();
        figure6->recorded = runs_[0].validation;
        figure6->simulated = {runs_[0].validation, runs_[1].validation};
        auto fit = std::make_shared<SceneFit>();
        fit->taps = 360;
        for (int k = 0; k < 12; ++k)
            fit->taxels.push_back({k, 0.05 + 0.01 * k, 0.12, 1.0, k % 5 != 0});
        figures_.push_back({"calibration",
                            [fit, figure6](QCustomPlot& plot, const FigureSize&) {
                                return buildCalibrationFigure(plot, *fit, *figure6);
                            },
                            FigureSize::physical(kDoubleColumn_mm, 90, kFigureDpi)});
    }

    void addFingertipFigure() {
        FingertipFigureData data;
        data.finger = "index";
        data.caption =
            "12 recordings, 24000 frames; resting readings above each recording's level.";
        for (int k = 0; k < 12; ++k) {
            data.sigma.push_back(0.8 + 0.1 * k);
            data.sigmaLow.push_back(0.7 + 0.1 * k);
            data.sigmaHigh.push_back(0.9 + 0.1 * k);
        }
        for (const char* scene : {"paper", "measured"}) {
            FingertipFigureData::Scene s{scene, 1.2, {}};
            for (int k = 0; k < 12; ++k) s.ks.push_back(0.05 * (k % 4));
            data.scenes.push_back(s);
        }
        figures_.push_back({"fingertip_stats",
                            [data](QCustomPlot& plot, const FigureSize&) {
                                return buildFingertipFigure(plot, data);
                            },
                            FigureSize::physical(kDoubleColumn_mm, 80, kFigureDpi)});
    }
};

QTEST_MAIN(TestFigureCheck)
#include "test_figure_check.moc"
