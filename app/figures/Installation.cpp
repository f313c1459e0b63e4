#include "app/figures/Installation.h"

#include <QCoreApplication>
#include <QDir>
#include <QFileInfo>

#ifndef ACTIVETOUCH_SOURCE_DIR
#error "ACTIVETOUCH_SOURCE_DIR: the source tree a build-tree binary reads its files from"
#endif

namespace activetouch {

namespace {
/// The folder above the running binary's: <prefix> for <prefix>/bin/activetouch.
QString binaryPrefix() {
    // Linux names the running binary itself; elsewhere the application object knows it.
    QString bin = QFileInfo(QStringLiteral("/proc/self/exe")).canonicalFilePath();
    bin = bin.isEmpty()
              ? (QCoreApplication::instance() ? QCoreApplication::applicationDirPath() : QString())
              : QFileInfo(bin).path();
    return bin.isEmpty() ? QString() : QDir::cleanPath(bin + "/..");
}
}  // namespace

QString installedDataDirectory() {
    const QString prefix = binaryPrefix();
    if (prefix.isEmpty()) return {};
    const QString data = prefix + "/share/activetouch";
    return QFileInfo::exists(data + "/resources/fingertip") ? data : QString();
}

void useInstalledResources() {
    if (!qEnvironmentVariableIsEmpty("ACTIVETOUCH_RESOURCES")) return;
    const QString data = installedDataDirectory();
    if (!data.isEmpty()) qputenv("ACTIVETOUCH_RESOURCES", QFile::encodeName(data + "/resources"));
}

QString experimentsDirectory() {
    const QString data = installedDataDirectory();
    return data.isEmpty() ? QStringLiteral(ACTIVETOUCH_SOURCE_DIR "/experiments")
                          : data + "/experiments";
}

QString documentationDirectory() {
    const QString data = installedDataDirectory();
    const QString docs = data.isEmpty() ? QStringLiteral(ACTIVETOUCH_SOURCE_DIR "/docs")
                                        : binaryPrefix() + "/share/doc/activetouch";
    return QFileInfo::exists(docs) ? docs : QString();
}

QString iconDirectory() {
    const QString data = installedDataDirectory();
    return data.isEmpty() ? QStringLiteral(ACTIVETOUCH_SOURCE_DIR "/resources/icons")
                          : data + "/resources/icons";
}

}  // namespace activetouch
