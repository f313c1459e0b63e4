// CPU share of the live view at 50 Hz (docs/benchmarks.md: <= 10 % of one core): the Live tab's
// taxel bars and traces fed frames at 50 Hz and a new tap every second, for 10 s; process CPU time
// (user + system) over wall time. Run offscreen or under Xvfb.
#include <sys/resource.h>

#include <QApplication>
#include <QElapsedTimer>
#include <QTimer>
#include <atomic>
#include <chrono>
#include <cmath>
#include <thread>

#include "app/gui/LiveView.h"
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
    // Let it settle, then measure 10 s.
    double cpu0 = 0;
    QElapsedTimer wall;
    std::uint64_t frames0 = 0;
    QTimer::singleShot(1000, [&] {
        cpu0 = cpuSeconds();
        frames0 = view.framesDrawn();
        wall.start();
        QTimer::singleShot(10000, [&] { app.quit(); });
    });
    app.exec();
    const double share = 100.0 * (cpuSeconds() - cpu0) / (wall.elapsed() / 1000.0);
    const double rate = (view.framesDrawn() - frames0) / (wall.elapsed() / 1000.0);
    stop = true;
    rig.join();
    std::printf("live view drew %.1f frames per second\n", rate);
    bench::report("live view at 50 Hz, share of one core", share, "%", 10.0);
    return 0;
}
