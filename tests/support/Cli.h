#pragma once
// The built headless runner, started as a user starts it (its path comes from CMake).
#include <QProcess>
#include <QString>
#include <QStringList>
#include <functional>

namespace activetouch::test {

struct CliOutcome {
    int exitCode;  ///< -1 if it crashed or did not end within five minutes
    QString out, err;
};

/// Runs the runner with `args`; `childSetUp`, if given, runs in the child before the runner
/// starts (to set a resource limit, say).
inline CliOutcome runCli(const QStringList& args,
                         const std::function<void()>& childSetUp = nullptr) {
    QProcess p;
    if (childSetUp) p.setChildProcessModifier(childSetUp);
    p.start(qEnvironmentVariable("ACTIVETOUCH_CLI"), args);
    p.waitForFinished(300000);
    return {p.exitStatus() == QProcess::NormalExit ? p.exitCode() : -1, p.readAllStandardOutput(),
            p.readAllStandardError()};
}

}  // namespace activetouch::test
