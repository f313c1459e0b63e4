#include "app/gui/WholeFile.h"

#include <QSaveFile>
#include <stdexcept>

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

void writeWholeOrThrow(const QString& path, const QByteArray& bytes) {
    const QString failed = writeFileWhole(path, bytes);
    if (!failed.isEmpty())
        throw std::runtime_error("could not write " + path.toStdString() + " (" +
                                 failed.toStdString() +
                                 "); free space on its disk or choose a writable place");
}

}  // namespace activetouch
