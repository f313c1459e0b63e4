// CPU share of the live view at 50 Hz (docs/benchmarks.md: <= 10 % of one core): the Live tab's
// taxel bars, traces and taxel scope (every channel over the last 10 s, scrolling) fed frames at
// 50 Hz and a new tap every second, for 10 s; process CPU time (user + system) over wall time. Run
// offscreen or under Xvfb.
#include <sys/resource.h>

#include <QApplication>
#include <QElapsedTimer>
#include <QTimer>
#include <atomic>
#include <chrono>
#include <cmath>
#include <thread>

#include "app/gui/LiveView.h"
#include "app/gui/TaxelScope.h"
#include "bench/BenchHarness.h"

using namespace activetouch;

namespace {
double cpuSeconds() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return u.ru_utime.tv_sec + u.ru_utime.tv_usec * 1e-6 + u.ru_stime.tv_sec +
           u.ru_stime.tv_usec * 1e-6;
}
}  // namespace

int main(int argc, char** argv) {
    if (qEnvironmentVariableIsEmpty("DISPLAY") && qEnvironmentVariableIsEmpty("QT_QPA_PLATFORM"))
        qputenv("QT_QPA_PLATFORM", "offscreen");
    QApplication app(argc, argv);
    LiveFeed feed;
    LiveView view(feed);
    view.resize(1200, 800);
    view.show();
    std::atomic<bool> stop{false};
    // The rig side: a tap a second, its frames streamed at 50 Hz.
    std::thread rig([&] {
        int n = 0;
        while (!stop) {
            TapRecord r;
            r.tap = Tap(kSamplesPerTap, kFingertipTaxels);
            for (int s = 0; s < kSamplesPerTap; ++s)
                for (int k = 0; k < kFingertipTaxels; ++k)
                    r.tap.at(s, k) = 100 + 80 * std::sin(0.1 * s + k + n);
            feed.publishTap(r, "benchmark tap", true);
            for (int s = 0; s < kSamplesPerTap && !stop; ++s) {
                feed.publishFrame(r.tap.frame(s), kFingertipTaxels);
                std::this_thread::sleep_for(std::chrono::milliseconds(20));
            }
            ++n;
        }
    });
    // Let it settle, then measure 10 s with the scope hidden and 10 s with it shown: the tab's
    // share, and the scope's as the difference.
    struct Phase {
        double cpu = 0.0, seconds = 0.0;
        std::uint64_t frames = 0, scopeFrames = 0;
    } phases[2];
    QElapsedTimer wall;
    double cpu0 = 0.0;
    std::uint64_t frames0 = 0, scope0 = 0;
    auto start = [&] {
        cpu0 = cpuSeconds();
        frames0 = view.framesDrawn();
        scope0 = view.scope()->framesDrawn();
        wall.start();
    };
    auto finish = [&](Phase& p) {
        p = {cpuSeconds() - cpu0, wall.elapsed() / 1000.0, view.framesDrawn() - frames0,
             view.scope()->framesDrawn() - scope0};
    };
    view.scope()->hide();
    QTimer::singleShot(1000, [&] {
        start();
        QTimer::singleShot(10000, [&] {
            finish(phases[0]);
            view.scope()->show();
            QTimer::singleShot(1000, [&] {
                start();
                QTimer::singleShot(10000, [&] {
                    finish(phases[1]);
                    app.quit();
                });
            });
        });
    });
    app.exec();
    stop = true;
    rig.join();
    auto share = [](const Phase& p) { return 100.0 * p.cpu / p.seconds; };
    std::printf(
        "live view drew %.1f frames per second; with the scope shown %.1f, the scope %.1f\n",
        phases[0].frames / phases[0].seconds, phases[1].frames / phases[1].seconds,
        phases[1].scopeFrames / phases[1].seconds);
    bench::report("live view at 50 Hz (bars, traces), share of one core", share(phases[0]), "%",
                  10.0);
    bench::report("taxel scope at 50 Hz (12 taxels and the total, 10 s), share of one core",
                  share(phases[1]) - share(phases[0]), "%", 10.0);
    return 0;
}
