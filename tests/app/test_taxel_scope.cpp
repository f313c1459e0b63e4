// The live tab's taxel scope as a person uses it: every channel the fingertip streams over the
// last seconds, a window of 2-60 s, held while the live view is paused, the total against the
// contact threshold, and the frames in the time range shown written as CSV.
#include <QTemporaryDir>
#include <QtTest>
#include <cmath>

#include "app/gui/LiveView.h"
#include "app/gui/PlotPanel.h"
#include "app/gui/TaxelScope.h"
#include "qcustomplot.h"
#include "support/Files.h"

using namespace activetouch;

namespace {
/// Channel k of frame i: distinct for every channel and frame.
double reading(int i, int k) {
    return 10.0 + k + 0.5 * (i % 40);
}

std::vector<double> frameAt(int i, int channels) {
    std::vector<double> f;
    for (int k = 0; k < channels; ++k) f.push_back(reading(i, k));
    return f;
}
}  // namespace

class TestTaxelScope : public QObject {
    Q_OBJECT

private slots:
    void showsEveryChannelOverTheWindowAsked() {
        TaxelScope scope;
        scope.resize(800, 400);
        scope.show();
        QCOMPARE(scope.channels(), 0);
        // 20 s of the paper's fingertip at 50 Hz.
        for (int i = 0; i < 1000; ++i) scope.append(i / 50.0, frameAt(i, 12));
        QCOMPARE(scope.channels(), 12);
        QVERIFY(scope.redraw());
        QCustomPlot& p = scope.panel()->plot();
        QCOMPARE(p.graphCount(), 13);  // every taxel and the total
        // The axis shown counts back from the newest frame over the window it opens with; the
        // traces' own axis is the time since the scope began.
        QCOMPARE(p.xAxis->range().lower, -10.0);
        QCOMPARE(p.xAxis->range().upper, 0.0);
        QCOMPARE(p.xAxis2->range().upper, 999 / 50.0);
        QCOMPARE(p.graph(0)->keyAxis(), p.xAxis2);
        for (const double asked : {2.0, 60.0}) {
            scope.setWindowSeconds(asked);
            QCOMPARE(p.xAxis->range().size(), asked);
            QVERIFY(std::abs(p.xAxis2->range().size() - asked) < 1e-9);
        }
        scope.setWindowSeconds(0.5);  // held to 2-60 s
        QCOMPARE(scope.windowSeconds(), TaxelScope::kLeastWindow_s);
        scope.setWindowSeconds(600.0);
        QCOMPARE(scope.windowSeconds(), TaxelScope::kMostWindow_s);
        // A fingertip of 24 channels starts the scope afresh with all of them.
        scope.append(20.0, frameAt(0, 24));
        QCOMPARE(scope.channels(), 24);
        QCOMPARE(p.graphCount(), 25);
        // The last minute is kept, no more.
        for (int i = 1; i <= 4000; ++i) scope.append(20.0 + i / 50.0, frameAt(i, 24));
        QVERIFY(p.graph(0)->data()->begin()->key >= 20.0 + 4000 / 50.0 - 60.0 - 1e-9);
    }

    void theTotalMeetsTheContactThreshold() {
        TaxelScope scope;
        scope.resize(800, 400);
        scope.show();
        scope.setContactThreshold(40.0);
        for (int i = 0; i < 100; ++i) scope.append(i / 50.0, frameAt(i, 12));
        QVERIFY(scope.redraw());
        QCustomPlot& p = scope.panel()->plot();
        QCPGraph* total = p.graph(12);
        double sum = 0.0;
        for (int k = 0; k < 12; ++k) sum += reading(99, k);
        QCOMPARE(total->data()->at(99)->value, sum);
        QCOMPARE(total->valueAxis(), p.yAxis2);
        auto* threshold = qobject_cast<QCPItemStraightLine*>(p.item(0));
        QVERIFY(threshold && threshold->visible());
        QCOMPARE(threshold->point1->coords().y(), 40.0);
        QVERIFY(p.yAxis2->range().contains(sum));
    }

    void exportsTheFramesShown() {
        TaxelScope scope;
        scope.resize(800, 400);
        scope.show();
        for (int i = 0; i < 1000; ++i) scope.append(i / 50.0, frameAt(i, 12));
        scope.setWindowSeconds(4.0);
        QTemporaryDir dir;
        const QString path = dir.filePath("scope.csv");
        scope.exportVisibleCsv(path);
        const QStringList lines = test::linesOf(path);
        QStringList header{"time_s"};
        for (int k = 0; k < 12; ++k) header << QString("taxel_%1").arg(k);
        header << "total";
        QCOMPARE(lines.front(), header.join(','));
        // The frames of the last 4 s shown, each with every taxel and the total.
        const QCPRange shown = scope.panel()->plot().xAxis2->range();
        QVERIFY(std::abs(shown.size() - 4.0) < 1e-9);
        int firstShown = -1, count = 0;
        for (int i = 0; i < 1000; ++i)
            if (shown.contains(i / 50.0)) {
                if (firstShown < 0) firstShown = i;
                ++count;
            }
        QVERIFY(count >= 200 && count <= 201);
        QCOMPARE(lines.size(), 1 + count);
        const QStringList first = lines.at(1).split(',');
        QCOMPARE(first.size(), 14);
        QCOMPARE(first.front(), QString::number(firstShown / 50.0, 'f', 3));
        double sum = 0.0;
        for (int k = 0; k < 12; ++k) {
            QCOMPARE(first.at(1 + k).toDouble(), reading(firstShown, k));
            sum += reading(firstShown, k);
        }
        QCOMPARE(first.at(13).toDouble(), sum);
        // A place that cannot be written is named, and nothing is left behind.
        QVERIFY_THROWS_EXCEPTION(std::runtime_error,
                                 scope.exportVisibleCsv(dir.filePath("no/such/folder/scope.csv")));
    }

    void pausingTheLiveViewHoldsTheScope() {
        LiveFeed feed;
        LiveView view(feed);
        view.resize(1200, 800);
        view.show();
        auto stream = [&](int frames) {
            for (int i = 0; i < frames; ++i) {
                const std::vector<double> f = frameAt(i, 12);
                feed.publishFrame(f.data(), 12);
                QTest::qWait(25);
            }
        };
        stream(20);
        TaxelScope* scope = view.scope();
        QCOMPARE(scope->channels(), 12);
        const int before = scope->panel()->plot().graph(0)->data()->size();
        QVERIFY(before > 5);
        view.setPaused(true);
        stream(20);
        QCOMPARE(scope->panel()->plot().graph(0)->data()->size(), before);
        view.setPaused(false);
        stream(20);
        QVERIFY(scope->panel()->plot().graph(0)->data()->size() > before + 5);
    }
};

QTEST_MAIN(TestTaxelScope)
#include "test_taxel_scope.moc"
