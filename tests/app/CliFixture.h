#pragma once
// What the command-line tests share: a test folder to write files in, and the experiments they
// write there. Each test runs activetouch-cli as a user would (support/Cli.h).
#include <sys/resource.h>

#include <QDir>
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QProcess>
#include <QTemporaryDir>
#include <QtTest>
#include <csignal>

#include "devices/emulators/FakeRcxController.h"
#include "support/Cli.h"
#include "support/FileSizeLimit.h"
#include "support/Files.h"
#include "support/Paths.h"

using namespace activetouch;
using test::linesIn;
using test::linesOf;
using test::readJson;
using test::runCli;
using Outcome = test::CliOutcome;
using test::sourceFile;

/// Each test executable derives its Q_OBJECT class from this.
class CliFixture : public QObject {
protected:
    QTemporaryDir dir_;

    QString write(const QString& name, const QString& text) {
        QFile f(dir_.filePath(name));
        f.open(QIODevice::WriteOnly);
        f.write(text.toUtf8());
        return f.fileName();
    }

    /// The paper's experiment with one active trial on the rectangle a rig holds, trained on two
    /// data sets (one to train, one to validate).
    QString rectangleOnTheRig() {
        return write(
            "on_the_stage.json",
            QString(R"({"extends": "%1", "name": "on_the_stage", "training": {"data_sets": 2},
                "following": {"trials": [{"mode": "active", "object": {"shape": "rectangle",
                "width_mm": 48, "height_mm": 58, "offset_mm": [150, 150], "top_height_mm": 10}}]}})")
                .arg(sourceFile("experiments/paper.json")));
    }

};
