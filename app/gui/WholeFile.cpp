#include "app/gui/WholeFile.h"

#include <QSaveFile>

namespace activetouch {

QString writeFileWhole(const QString& path, const QByteArray& bytes) {
    QSaveFile file(path);
    // Unbuffered, so that a write the disk cuts short shows in its count: a buffered QSaveFile can
    // commit a file that a full disk truncated.
    if (!file.open(QIODevice::WriteOnly | QIODevice::Unbuffered)) return file.errorString();
    if (file.write(bytes) != bytes.size()) {
        const QString why = file.errorString();
        file.cancelWriting();
        return why.isEmpty() || why == QLatin1String("Unknown error")
                   ? QStringLiteral("the disk took only part of it")
                   : why;
    }
    if (!file.commit()) return file.errorString();
    return {};
}

}  // namespace activetouch
