#include "app/gui/SeedRange.h"

#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QPushButton>
#include <QSpinBox>
#include <QTableWidget>
#include <QVBoxLayout>
#include <algorithm>

namespace activetouch {

SeedRangeBar::SeedRangeBar(const QString& firstName, const QString& lastName, int lastValue,
                           QPushButton* button, const QString& about, QWidget* parent)
    : QWidget(parent), first_(new QSpinBox), last_(new QSpinBox) {
    first_->setObjectName(firstName);
    last_->setObjectName(lastName);
    for (QSpinBox* s : {first_, last_}) s->setRange(0, kMaxSeed);
    first_->setValue(1);
    last_->setValue(lastValue);
    connect(first_, &QSpinBox::valueChanged, last_, [this](int v) {
        if (last_->value() < v) last_->setValue(v);
    });
    connect(last_, &QSpinBox::valueChanged, first_, [this](int v) {
        if (first_->value() > v) first_->setValue(v);
    });
    auto* row = new QHBoxLayout(this);
    row->setContentsMargins(0, 0, 0, 0);
    row->addWidget(new QLabel(tr("Seeds from")));
    row->addWidget(first_);
    row->addWidget(new QLabel(tr("to")));
    row->addWidget(last_);
    row->addWidget(button);
    auto* text = new QLabel(about);
    text->setWordWrap(true);
    row->addWidget(text, 1);
}

std::uint64_t SeedRangeBar::first() const {
    return static_cast<std::uint64_t>(first_->value());
}

std::uint64_t SeedRangeBar::last() const {
    return static_cast<std::uint64_t>(last_->value());
}

void SeedRangeBar::set(std::uint64_t first, std::uint64_t last) {
    // The last first, so that raising the range never drags the last along to the first.
    last_->setValue(static_cast<int>(std::min<std::uint64_t>(last, kMaxSeed)));
    first_->setValue(static_cast<int>(std::min<std::uint64_t>(first, kMaxSeed)));
}

SummaryTable::SummaryTable(const QString& objectName, const QString& hint, QWidget* parent)
    : QWidget(parent), state_(new QLabel(hint)), table_(new QTableWidget) {
    setObjectName(objectName);
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    state_->setWordWrap(true);
    state_->setTextInteractionFlags(Qt::TextSelectableByMouse);
    state_->setObjectName(objectName + "State");
    layout->addWidget(state_);
    table_->setObjectName(objectName + "Table");
    table_->setEditTriggers(QAbstractItemView::NoEditTriggers);
    table_->setSelectionMode(QAbstractItemView::ContiguousSelection);
    table_->verticalHeader()->setVisible(false);
    table_->setWordWrap(true);
    table_->setTextElideMode(Qt::ElideNone);
    table_->horizontalHeader()->setStretchLastSection(false);
    table_->hide();  // until there is something to show
    layout->addWidget(table_, 1);
}

void SummaryTable::setColumns(const QStringList& headings) {
    table_->setColumnCount(int(headings.size()));
    table_->setHorizontalHeaderLabels(headings);
    QHeaderView* header = table_->horizontalHeader();
    header->setSectionResizeMode(0, QHeaderView::Stretch);
    for (int c = 1; c < headings.size(); ++c)
        header->setSectionResizeMode(c, QHeaderView::ResizeToContents);
}

void SummaryTable::clearRows() {
    table_->clearSpans();
    table_->setRowCount(0);
}

void SummaryTable::addRow(const QStringList& cells, int indent) {
    const int row = table_->rowCount();
    table_->insertRow(row);
    for (int c = 0; c < cells.size() && c < table_->columnCount(); ++c) {
        const QString text = c == 0 ? QString(4 * indent, ' ') + cells[c] : cells[c];
        auto* item = new QTableWidgetItem(text);
        item->setToolTip(cells[c]);
        if (c > 0) item->setTextAlignment(Qt::AlignRight | Qt::AlignVCenter);
        table_->setItem(row, c, item);
    }
    table_->resizeRowToContents(row);
    fitHeight();
}

void SummaryTable::fitHeight() {
    // As tall as its rows, up to a third of a laptop screen, and it scrolls beyond; a short
    // window shrinks it to a few rows rather than growing.
    int height = table_->horizontalHeader()->height() + 2 * table_->frameWidth();
    for (int r = 0; r < table_->rowCount(); ++r) height += table_->rowHeight(r);
    table_->setMaximumHeight(std::min(height, 240));
    table_->setMinimumHeight(std::min(height, 90));
    table_->show();
}

void SummaryTable::addNote(const QString& text, int indent) {
    const int row = table_->rowCount();
    table_->insertRow(row);
    auto* item = new QTableWidgetItem(QString(4 * indent, ' ') + text);
    item->setToolTip(text);
    QFont italic = item->font();
    italic.setItalic(true);
    item->setFont(italic);
    table_->setItem(row, 0, item);
    if (table_->columnCount() > 1) table_->setSpan(row, 0, 1, table_->columnCount());
    table_->resizeRowToContents(row);
    fitHeight();
}

void SummaryTable::setState(const QString& text) {
    state_->setText(text);
}

QString SummaryTable::state() const {
    return state_->text();
}

}  // namespace activetouch
