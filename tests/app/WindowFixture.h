#pragma once
// What the window tests share: one window on the paper experiment, in a test folder, driven
// offscreen, and the helpers that click, wait and look at it as a person would.
#include <sys/resource.h>

#include <QComboBox>
#include <QDoubleSpinBox>
#include <QElapsedTimer>
#include <QFontMetricsF>
#include <QGroupBox>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QLabel>
#include <QLineEdit>
#include <QMessageBox>
#include <QPlainTextEdit>
#include <QProgressBar>
#include <QPushButton>
#include <QSpinBox>
#include <QStandardPaths>
#include <QStyleOptionGroupBox>
#include <QTabWidget>
#include <QTableWidget>
#include <QTemporaryDir>
#include <QToolButton>
#include <QtTest>
#include <csignal>
#include <thread>
#if defined(__x86_64__)
#include <cpuid.h>
#include <immintrin.h>
#endif

#include "app/figures/SweepFigures.h"
#include "app/gui/CalibrationDialog.h"
#include "app/gui/ComparisonTab.h"
#include "app/gui/DevicesPanel.h"
#include "app/gui/FollowingTab.h"
#include "app/gui/LiveView.h"
#include "app/gui/MainWindow.h"
#include "app/gui/PlotPanel.h"
#include "app/gui/ProtocolPanel.h"
#include "app/gui/ResultTabs.h"
#include "app/gui/ScenePanel.h"
#include "app/gui/SeedsTab.h"
#include "core/common/VectorState.h"
#include "core/fingertip/FingertipContactModel.h"
#include "core/run/Sweeps.h"
#include "devices/rigs/RigFile.h"
#include "qcustomplot.h"
#include "support/FigureChecks.h"
#include "support/FileSizeLimit.h"
#include "support/Files.h"
#include "support/Paths.h"
#include "support/SimulatedRun.h"

using namespace activetouch;
using test::linesIn;
using test::readJson;
using test::sourceFile;

namespace window_test {
/// What a seeds row lists as falling short: the active trials lost, then the paths misnamed.
inline QString shortfallsOf(const SeedOutcome& o) {
    QStringList items;
    for (const auto& f : o.passiveShortfalls) items << QString::fromStdString(f);
    for (const auto& f : o.failures) items << QString::fromStdString(f);
    for (const auto& m : o.misnamed()) items << QString::fromStdString(m);
    return items.join("; ");
}

inline void click(QMainWindow& w, const char* actionName) {
    QAction* action = w.findChild<QAction*>(actionName);
    QVERIFY2(action, actionName);
    for (QToolButton* b : w.findChildren<QToolButton*>())
        if (b->defaultAction() == action) {
            QTest::mouseClick(b, Qt::LeftButton);
            return;
        }
    QFAIL("no button for the action");
}

inline void writeJson(const QString& path, const QJsonObject& j) {
    QFile f(path);
    if (f.open(QIODevice::WriteOnly | QIODevice::Truncate)) f.write(QJsonDocument(j).toJson());
}

/// Clicks the check box in a checkable group box's title, as a person would.
inline void clickCheckBox(QGroupBox* box) {
    box->window()->raise();
    for (QWidget* w = box; w; w = w->parentWidget()) w->show();
    box->ensurePolished();
    QStyleOptionGroupBox option;
    option.initFrom(box);
    option.text = box->title();
    option.subControls =
        QStyle::SC_GroupBoxCheckBox | QStyle::SC_GroupBoxLabel | QStyle::SC_GroupBoxFrame;
    option.features = QStyleOptionFrame::None;
    option.state |= box->isChecked() ? QStyle::State_On : QStyle::State_Off;
    const QRect r = box->style()->subControlRect(QStyle::CC_GroupBox, &option,
                                                 QStyle::SC_GroupBoxCheckBox, box);
    QTest::mouseClick(box, Qt::LeftButton, Qt::NoModifier, r.center());
}

/// Whether a single run fills the panel (sweeps and seeds have their own runs).
inline bool filledByARun(const PlotPanel* p) {
    return !p->name().startsWith("sweep") && !p->name().startsWith("seed") &&
           !p->name().startsWith("compare");
}

/// Whether the plot draws any axis (after a redraw): an empty figure shows its hint alone.
inline bool drawsAnAxis(PlotPanel* p) {
    p->plot().replot(QCustomPlot::rpImmediateRefresh);
    for (QCPAxisRect* r : p->plot().axisRects())
        for (QCPAxis* a : r->axes())
            if (a->realVisibility()) return true;
    return false;
}

/// Brings the tab holding `w` to the front, as a person clicking its tabs would.
inline void showTab(QWidget* w) {
    for (; w && w->parentWidget(); w = w->parentWidget())
        if (auto* tabs = qobject_cast<QTabWidget*>(w->parentWidget()->parentWidget()))
            if (tabs->indexOf(w) >= 0) tabs->setCurrentWidget(w);
}

inline void showAt(PlotPanel* panel, QSize size) {
    panel->window()->resize(size);
    QCoreApplication::processEvents();
    panel->plot().replot(QCustomPlot::rpImmediateRefresh);
    QCoreApplication::processEvents();
    // What a person sees is a replot's: a figure drawn anew meanwhile (a run's last results
    // arriving) is laid out for the plot by its replot, as it is before it is ever painted.
    panel->plot().replot(QCustomPlot::rpImmediateRefresh);
}

#if defined(__x86_64__)
/// XINUSE: the register state components the thread has in use (bit 2: the AVX upper halves).
__attribute__((target("xsave"))) unsigned long long vectorStateInUse() {
    return _xgetbv(1);
}
constexpr unsigned long long kUpperHalvesInUse = 1ull << 2;
/// Leaves the upper halves of the vector registers in use, as some libraries' AVX code does
/// (written out, since a compiler ends its own AVX functions by clearing them). Only where the
/// CPU has AVX.
__attribute__((naked)) void markUpperHalvesInUse() {
    asm volatile("vcmpps $15, %ymm0, %ymm0, %ymm0\n\tret");
}
#endif

inline void closeErrorDialogs(QWidget& w) {
    for (QMessageBox* box : w.findChildren<QMessageBox*>("errorDialog")) box->close();
}

/// The run the window has just started ends within `timeout_ms`, successfully, and leaves the
/// window idle. `ended` spies on MainWindow::runEnded; its latest signal is taken.
inline void endsSuccessfully(MainWindow& w, QSignalSpy& ended, int timeout_ms = 60000) {
    QVERIFY(ended.wait(timeout_ms));
    QCOMPARE(ended.takeLast().at(0).toBool(), true);
    QTRY_VERIFY(!w.running());
}
}  // namespace window_test

using namespace window_test;

/// The window under test and what the tests do with it. Each test executable derives its
/// Q_OBJECT class from this and calls openWindow() in initTestCase, closeWindow() in
/// cleanupTestCase.
class WindowFixture : public QObject {
protected:
    QTemporaryDir dir_;
    std::unique_ptr<MainWindow> window_;

    /// Writes `name` in the test folder: the paper experiment with `keys` patched on top (an
    /// experiment that extends it); returns its path.
    QString paperVariant(const QString& name, const QString& keys) {
        const QString path = dir_.filePath(name);
        writeJson(path, QJsonDocument::fromJson(QString(R"({"extends": "%1", %2})")
                                                    .arg(sourceFile("experiments/paper.json"), keys)
                                                    .toUtf8())
                            .object());
        return path;
    }

    /// The protocol panel's widget for the experiment key `name` ("following_follow_step_mm").
    template <class W>
    W* protocolField(const char* name) {
        return window_->protocolPanel()->findChild<W*>(QString("protocol_") + name);
    }
    QComboBox* trialMode(int row) {
        auto* table = window_->protocolPanel()->findChild<QTableWidget*>("protocol_trials");
        return table ? qobject_cast<QComboBox*>(table->cellWidget(row, 1)) : nullptr;
    }
    QSpinBox* trialRepeats(int row) {
        auto* table = window_->protocolPanel()->findChild<QTableWidget*>("protocol_trials");
        return table ? qobject_cast<QSpinBox*>(table->cellWidget(row, 2)) : nullptr;
    }

    /// Starting `what` is refused with one error saying each of `parts`: nothing runs and the
    /// last run stays the last run.
    void expectRefused(RunController::What what, const QStringList& parts) {
        const auto before = window_->lastRun();
        QSignalSpy errors(window_.get(), &MainWindow::errorShown);
        QVERIFY(!window_->startRun(what));
        QCOMPARE(errors.count(), 1);
        const QString message = errors.takeFirst().at(0).toString();
        for (const QString& part : parts) QVERIFY2(message.contains(part), qPrintable(message));
        QVERIFY(!window_->running());
        QCOMPARE(window_->lastRun(), before);
        closeErrorDialogs(*window_);
    }

    void openWindow() {
        QStandardPaths::setTestModeEnabled(true);  // settings go to a test location
        QCoreApplication::setOrganizationName("ActiveTouchTest");
        window_ = std::make_unique<MainWindow>();
        window_->setOutputBase(dir_.filePath("runs"));
        window_->resize(1600, 1000);
        window_->show();
        QVERIFY(window_->openExperiment(sourceFile("experiments/paper.json")));
    }

    void closeWindow() {
        if (!window_) return;
        // Edits the tests left in the panels are discarded when the window asks.
        QTimer discard;
        discard.setInterval(20);
        QObject::connect(&discard, &QTimer::timeout, [] {
            if (auto* box = qobject_cast<QMessageBox*>(QApplication::activeModalWidget()))
                if (box->objectName() == "unsavedDialog")
                    box->button(QMessageBox::Discard)->click();
        });
        discard.start();
        window_->close();
        window_.reset();
    }
};
