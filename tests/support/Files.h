#pragma once
// Reading back what a run wrote.
#include <QFile>
#include <QString>

namespace activetouch::test {

/// How many lines the file holds (-1 if it cannot be read): a recording's header and rows.
inline int linesIn(const QString& path) {
    QFile f(path);
    if (!f.open(QIODevice::ReadOnly)) return -1;
    return static_cast<int>(f.readAll().count('\n'));
}

}  // namespace activetouch::test
