#pragma once
// The built headless runner, started as a user starts it (its path comes from CMake).
#include <QProcess>
#include <QString>
#include <QStringList>

namespace activetouch::test {

struct CliOutcome {
    int exitCode;  ///< -1 if it crashed or did not end within five minutes
    QString out, err;
};

inline CliOutcome runCli(const QStringList& args) {
    QProcess p;
    p.start(qEnvironmentVariable("ACTIVETOUCH_CLI"), args);
    p.waitForFinished(300000);
    return {p.exitStatus() == QProcess::NormalExit ? p.exitCode() : -1, p.readAllStandardOutput(),
            p.readAllStandardError()};
}

}  // namespace activetouch::test
