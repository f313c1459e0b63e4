// Wall time of the whole paper reproduction (training, validation, 10 following trials,
// recognition) run headless, as `activetouch-cli run` does it: without
// figures (budget <= 1 s) and with figures (budget <= 10 s). Median of 5 runs each.
#include <QApplication>
#include <QTemporaryDir>
#include <chrono>
#include <cstdio>

#include "app/figures/FollowingFigures.h"
#include "core/run/ExperimentRun.h"
#include "core/run/RunArtefacts.h"
#include "bench/BenchHarness.h"
#include "support/SimulatedRun.h"

using namespace activetouch;

int main(int argc, char** argv) {
    if (qEnvironmentVariableIsEmpty("DISPLAY") && qEnvironmentVariableIsEmpty("QT_QPA_PLATFORM"))
        qputenv("QT_QPA_PLATFORM", "offscreen");
    QApplication app(argc, argv);
    const ExperimentSpec spec =
        loadExperiment(std::string(ACTIVETOUCH_SOURCE_DIR) + "/experiments/paper.json");
    QTemporaryDir dir;
    auto once = [&](bool figures) {
        RunOptions options = test::onSimulatedRig();
        options.outDir = dir.path().toStdString();
        const RunResult r = runExperiment(spec, options);
        writeRunTables(r, options.outDir);
        if (figures) writeRunFigures(r, dir.path());
        writeSummary(r, options.outDir, 0, 0);
    };
    bench::report("paper reproduction, headless, no figures",
                  bench::medianMicroseconds([&] { once(false); }, 1, 5) / 1e6, "s", 1.0);
    bench::report("paper reproduction, headless, with figures",
                  bench::medianMicroseconds([&] { once(true); }, 1, 5) / 1e6, "s", 10.0);
    return 0;
}
