#pragma once
// A box in a failure's message: "(left, top, width×height)" in whole pixels.
#include <QRectF>
#include <QString>

inline QString boxText(const QRectF& r) {
    return QString("(%1, %2, %3×%4)")
        .arg(r.left(), 0, 'f', 0)
        .arg(r.top(), 0, 'f', 0)
        .arg(r.width(), 0, 'f', 0)
        .arg(r.height(), 0, 'f', 0);
}
