#pragma once
// The screenshot tour (scripts/screenshots.sh): runs the experiment open in `window`, then over
// seeds 1-10, then compares it with paper_kernel.json beside it (if there) over seeds 1-10 and
// shows the first active trial the two ended differently in both; saves a PNG of the whole
// screen, of each tab, of the device and protocol panels, then of the replay of the first seed's
// lost active trial, if any, into `dir`; and quits. Returns the exit status.
#include <QString>

namespace activetouch {

class MainWindow;

int runScreenshotTour(MainWindow& window, const QString& dir);

}  // namespace activetouch
