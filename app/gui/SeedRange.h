#pragma once
// What the tabs that run over seeds share: the row that chooses the seeds, whose two boxes can
// never be given backwards (raising the first raises the last with it, lowering the last lowers
// the first), and the table summarising their rates.
#include <QWidget>
#include <cstdint>

class QLabel;
class QTableWidget;
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

/// A summary of rates over seeds as a table: a line saying what it summarises and how far the run
/// has got, then one row per entry (a note spans the row). No cell's text is cut: the first
/// column takes the room left and wraps, and every cell has its whole text as its tooltip.
class SummaryTable : public QWidget {
public:
    SummaryTable(const QString& objectName, const QString& hint, QWidget* parent = nullptr);
    void setColumns(const QStringList& headings);
    void clearRows();
    /// A row of `cells`, the first indented by `indent` levels under the row above.
    void addRow(const QStringList& cells, int indent = 0);
    /// A note across the whole row.
    void addNote(const QString& text, int indent = 0);
    void setState(const QString& text);
    QString state() const;
    QTableWidget* table() const { return table_; }

private:
    void fitHeight();
    QLabel* state_;
    QTableWidget* table_;
};

}  // namespace activetouch
