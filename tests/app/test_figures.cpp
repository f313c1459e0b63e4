// The figures a run exports, as a reader of the paper sees them: each laid out at the size it is
// written at, paths and histograms at equal scales on both axes, no legend over data, every title
// and axis label inside its panel and no tick labels running into each other.
#include <QProcess>
#include <QRegularExpression>
#include <QTemporaryDir>
#include <QXmlStreamReader>
#include <QtTest>
#include <cmath>

#include "app/figures/ComparisonFigures.h"
#include "app/figures/FigureExport.h"
#include "app/figures/FollowingFigures.h"
#include "app/figures/SeedFigures.h"
#include "core/analysis/PairedComparison.h"
#include "core/analysis/SeedRates.h"
#include "core/run/ExperimentRun.h"
#include "qcustomplot.h"
#include "support/FigureChecks.h"
#include "support/FigureRuns.h"
#include "support/Paths.h"
#include "support/SimulatedRun.h"

using namespace activetouch;

class TestFigures : public QObject {
    Q_OBJECT
    std::vector<RunResult> runs_;  // the paper, the accuracy-versus-time sweeps, general shapes

private slots:
    void initTestCase() { runs_ = test::figureRuns(); }

    void everyExportedFigureReadsCleanly() {
        QStringList drawn;
        for (const RunResult& run : runs_) {
            for (const RunFigure& figure : runFigures()) {
                QCustomPlot plot;
                if (!figure.build(plot, run)) continue;
                layOutAt(plot, figure.size);
                const QString name =
                    QString("%1 (%2)").arg(figure.file, QString::fromStdString(run.spec.name));
                QMap<int, QPair<QCPRange, QCPRange>> views;
                test::checkEqualAspect(plot, name, views);
                if (QTest::currentTestFailed()) return;
                test::checkLegendsClearOfData(plot, name);
                if (QTest::currentTestFailed()) return;
                test::checkLabelsFitTheirPanels(plot, name);
                if (QTest::currentTestFailed()) return;
                if (!drawn.contains(figure.file)) drawn << figure.file;
            }
        }
        // Between them the runs draw every figure there is.
        QCOMPARE(drawn.size(), static_cast<int>(runFigures().size()));
    }

    void figure6FitsASingleJournalColumn() {
        // Figure 6 at 89 mm wide and 300 dpi, as a journal's single column takes it: laid out
        // there it reads cleanly (labels inside their panels, no tick labels run together); every
        // text measured in the written files is 7-9 pt at that size;
        // the PDF's fonts are embedded.
        const RunFigure& errors =
            *std::find_if(runFigures().begin(), runFigures().end(),
                          [](const RunFigure& f) { return QString(f.file) == "figure6_errors"; });
        // At its own height for the column (figureSizeFor), as `run --figure-width-mm 89` and
        // the export dialog's single column write it.
        FigureSize size = FigureSize::physical(kSingleColumn_mm, errors.size.height_mm, 300);
        auto shaped = [&](QCustomPlot& plot) { plot.resize(layoutSize(plot, size)); };
        {
            QCustomPlot plot;
            shaped(plot);
            QVERIFY(errors.build(plot, runs_.front()));
            size = figureSizeFor(plot, errors.size, kSingleColumn_mm);
            QVERIFY(size.height_mm > errors.size.height_mm);  // its panels one to a line
            layOutAt(plot, size);
            test::checkLabelsFitTheirPanels(plot, "figure6_errors at 89 mm");
            if (QTest::currentTestFailed()) return;
        }
        QCustomPlot plot;
        shaped(plot);
        QVERIFY(errors.build(plot, runs_.front()));
        QTemporaryDir dir;
        const QStringList files =
            exportFigure(plot, dir.filePath("figure6"), {"png", "pdf", "svg"}, size);
        QCOMPARE(files.size(), 3);
        const QImage png(dir.filePath("figure6.png"));
        QCOMPARE(png.width(), 1051);  // 89 mm at 300 dpi
        QCOMPARE(qRound(png.dotsPerMeterX() * 0.0254), 300);

        // The SVG: each text's size in user units, through its groups' transforms, at the
        // document's mm per unit.
        QFile svg(dir.filePath("figure6.svg"));
        QVERIFY(svg.open(QIODevice::ReadOnly));
        QXmlStreamReader xml(&svg);
        double mmPerUnit = 0.0, smallest = 1e9, largest = 0.0;
        int texts = 0;
        std::vector<double> scales{1.0};
        static const QRegularExpression matrix(R"(matrix\(([-0-9.e]+),([-0-9.e]+),)");
        while (!xml.atEnd()) {
            xml.readNext();
            if (xml.isStartElement()) {
                const auto a = xml.attributes();
                if (xml.name() == QLatin1String("svg")) {
                    const double widthMm = a.value("width").toString().remove("mm").toDouble();
                    const double units = a.value("viewBox").toString().split(' ').at(2).toDouble();
                    mmPerUnit = widthMm / units;
                    QVERIFY2(std::abs(widthMm - kSingleColumn_mm) < 0.5,
                             qPrintable(QString::number(widthMm)));
                }
                double scale = scales.back();
                const QRegularExpressionMatch m = matrix.match(a.value("transform").toString());
                if (m.hasMatch())
                    scale *= std::hypot(m.captured(1).toDouble(), m.captured(2).toDouble());
                scales.push_back(scale);
                if (xml.name() == QLatin1String("text")) {
                    const double pt =
                        a.value("font-size").toDouble() * scale * mmPerUnit / 25.4 * 72.0;
                    const QString what = xml.readElementText();
                    scales.pop_back();
                    if (what.trimmed().isEmpty()) continue;
                    ++texts;
                    smallest = std::min(smallest, pt);
                    largest = std::max(largest, pt);
                    QVERIFY2(pt >= kSmallestText_pt - 0.05,
                             qPrintable(QString("'%1' at %2 pt").arg(what).arg(pt)));
                }
            } else if (xml.isEndElement()) {
                scales.pop_back();
            }
        }
        QVERIFY(!xml.hasError());
        QVERIFY(texts > 30);
        qInfo("Figure 6 at %.0f mm: %d texts from %.1f to %.1f pt", kSingleColumn_mm, texts,
              smallest, largest);
        QVERIFY(largest <= kLargestText_pt + 0.05);

        // The PDF: a page 89 mm wide; every font embedded (pdffonts); every word at least 7 pt
        // tall as a reader's PDF tool places it (pdftotext).
        QProcess fonts;
        fonts.start("pdffonts", {dir.filePath("figure6.pdf")});
        QVERIFY2(fonts.waitForFinished(30000) && fonts.exitCode() == 0,
                 "pdffonts (poppler-utils) could not read the PDF");
        const QStringList lines =
            QString(fonts.readAllStandardOutput()).split('\n', Qt::SkipEmptyParts);
        QVERIFY(lines.size() >= 2);
        for (const QString& line : lines.mid(2)) {
            // name type [more type] encoding emb sub uni object ID: "emb" is fifth from last.
            const QStringList f = line.simplified().split(' ');
            QVERIFY2(f.size() >= 7 && f[f.size() - 5] == "yes", qPrintable(line));
        }
        QProcess words;
        words.start("pdftotext", {"-bbox", dir.filePath("figure6.pdf"), "-"});
        QVERIFY(words.waitForFinished(30000) && words.exitCode() == 0);
        const QString html = words.readAllStandardOutput();
        static const QRegularExpression page(R"re(<page width="([0-9.]+)")re");
        QVERIFY(std::abs(page.match(html).captured(1).toDouble() - kSingleColumn_mm / 25.4 * 72) <
                1.5);
        static const QRegularExpression word(
            R"re(<word xMin="([0-9.]+)" yMin="([0-9.]+)" xMax="([0-9.]+)" yMax="([0-9.]+)">([^<]*)<)re");
        int counted = 0;
        for (auto it = word.globalMatch(html); it.hasNext();) {
            const QRegularExpressionMatch w = it.next();
            const double height = w.captured(4).toDouble() - w.captured(2).toDouble();
            const double width = w.captured(3).toDouble() - w.captured(1).toDouble();
            // A word's size is its box across its line: the height of a word set level, the
            // width of one set sideways (the y labels); a word of one or two letters is no wider
            // than its size either way.
            const double tall =
                w.captured(5).size() <= 2 ? std::max(width, height) : std::min(width, height);
            QVERIFY2(tall >= kSmallestText_pt - 0.05,
                     qPrintable(QString("'%1' %2 pt tall").arg(w.captured(5)).arg(tall)));
            ++counted;
        }
        QVERIFY(counted > 30);
    }

    void pathFiguresMarkWhereLostTrialsEnded() {
        // The paper's passive trials are lost: a cross at each one's last tap, one legend entry.
        const RunResult& paper = runs_.front();
        QCustomPlot plot;
        QVERIFY(buildPathFigure(plot, paper, FollowingMode::Passive, "passive"));
        std::vector<Vec2> ends;
        for (const auto& t : paper.trials)
            if (t.result.mode == FollowingMode::Passive && !t.result.completed())
                ends.push_back(t.result.path().back());
        QCOMPARE(int(ends.size()), 2);
        int marks = 0, inLegend = 0;
        for (int i = 0; i < plot.plottableCount(); ++i) {
            auto* c = qobject_cast<QCPCurve*>(plot.plottable(i));
            if (!c || c->name() != "where the trial ended") continue;
            QCOMPARE(c->dataCount(), 1);
            const Vec2 at{c->data()->begin()->key, c->data()->begin()->value};
            QVERIFY(std::any_of(ends.begin(), ends.end(),
                                [&](Vec2 e) { return distance(e, at) < 1e-9; }));
            ++marks;
            for (QCPAxisRect* rect : plot.axisRects())
                for (int e = 0; e < rect->insetLayout()->elementCount(); ++e)
                    if (auto* legend = qobject_cast<QCPLegend*>(rect->insetLayout()->elementAt(e)))
                        inLegend += legend->hasItemWithPlottable(c);
        }
        QCOMPARE(marks, 2);
        QCOMPARE(inLegend, 1);
        // And where along the contour each got furthest: one series over the paths, both points.
        std::vector<Vec2> furthest;
        for (int i = 0; i < plot.plottableCount(); ++i)
            if (auto* c = qobject_cast<QCPCurve*>(plot.plottable(i));
                c && c->name() == "furthest along the contour") {
                QCOMPARE(i, plot.plottableCount() - 1);  // drawn last, over every path
                for (auto d = c->data()->begin(); d != c->data()->end(); ++d)
                    furthest.push_back({d->key, d->value});
            }
        QCOMPARE(int(furthest.size()), 2);
        for (const auto& t : paper.trials)
            if (t.result.mode == FollowingMode::Passive)
                QVERIFY(std::any_of(furthest.begin(), furthest.end(), [&](Vec2 p) {
                    return distance(p, t.result.furthest.point) < 1e-9;
                }));
        // Every active trial of seed 1 completed: no marks there.
        QCustomPlot active;
        QVERIFY(buildPathFigure(active, paper, FollowingMode::Active, "active"));
        for (int i = 0; i < active.plottableCount(); ++i) {
            QVERIFY(active.plottable(i)->name() != "where the trial ended");
            QVERIFY(active.plottable(i)->name() != "furthest along the contour");
        }
    }

    void theErrorFigureNamesALikelihoodOtherThanThePapers() {
        // The paper's histogram is what Figure 6 shows unless told otherwise; a kernel-smoothed
        // likelihood is named in the title, which still fits the exported figure.
        const RunFigure& errors =
            *std::find_if(runFigures().begin(), runFigures().end(),
                          [](const RunFigure& f) { return QString(f.file) == "figure6_errors"; });
        auto title = [&](const RunResult& run) {
            QCustomPlot plot;
            if (!errors.build(plot, run)) return QString();
            layOutAt(plot, errors.size);
            test::checkLabelsFitTheirPanels(plot, "figure6_errors");
            return qobject_cast<QCPTextElement*>(plot.plotLayout()->element(0, 0))->text();
        };
        const QString paper = title(runs_.front());
        QVERIFY(paper.startsWith("Figure 6"));
        QVERIFY2(!paper.contains("kernel"), qPrintable(paper));
        ExperimentSpec spec = loadExperiment(test::sourcePath("experiments/paper_kernel.json"));
        spec.trials.clear();  // the validation is all Figure 6 needs
        const RunResult kernel = runExperiment(spec, test::onSimulatedRig());
        const QString named = title(kernel);
        QVERIFY2(named.endsWith("; kernel 2.5 bins"), qPrintable(named));
    }

    void thePathFiguresNameTheClassifierTheTrialsFollowedWith() {
        // Figures 7 and 8 of a run that followed with a kernel, trained again on every set after
        // validation, say so; the paper's say nothing more; every title fits its figure.
        auto titles = [](const RunResult& run) {
            QStringList t;
            for (const char* file : {"figure7_passive_paths", "figure8_active_paths"}) {
                const RunFigure& f =
                    *std::find_if(runFigures().begin(), runFigures().end(),
                                  [&](const RunFigure& g) { return QString(g.file) == file; });
                QCustomPlot plot;
                if (!f.build(plot, run)) return QStringList();
                layOutAt(plot, f.size);
                test::checkLabelsFitTheirPanels(plot, file);
                t << qobject_cast<QCPTextElement*>(plot.plotLayout()->element(0, 0))->text();
            }
            return t;
        };
        QCOMPARE(titles(runs_.front()), (QStringList{"Figure 7 - passive contour following (PCF)",
                                                     "Figure 8 - active contour following (ACF)"}));
        ExperimentSpec spec = loadExperiment(test::sourcePath("experiments/paper_retrained.json"));
        spec.classifier.kernelSigma_bins = 2.5;
        const QStringList named = titles(runExperiment(spec, test::onSimulatedRig()));
        QCOMPARE(named.size(), 2);
        for (const QString& t : named)
            QVERIFY2(t.endsWith("; kernel 2.5 bins; trained on all 5 data sets"), qPrintable(t));
    }

    void recognitionRowsFollowTheConfusionTables() {
        // Figure 9 reads top to bottom in the order of the confusion tables shown beside it: the
        // templates' order, for the paper rectangle, cross, C, L.
        const RunResult& paper = runs_.front();
        QStringList followed;
        for (const std::string& shape : recognitionConfusion(paper).labels)
            followed << QString::fromStdString(shape);
        QCOMPARE(followed, (QStringList{"rectangle", "cross", "C", "L"}));
        QCustomPlot plot;
        QVERIFY(buildRecognitionFigure(plot, paper));
        const RunFigure& figure9 = *std::find_if(
            runFigures().begin(), runFigures().end(),
            [](const RunFigure& f) { return QString(f.file) == "figure9_recognition"; });
        layOutAt(plot, figure9.size);
        QMap<int, QString> byHeight;  // each template panel's top edge, as laid out
        for (QCPAxisRect* rect : plot.axisRects()) {
            // A title wrapped to its panel reads as one line.
            const QString title = rect->axis(QCPAxis::atTop)->label().simplified();
            if (title.startsWith("template: ")) byHeight.insert(rect->top(), title.mid(10));
        }
        const QStringList rows = byHeight.values();
        QCOMPARE(rows, followed);
    }

    void aCancelledRunDrawsOnlyItsTaps() {
        RunResult cancelled = runs_.front();
        cancelled.cancelled = true;
        QStringList drawn;
        for (const RunFigure& figure : runFigures()) {
            QCustomPlot plot;
            if (figure.build(plot, cancelled)) drawn << figure.file;
        }
        QCOMPARE(drawn, QStringList{"figure5_taps"});
    }

    void theSeedRatesFigureReadsCleanly() {
        const SeedRates rates = runSeeds(
            simulatedRigs(), loadExperiment(test::sourcePath("experiments/paper.json")), 1, 3, "");
        QCOMPARE(rates.seeds.size(), std::size_t(3));
        // Side by side at the exported size and narrower; stacked in a panel taller than wide,
        // as the window shows it, down to a narrow one: the legends take fewer entries to a line
        // rather than run off the figure.
        const QList<QPair<bool, FigureSize>> layouts{{false, kSeedFigureSize},
                                                     {false, FigureSize{1000, 600, 150}},
                                                     {true, FigureSize{600, 900, 150}},
                                                     {true, FigureSize{340, 900, 150}}};
        for (const auto& [stacked, size] : layouts) {
            QCustomPlot plot;
            QVERIFY(buildSeedRatesFigure(plot, rates, "paper", stacked));
            layOutAt(plot, size);
            const QString name = QString("seed_rates %1 at %2 x %3")
                                     .arg(stacked ? "stacked" : "side by side")
                                     .arg(size.width_px)
                                     .arg(size.height_px);
            test::checkLegendsClearOfData(plot, name);
            if (QTest::currentTestFailed()) return;
            test::checkLabelsFitTheirPanels(plot, name);
            if (QTest::currentTestFailed()) return;
        }
    }

    void theComparisonFigureShowsEachDifferenceWithItsInterval() {
        // A made-up comparison: 9 trials only B completed against 1 only A, one path only A
        // named rightly; no passive trials, no whole runs.
        PairedComparison c;
        c.nameA = "paper";
        c.nameB = "variant";
        c.seeds = 10;
        for (int i = 0; i < 100; ++i) c.activeCompleted.add(i <= 80, i < 80 || (i > 80 && i < 90));
        for (int i = 0; i < 50; ++i) c.recognisedRaw.add(true, i != 0);
        QCOMPARE(c.activeCompleted.onlyA, 1);
        QCOMPARE(c.activeCompleted.onlyB, 9);
        QCustomPlot plot;
        QVERIFY(buildComparisonFigure(plot, c));
        // One point per part compared, in its colour, the passive row left out; the first part
        // at the top.
        QCOMPARE(plot.graphCount(), 2);
        QCPGraph* top = plot.graph(0);
        QCPGraph* below = plot.graph(1);
        QCOMPARE(top->name(), QString("B - A: active trials completed"));
        QCOMPARE(below->name(), QString("B - A: completed paths recognised (paper's rule)"));
        QCOMPARE(top->data()->size(), 1);
        QCOMPARE(top->data()->at(0)->key, 2.0);
        QCOMPARE(below->data()->at(0)->key, 1.0);
        QCOMPARE(top->data()->at(0)->value, 100.0 * c.activeCompleted.difference());
        QCOMPARE(below->data()->at(0)->value, 100.0 * c.recognisedRaw.difference());
        QVERIFY(top->scatterStyle().pen().color() != below->scatterStyle().pen().color());
        QCPErrorBars* bars = nullptr;
        for (int i = 0; i < plot.plottableCount(); ++i)
            if (auto* b = qobject_cast<QCPErrorBars*>(plot.plottable(i)))
                if (b->dataPlottable() == top) bars = b;
        QVERIFY(bars);
        const QCPErrorBarsData upper = bars->data()->at(0);
        const double value = top->data()->at(0)->value;
        QVERIFY(qAbs(value - upper.errorMinus - 100.0 * c.activeCompleted.differenceLow()) < 1e-9);
        QVERIFY(qAbs(value + upper.errorPlus - 100.0 * c.activeCompleted.differenceHigh()) < 1e-9);
        // Each row says its counts and McNemar's p under its name.
        auto names = plot.graph(0)->keyAxis()->ticker().dynamicCast<QCPAxisTickerText>();
        QVERIFY(names);
        QCOMPARE(names->ticks().value(2.0),
                 QString("active trials completed\nA 81/100, B 89/100; only A 1, only B 9; p "
                         "0.021"));
        layOutAt(plot, kComparisonFigureSize);
        test::checkLabelsFitTheirPanels(plot, "compare");
        // Nothing compared: the title only.
        QCustomPlot empty;
        QVERIFY(!buildComparisonFigure(empty, PairedComparison{}));
        QCOMPARE(empty.plottableCount(), 0);
    }

    void theComparisonFigureShowsHowEachDifferenceSettles() {
        // Three made-up seeds of 10 active trials each and a run each: B completes 2, 0 and 3
        // trials that A lost; the runs differ at the first seed only. No passive trials.
        PairedComparison c;
        c.nameA = "paper";
        c.nameB = "variant";
        for (int onlyB : {2, 0, 3}) {
            for (int i = 0; i < 10; ++i) c.activeCompleted.add(i >= onlyB, true);
            c.paperResult.add(onlyB == 0, true);
            ++c.seeds;
            c.soFar.push_back(c);
        }
        const QList<QPair<bool, FigureSize>> layouts{{false, kComparisonFigureSize},
                                                     {true, FigureSize{840, 900, 100}}};
        for (const auto& [stacked, size] : layouts) {
            QCustomPlot plot;
            QVERIFY(buildComparisonFigure(plot, c, stacked));
            // After each seed, the active difference and its interval as they stood then.
            QCPGraph* line = nullptr;
            QCPGraph *low = nullptr, *high = nullptr;
            for (int i = 0; i < plot.graphCount(); ++i) {
                const QString name = plot.graph(i)->name();
                if (name == "active trials completed") line = plot.graph(i);
                if (name == "active trials completed (95 % low)") low = plot.graph(i);
                if (name == "active trials completed (95 % high)") high = plot.graph(i);
                QVERIFY2(!name.contains("passive"), qPrintable(name));  // nothing to compare
            }
            QVERIFY(line && low && high);
            QCOMPARE(line->data()->size(), 3);
            for (int i = 0; i < 3; ++i) {
                const PairedRate& at = c.soFar[std::size_t(i)].activeCompleted;
                QCOMPARE(line->data()->at(i)->key, double(i + 1));
                QCOMPARE(line->data()->at(i)->value, 100.0 * at.difference());
                QCOMPARE(low->data()->at(i)->value, 100.0 * at.differenceLow());
                QCOMPARE(high->data()->at(i)->value, 100.0 * at.differenceHigh());
            }
            // 2 of 10, then 2 of 20, then 5 of 30 percentage points.
            QCOMPARE(line->data()->at(1)->value, 10.0);
            QVERIFY(qAbs(line->data()->at(2)->value - 50.0 / 3.0) < 1e-9);
            const QString name = QString("compare %1").arg(stacked ? "stacked" : "side by side");
            layOutAt(plot, size);
            test::checkLegendsClearOfData(plot, name);
            if (QTest::currentTestFailed()) return;
            test::checkLabelsFitTheirPanels(plot, name);
            if (QTest::currentTestFailed()) return;
            // Over three seeds the value axis holds every interval, the first run's +100 too.
            QCOMPARE(line->valueAxis()->range().upper >= 100.0, true);
        }
        // Over 100 seeds, the first run only A had whole and 99 both had: the axis fits the
        // intervals from the tenth seed on, and the first seeds' run off the panel.
        PairedComparison many;
        for (int seed = 1; seed <= 100; ++seed) {
            many.paperResult.add(true, seed > 1);
            ++many.seeds;
            many.soFar.push_back(many);
        }
        QCustomPlot plot;
        QVERIFY(buildComparisonFigure(plot, many));
        QCPGraph* whole = nullptr;
        for (int i = 0; i < plot.graphCount(); ++i)
            if (plot.graph(i)->name() == "runs with the paper's result whole")
                whole = plot.graph(i);
        QVERIFY(whole);
        QCOMPARE(whole->data()->at(0)->value, -100.0);
        const QCPRange shown = whole->valueAxis()->range();
        QVERIFY2(shown.lower > -50.0 && shown.upper > 0.0,
                 qPrintable(QString("%1 to %2").arg(shown.lower).arg(shown.upper)));
        for (int i = 9; i < 100; ++i) {
            const PairedRate& at = many.soFar[std::size_t(i)].paperResult;
            QVERIFY(shown.contains(100.0 * at.differenceLow()));
            QVERIFY(shown.contains(100.0 * at.differenceHigh()));
        }
    }

    void aTrialPairShowsBothPathsOnTheObject() {
        // Seed 3's second active cross trial: the paper's histogram loses it at a corner, the
        // kernel's completes it (compare over seeds 1-10 lists it).
        const ExperimentSpec a = loadExperiment(test::sourcePath("experiments/paper.json"));
        const ExperimentSpec b = loadExperiment(test::sourcePath("experiments/paper_kernel.json"));
        const TrialPairRun pair =
            runTrialPair(simulatedRigs(), a, b, 3, FollowingMode::Active, "cross", 2);
        QCOMPARE(pair.seed, std::uint64_t(3));
        QVERIFY2(trialOutcome(pair.a).rfind("lost at a corner", 0) == 0,
                 trialOutcome(pair.a).c_str());
        QCOMPARE(trialOutcome(pair.b), std::string("completed"));
        QCOMPARE(pair.a.outline.vertices(), pair.b.outline.vertices());
        QCustomPlot plot;
        QVERIFY(buildTrialPairFigure(plot, pair));
        QMap<QString, QCPCurve*> curves;
        for (int i = 0; i < plot.plottableCount(); ++i)
            if (auto* c = qobject_cast<QCPCurve*>(plot.plottable(i))) curves[c->name()] = c;
        // The object once (both placed it alike), each path with how it ended, where A ended
        // and how far along the contour it got.
        QVERIFY(curves.contains("object") && !curves.contains("object in B"));
        QStringList paths;
        for (const QString& name : curves.keys())
            if (name.startsWith("A ") || name.startsWith("B ")) paths << name;
        QCOMPARE(paths.size(), 2);
        QVERIFY2(paths[0].startsWith("A paper: lost at a corner"), qPrintable(paths[0]));
        QCOMPARE(paths[1], QString("B paper_kernel: completed, named %1, %2 taps")
                               .arg(QString::fromStdString(pair.b.recognition.predicted))
                               .arg(pair.b.result.taps.size()));
        QCOMPARE(curves[paths[0]]->data()->size(), int(pair.a.result.path().size()));
        QCOMPARE(curves[paths[1]]->data()->size(), int(pair.b.result.path().size()));
        QVERIFY(curves.contains("where the trial ended"));
        QCOMPARE((curves["where the trial ended"]->data()->begin())->key,
                 pair.a.result.path().back().x);
        QVERIFY(curves.contains("furthest along the contour"));
        QCOMPARE(curves["furthest along the contour"]->data()->size(), 1);
        layOutAt(plot, FigureSize{700, 800, 100});
        QMap<int, QPair<QCPRange, QCPRange>> views;
        test::checkEqualAspect(plot, "trial pair", views);
        if (QTest::currentTestFailed()) return;
        test::checkLegendsClearOfData(plot, "trial pair");
        if (QTest::currentTestFailed()) return;
        // A trial one of them does not run is refused, naming it.
        QString message;
        try {
            runTrialPair(simulatedRigs(), a, b, 3, FollowingMode::Active, "cross", 3);
        } catch (const std::exception& e) {
            message = e.what();
        }
        QVERIFY2(message.contains("has no active trial 3 of 'cross'"), qPrintable(message));
    }
};

QTEST_MAIN(TestFigures)
#include "test_figures.moc"
