// Wall time of the paper experiment run headless, as `activetouch-cli run` does it: without
// figures (budget <= 1 s) and with figures (budget <= 10 s). Median of 5 runs each.
#include <QApplication>
#include <QTemporaryDir>
#include <chrono>
#include <cstdio>

#include "app/figures/FigureExport.h"
#include "app/figures/ValidationFigures.h"
#include "app/run/ExperimentRun.h"
#include "bench/BenchHarness.h"
#include "qcustomplot.h"

using namespace activetouch;

int main(int argc, char** argv) {
    if (qEnvironmentVariableIsEmpty("DISPLAY") && qEnvironmentVariableIsEmpty("QT_QPA_PLATFORM")) qputenv("QT_QPA_PLATFORM", "offscreen");
    QApplication app(argc, argv);
    const ExperimentSpec spec = loadExperiment(std::string(ACTIVETOUCH_SOURCE_DIR) + "/experiments/paper.json");
    QTemporaryDir dir;
    auto once = [&](bool figures) {
        RunOptions options;
        options.outDir = dir.path().toStdString();
        const RunResult r = runExperiment(spec, options);
        writeRunTables(r, options.outDir);
        if (figures) {
            QCustomPlot plot;
            buildTapFigure(plot, r);
            exportFigure(plot, dir.filePath("figure5"), {"png", "pdf", "svg"}, {1600, 1100, 150});
            buildErrorFigure(plot, r);
            exportFigure(plot, dir.filePath("figure6"), {"png", "pdf", "svg"}, {1800, 1100, 150});
        }
        writeSummary(r, options.outDir, 0, 0);
    };
    bench::report("paper reproduction, headless, no figures", bench::medianMicroseconds([&] { once(false); }, 1, 5) / 1e6, "s", 1.0);
    bench::report("paper reproduction, headless, with figures", bench::medianMicroseconds([&] { once(true); }, 1, 5) / 1e6, "s", 10.0);
    return 0;
}
