#pragma once
// Reading back what a run wrote.
#include <QDir>
#include <QFile>
#include <QJsonDocument>
#include <QJsonObject>
#include <QString>
#include <QStringList>

namespace activetouch::test {

/// The file's bytes (empty if it cannot be read).
inline QByteArray bytesOf(const QString& path) {
    QFile f(path);
    if (!f.open(QIODevice::ReadOnly)) return {};
    return f.readAll();
}

/// Copies folder `from` to `to`, files and subfolders.
inline void copyFolder(const QString& from, const QString& to) {
    QDir().mkpath(to);
    for (const QFileInfo& e :
         QDir(from).entryInfoList(QDir::Files | QDir::Dirs | QDir::NoDotAndDotDot)) {
        if (e.isDir())
            copyFolder(e.filePath(), to + "/" + e.fileName());
        else
            QFile::copy(e.filePath(), to + "/" + e.fileName());
    }
}

/// How many lines the file holds (-1 if it cannot be read): a recording's header and rows.
inline int linesIn(const QString& path) {
    QFile f(path);
    if (!f.open(QIODevice::ReadOnly)) return -1;
    return static_cast<int>(f.readAll().count('\n'));
}

/// The file's non-empty lines (none if it cannot be read): a table's header and rows.
inline QStringList linesOf(const QString& path) {
    QFile f(path);
    if (!f.open(QIODevice::ReadOnly)) return {};
    return QString::fromUtf8(f.readAll()).split('\n', Qt::SkipEmptyParts);
}

/// The JSON object a file holds (empty if it cannot be read): a summary, a rates table.
inline QJsonObject readJson(const QString& path) {
    QFile f(path);
    if (!f.open(QIODevice::ReadOnly)) return {};
    return QJsonDocument::fromJson(f.readAll()).object();
}

}  // namespace activetouch::test
