#pragma once
// What the tabs that run over seeds share: the row that chooses the seeds, whose two boxes can
// never be given backwards (raising the first raises the last with it, lowering the last lowers
// the first), and the monospaced summary of their rates.
#include <QWidget>
#include <cstdint>

class QLabel;
class QPushButton;
class QSpinBox;

namespace activetouch {

/// The largest seed a box takes (a seed is a whole number 0..2^31-1, as in experiment files).
constexpr int kMaxSeed = 2147483647;

/// "Seeds from [first] to [last]", the tab's button, and a sentence on what the tab does.
class SeedRangeBar : public QWidget {
public:
    /// The boxes are named `firstName` and `lastName` and start at 1 and `lastValue`.
    SeedRangeBar(const QString& firstName, const QString& lastName, int lastValue,
                 QPushButton* button, const QString& about, QWidget* parent = nullptr);

    std::uint64_t first() const;
    std::uint64_t last() const;
    /// Shows `first`..`last` in the boxes (a seed beyond what a box takes shows as kMaxSeed).
    void set(std::uint64_t first, std::uint64_t last);

private:
    QSpinBox *first_, *last_;
};

/// A summary of rates over seeds: monospaced so its columns line up, selectable, and cut at the
/// right rather than widening the tab (the status bar and the log name the results folder too).
QLabel* seedsSummaryLabel(const QString& objectName, const QString& text);

}  // namespace activetouch
