#include "app/gui/SeedRange.h"

#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>
#include <QSpinBox>
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

QLabel* seedsSummaryLabel(const QString& objectName, const QString& text) {
    auto* label = new QLabel(text);
    label->setObjectName(objectName);
    label->setFont(QFont("Monospace", 9));
    label->setTextInteractionFlags(Qt::TextSelectableByMouse);
    label->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Preferred);
    return label;
}

}  // namespace activetouch
