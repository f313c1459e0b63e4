// The window as a desktop application: its menus and shortcuts, recent files, files dropped on
// it, the prompt before unsaved edits are lost, the results folder preference, and its layout.
#include <QAction>
#include <QApplication>
#include <QDesktopServices>
#include <QDialog>
#include <QDialogButtonBox>
#include <QDir>
#include <QDockWidget>
#include <QDragEnterEvent>
#include <QDropEvent>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QJsonDocument>
#include <QJsonObject>
#include <QLabel>
#include <QLineEdit>
#include <QMenuBar>
#include <QMessageBox>
#include <QMimeData>
#include <QPushButton>
#include <QScreen>
#include <QSettings>
#include <QStandardPaths>
#include <QToolBar>
#include <QUrl>

#include "app/figures/Installation.h"
#include "app/gui/ComparisonTab.h"
#include "app/gui/DevicesPanel.h"
#include "app/gui/HelpBrowser.h"
#include "app/gui/LiveView.h"
#include "app/gui/MainWindow.h"
#include "app/gui/PlotPanel.h"
#include "app/gui/ProtocolPanel.h"
#include "app/gui/ScenePanel.h"
#include "app/gui/SeedsTab.h"
#include "core/common/InputError.h"
#include "core/io/InputFile.h"
#include "core/io/JsonText.h"
#include "qcustomplot.h"

namespace activetouch {

namespace {
constexpr int kRecentFiles = 8;
}  // namespace

QString MainWindow::defaultResultsFolder() {
    QString documents = QStandardPaths::writableLocation(QStandardPaths::DocumentsLocation);
    if (documents.isEmpty()) documents = QDir::homePath();
    return QDir(documents).filePath("ActiveTouch/results");
}

void MainWindow::setResultsFolder(const QString& dir) {
    resultsFolder_ = QDir::cleanPath(QDir(dir).absolutePath());
    outputBase_ = resultsFolder_;
    QSettings().setValue("resultsFolder", resultsFolder_);
    showResultsFolder();
}

void MainWindow::setOutputBase(const QString& dir) {
    outputBase_ = dir;  // this session only: the preference stays as it is
    showResultsFolder();
}

void MainWindow::showResultsFolder() {
    PlotPanel::setExportFolder(outputBase_);
    if (!resultsLabel_) return;
    resultsLabel_->setText(tr("Results: <a href=\"open\">%1</a>").arg(outputBase_.toHtmlEscaped()));
    resultsLabel_->setToolTip(
        tr("Runs are written under this folder; click to open it, change "
           "it in File > Preferences"));
}

bool MainWindow::openResultsFolder() {
    if (!QDir().mkpath(outputBase_)) {
        showError(tr("Cannot create the results folder %1; choose a writable folder in File > "
                     "Preferences.")
                      .arg(outputBase_));
        return false;
    }
    if (!QDesktopServices::openUrl(QUrl::fromLocalFile(outputBase_))) {
        showError(tr("No file manager could open %1; open it by hand.").arg(outputBase_));
        return false;
    }
    return true;
}

void MainWindow::showPreferences() {
    QDialog dialog(this);
    dialog.setObjectName("preferencesDialog");
    dialog.setWindowTitle(tr("Preferences"));
    auto* form = new QFormLayout(&dialog);
    auto* folder = new QLineEdit(resultsFolder_);
    folder->setObjectName("resultsFolder");
    folder->setMinimumWidth(360);
    auto* browse = new QPushButton(tr("Browse..."));
    connect(browse, &QPushButton::clicked, &dialog, [&] {
        const QString dir =
            QFileDialog::getExistingDirectory(&dialog, tr("Results folder"), folder->text());
        if (!dir.isEmpty()) folder->setText(dir);
    });
    auto* row = new QHBoxLayout;
    row->addWidget(folder, 1);
    row->addWidget(browse);
    form->addRow(tr("Results folder"), row);
    auto* note = new QLabel(tr("Each run gets a folder of its own under it (default: %1).")
                                .arg(defaultResultsFolder()));
    note->setWordWrap(true);
    form->addRow(note);
    auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel |
                                         QDialogButtonBox::RestoreDefaults);
    connect(buttons->button(QDialogButtonBox::RestoreDefaults), &QPushButton::clicked, &dialog,
            [&] { folder->setText(defaultResultsFolder()); });
    connect(buttons, &QDialogButtonBox::accepted, &dialog, [&] {
        const QString dir = folder->text().trimmed();
        if (dir.isEmpty() || !QDir().mkpath(dir)) {
            QMessageBox::warning(&dialog, tr("Preferences"),
                                 tr("The results folder \"%1\" cannot be created; choose a "
                                    "writable folder.")
                                     .arg(dir));
            return;
        }
        dialog.accept();
    });
    connect(buttons, &QDialogButtonBox::rejected, &dialog, &QDialog::reject);
    form->addRow(buttons);
    if (dialog.exec() != QDialog::Accepted) return;
    setResultsFolder(folder->text().trimmed());
    log(tr("results folder: %1").arg(resultsFolder_));
}

void MainWindow::fillRecentMenu() {
    recentMenu_->clear();
    const QStringList files = QSettings().value("recentExperiments").toStringList();
    for (const QString& f : files) {
        QAction* a = recentMenu_->addAction(QFileInfo(f).fileName(), this, [this, f] {
            if (maySwitchExperiment()) openExperiment(f);
        });
        a->setToolTip(f);
        a->setStatusTip(f);
        a->setEnabled(QFileInfo::exists(f));
    }
    if (files.isEmpty()) recentMenu_->addAction(tr("(none yet)"))->setEnabled(false);
    recentMenu_->addSeparator();
    recentMenu_->addAction(tr("Clear the list"), this,
                           [] { QSettings().remove("recentExperiments"); });
}

QStringList MainWindow::recentExperiments() const {
    return QSettings().value("recentExperiments").toStringList();
}

void MainWindow::rememberRecent(const QString& path) {
    const QString absolute = QFileInfo(path).absoluteFilePath();
    QStringList files = QSettings().value("recentExperiments").toStringList();
    files.removeAll(absolute);
    files.prepend(absolute);
    while (files.size() > kRecentFiles) files.removeLast();
    QSettings().setValue("recentExperiments", files);
}

void MainWindow::chooseExperiment() {
    if (!maySwitchExperiment()) return;
    const QString path =
        QFileDialog::getOpenFileName(this, tr("Open an experiment"),
                                     QFileInfo(experimentPath_).path(), tr("Experiments (*.json)"));
    if (!path.isEmpty()) openExperiment(path);
}

void MainWindow::chooseSaveAs() {
    const QString path = QFileDialog::getSaveFileName(this, tr("Save the experiment"),
                                                      experimentPath_, tr("Experiments (*.json)"));
    // The saved file becomes the one open, as it was written.
    if (!path.isEmpty() && saveExperiment(path) && QFileInfo(path) != QFileInfo(experimentPath_))
        openExperiment(path);
}

void MainWindow::saveExperimentInPlace() {
    if (experimentPath_.isEmpty()) {
        showError(tr("Open an experiment first."));
        return;
    }
    const QFileInfo file(experimentPath_);
    if (!(file.exists() ? file.isWritable() : QFileInfo(file.path()).isWritable())) {
        chooseSaveAs();  // an installed example: save a copy
        return;
    }
    saveExperiment(experimentPath_);
}

void MainWindow::chooseExportFolder() {
    if (!last_) {
        showError(tr("There is no run to export yet."));
        return;
    }
    const QString dir =
        QFileDialog::getExistingDirectory(this, tr("Export all figures into"), lastOutDir_);
    if (!dir.isEmpty()) exportAllFigures(dir);
}

// ---- unsaved edits ----

Json MainWindow::documentAsShown() const {
    Json j = protocol_->patch(experimentJson_);
    j["scene"] = sceneToJson(scene_->sceneFromPanel(spec_.scene));
    return j;
}

bool MainWindow::hasUnsavedEdits() const {
    if (experimentPath_.isEmpty()) return false;
    try {
        return documentAsShown() != savedDocument_;
    } catch (const std::exception&) {
        return true;  // a panel holds a value no file could: an edit
    }
}

void MainWindow::updateModified() {
    setWindowModified(hasUnsavedEdits());
}

bool MainWindow::maySwitchExperiment() {
    if (!hasUnsavedEdits()) return true;
    QMessageBox box(QMessageBox::Question, tr("Unsaved changes"),
                    tr("The scene or protocol panel shows changes to %1 that are not saved.")
                        .arg(QFileInfo(experimentPath_).fileName()),
                    QMessageBox::Save | QMessageBox::Discard | QMessageBox::Cancel, this);
    box.setObjectName("unsavedDialog");
    box.setInformativeText(tr("Save them before going on?"));
    box.setDefaultButton(QMessageBox::Save);
    const int answer = box.exec();
    if (answer == QMessageBox::Discard) return true;
    if (answer != QMessageBox::Save) return false;
    const QString before = experimentPath_;
    saveExperimentInPlace();
    return !hasUnsavedEdits() || experimentPath_ != before;
}

// ---- files dropped on the window ----

MainWindow::DroppedKind MainWindow::kindOfDropped(const QString& path) {
    const QFileInfo info(path);
    if (info.isDir()) return DroppedKind::RunFolder;
    if (info.suffix().compare("csv", Qt::CaseInsensitive) == 0) return DroppedKind::Recording;
    if (info.suffix().compare("json", Qt::CaseInsensitive) != 0) return DroppedKind::Unknown;
    // Read as every file is (a regular file, within its bound); one that cannot be is opened as
    // an experiment, whose error names it.
    std::string text;
    try {
        text = readBoundedFile(path.toStdString(), kMaxJsonFileBytes, "an experiment or rig file");
    } catch (const InputError&) {
        return DroppedKind::Experiment;
    }
    const QJsonObject j = QJsonDocument::fromJson(QByteArray::fromStdString(text)).object();
    const bool experiment = j.contains("training") || j.contains("following") ||
                            j.contains("extends") || j.contains("scene");
    const bool rig = j.contains("stage") || j.contains("tapper") || j.contains("fingertip");
    return rig && !experiment ? DroppedKind::Rig : DroppedKind::Experiment;
}

bool MainWindow::openDropped(const QString& path) {
    switch (kindOfDropped(path)) {
        case DroppedKind::Experiment:
            return maySwitchExperiment() && openExperiment(path);
        case DroppedKind::Rig:
            return devicesPanel_->openRigFile(path);
        case DroppedKind::Recording:
            return analyseRecording(path);
        case DroppedKind::RunFolder:
            return replayRun(path);
        case DroppedKind::Unknown:
            break;
    }
    showError(tr("%1 is not a file the workbench opens: drop an experiment or rig file (.json), "
                 "a tap recording (.csv) or a run's folder.")
                  .arg(path));
    return false;
}

void MainWindow::dragEnterEvent(QDragEnterEvent* event) {
    const QList<QUrl> urls = event->mimeData()->urls();
    if (urls.size() == 1 && urls.front().isLocalFile() &&
        kindOfDropped(urls.front().toLocalFile()) != DroppedKind::Unknown)
        event->acceptProposedAction();
}

void MainWindow::dropEvent(QDropEvent* event) {
    const QList<QUrl> urls = event->mimeData()->urls();
    if (urls.size() != 1 || !urls.front().isLocalFile()) return;
    event->acceptProposedAction();
    const QString path = urls.front().toLocalFile();
    // After the drop has finished: opening may ask a question.
    QMetaObject::invokeMethod(
        this, [this, path] { openDropped(path); }, Qt::QueuedConnection);
}

// ---- layout and help ----

void MainWindow::fitToScreen() {
    const QScreen* screen = this->screen() ? this->screen() : QGuiApplication::primaryScreen();
    if (!screen) return;
    const QRect available = screen->availableGeometry();
    const QSize wanted(std::min(1600, available.width() * 9 / 10),
                       std::min(1000, available.height() * 9 / 10));
    resize(wanted.expandedTo(minimumSizeHint()).boundedTo(available.size()));
    move(available.center() - rect().center());
}

void MainWindow::resetLayout() {
    restoreState(defaultState_);
    for (QDockWidget* dock : findChildren<QDockWidget*>()) dock->show();
    runBar_->show();
    if (auto* scene = findChild<QDockWidget*>("sceneDock")) scene->raise();
    fitToScreen();
    log(tr("layout reset"));
}

void MainWindow::openDocumentation() {
    const QString docs = documentationDirectory();
    if (docs.isEmpty() || !QFileInfo::exists(QDir(docs).filePath("window.md"))) {
        showError(tr("The documentation is not installed beside the workbench (looked in %1); "
                     "reinstall it, or read docs/ in the source tree.")
                      .arg(docs.isEmpty() ? tr("its share folder") : docs));
        return;
    }
    if (!help_) help_ = new HelpBrowser(docs, this);
    // The section of docs/window.md about the tab in front: "- **Live**: ...".
    QString tab = tabs_->tabText(tabs_->currentIndex());
    tab.replace("&&", "\x01").remove('&').replace("\x01", "&");
    help_->showTopic("window.md", tab + ":");
}

void MainWindow::showAbout() {
    QMessageBox box(this);
    box.setObjectName("aboutDialog");
    box.setWindowTitle(tr("About ActiveTouch Workbench"));
    box.setIconPixmap(windowIcon().pixmap(64, 64));
    box.setTextFormat(Qt::RichText);
    box.setText(tr("<b>ActiveTouch Workbench %1</b><br>Active tactile perception experiments: "
                   "edge perception, contour following and shape recognition with a tapping "
                   "fingertip, on a simulated or real rig.")
                    .arg(QApplication::applicationVersion().toHtmlEscaped()));
    box.setInformativeText(tr("Qt %1 (built with %2), QCustomPlot %3")
                               .arg(qVersion(), QT_VERSION_STR, QCUSTOMPLOT_VERSION_STR));
    box.exec();
}

}  // namespace activetouch
