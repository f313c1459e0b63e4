#pragma once
// Two boxes for a range of seeds, first and last, that can never be given backwards: raising the
// first raises the last with it, lowering the last lowers the first.
#include <QSpinBox>

namespace activetouch {

/// The largest seed a box takes (a seed is a whole number 0..2^31-1, as in experiment files).
constexpr int kMaxSeed = 2147483647;

inline void makeSeedRange(QSpinBox* first, QSpinBox* last, int firstValue, int lastValue) {
    for (QSpinBox* s : {first, last}) s->setRange(0, kMaxSeed);
    first->setValue(firstValue);
    last->setValue(lastValue);
    QObject::connect(first, &QSpinBox::valueChanged, last, [last](int v) {
        if (last->value() < v) last->setValue(v);
    });
    QObject::connect(last, &QSpinBox::valueChanged, first, [first](int v) {
        if (first->value() > v) first->setValue(v);
    });
}

}  // namespace activetouch
