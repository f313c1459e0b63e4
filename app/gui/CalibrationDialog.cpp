#include "app/gui/CalibrationDialog.h"

#include <QCoreApplication>
#include <QDialogButtonBox>
#include <QFileDialog>
#include <QHeaderView>
#include <QLabel>
#include <QPointer>
#include <QPushButton>
#include <QTableWidget>
#include <QVBoxLayout>

#include "app/figures/CalibrationFigures.h"
#include "app/gui/PlotTheme.h"
#include "app/gui/WholeFile.h"
#include "core/records/TapCsv.h"
#include "qcustomplot.h"

namespace activetouch {

namespace {

QTableWidget* table(const QStringList& headers, const QString& name) {
    auto* t = new QTableWidget(0, static_cast<int>(headers.size()));
    t->setObjectName(name);
    t->setHorizontalHeaderLabels(headers);
    t->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
    t->horizontalHeader()->setStretchLastSection(true);
    t->verticalHeader()->hide();
    t->setEditTriggers(QAbstractItemView::NoEditTriggers);
    return t;
}

void addRow(QTableWidget* t, const QStringList& cells) {
    const int row = t->rowCount();
    t->insertRow(row);
    for (int c = 0; c < cells.size(); ++c) t->setItem(row, c, new QTableWidgetItem(cells[c]));
}

}  // namespace

CalibrationDialog::CalibrationDialog(const ExperimentSpec& spec, const QString& recording,
                                     QWidget* parent)
    : QDialog(parent), spec_(spec), recording_(recording) {
    setObjectName("calibrationDialog");
    setWindowTitle(tr("Calibrate: %1").arg(recording));
    auto* layout = new QVBoxLayout(this);
    status_ = new QLabel(
        tr("Fitting %1 to the taps in %2: simulating the recording at its "
           "poses, then 20 more for the uncertainties (about 20 s)...")
            .arg(QString::fromStdString(spec.scene.source.empty() ? std::string("the scene")
                                                                  : spec.scene.source),
                 recording));
    status_->setObjectName("calibrationStatus");
    status_->setWordWrap(true);
    layout->addWidget(status_);
    estimates_ = table({tr("effect"), tr("parameter"), tr("estimate"), tr("95 % interval")},
                       "calibrationEstimates");
    choices_ = table({tr("effect"), tr("listed"), tr("statistic"), tr("threshold"), tr("test")},
                     "calibrationChoices");
    taxels_ = table(
        {tr("taxel"), tr("KS distance"), tr("match at most"), tr("Wasserstein"), tr("matches")},
        "calibrationTaxels");
    plot_ = new QCustomPlot;
    plot_->setObjectName("calibrationPlot");
    plot_->setMinimumHeight(300);
    connect(plot_, &QCustomPlot::afterLayout, this,
            [this] { setDarkInk(*plot_, isDarkPalette(palette())); });
    auto* tables = new QHBoxLayout;
    auto* left = new QVBoxLayout;
    left->addWidget(new QLabel(tr("Which effects the taps call for (level 0.001)")));
    left->addWidget(choices_);
    left->addWidget(new QLabel(tr("Estimates")));
    left->addWidget(estimates_);
    auto* right = new QVBoxLayout;
    right->addWidget(new QLabel(tr("Each taxel's readings, recorded against the fitted scene")));
    right->addWidget(taxels_);
    tables->addLayout(left, 3);
    tables->addLayout(right, 2);
    layout->addLayout(tables, 1);
    layout->addWidget(plot_, 1);
    auto* buttons = new QDialogButtonBox(QDialogButtonBox::Close);
    save_ = buttons->addButton(tr("Save fitted scene..."), QDialogButtonBox::ActionRole);
    save_->setObjectName("saveFittedScene");
    save_->setEnabled(false);
    connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
    connect(save_, &QPushButton::clicked, this, [this] {
        const QString path = QFileDialog::getSaveFileName(
            this, tr("Save the fitted scene"),
            QFileInfo(recording_).dir().filePath("fitted_scene.json"), tr("Scenes (*.json)"));
        if (path.isEmpty()) return;
        const QString problem = saveFittedScene(path);
        status_->setText(problem.isEmpty() ? tr("Saved the fitted scene to %1.").arg(path)
                                           : tr("Could not save %1: %2").arg(path, problem));
    });
    layout->addWidget(buttons);
    resize(1200, 860);
    startFit();
}

void CalibrationDialog::startFit() {
    // The fit runs off the window's thread on its own copies; a dialog closed meanwhile is not
    // told.
    const QPointer<CalibrationDialog> self(this);
    worker_ = std::thread([self, spec = spec_, path = recording_.toStdString()] {
        std::shared_ptr<SceneFit> fit;
        QString problem;
        Figure6Comparison figure6;
        try {
            std::string cut;
            const auto taps = readTapCsv(path, spec.classes, &cut);
            std::vector<TapRecord> records;
            for (const auto& t : taps) records.push_back(t.record);
            fit = std::make_shared<SceneFit>(fitScene(spec.scene, records));
            figure6 = compareFigure6(spec, taps, *fit);
        } catch (const std::exception& e) {
            problem = QString::fromUtf8(e.what());
            fit.reset();
        }
        auto shared = std::make_shared<Figure6Comparison>(std::move(figure6));
        QMetaObject::invokeMethod(qApp, [self, fit, shared, problem] {
            if (self) self->showFit(fit, shared, problem);
        });
    });
    worker_.detach();
}

CalibrationDialog::~CalibrationDialog() = default;

void CalibrationDialog::showFit(std::shared_ptr<SceneFit> fit,
                                std::shared_ptr<Figure6Comparison> figure6,
                                const QString& problem) {
    done_ = true;
    if (!fit) {
        status_->setText(tr("Could not fit %1:\n%2").arg(recording_, problem));
        emit fitFinished(false);
        return;
    }
    fit_ = std::move(fit);
    for (const auto& c : fit_->choices)
        addRow(choices_, {QString::fromStdString(c.effect),
                          c.estimated ? (c.listed ? tr("yes") : tr("no")) : tr("kept"),
                          c.estimated ? QString::number(c.statistic, 'g', 3) : QString(),
                          c.estimated ? QString::number(c.threshold, 'g', 3) : QString(),
                          QString::fromStdString(c.test)});
    for (const auto& p : fit_->parameters)
        addRow(estimates_,
               {QString::fromStdString(p.effect), QString::fromStdString(p.parameter),
                QString::number(p.value, 'g', 4),
                QString("%1 to %2")
                    .arg(QString::number(p.low, 'g', 4), QString::number(p.high, 'g', 4))});
    if (!fit_->deadTaxels.empty()) {
        QStringList dead;
        for (int k : fit_->deadTaxels) dead << QString::number(k);
        addRow(estimates_,
               {"dead_taxel", "taxels", dead.join(", "), tr("reading %1").arg(fit_->deadReading)});
    }
    addRow(estimates_, {tr("(pressure level)"), tr("against the scene's"),
                        QString::number(fit_->pressureScale, 'g', 4),
                        QString("%1 to %2")
                            .arg(QString::number(fit_->pressureScaleLow, 'g', 4),
                                 QString::number(fit_->pressureScaleHigh, 'g', 4))});
    int matching = 0;
    for (const auto& t : fit_->taxels) {
        addRow(taxels_, {QString::number(t.taxel), QString::number(t.ks, 'f', 3),
                         QString::number(t.ksMatch, 'f', 3), QString::number(t.wasserstein, 'f', 3),
                         t.matches ? tr("yes") : tr("no")});
        matching += t.matches;
    }
    buildCalibrationFigure(*plot_, *fit_, *figure6);
    plot_->replot();
    status_->setText(
        tr("Fitted to %1 taps (%2 samples over nothing). %3 of %4 taxels match the fitted scene. "
           "Figure 6 recorded: angle %5 deg, position %6 mm; simulated with the fitted scene "
           "(mean of %7 recordings): angle %8 deg, position %9 mm.")
            .arg(fit_->taps)
            .arg(fit_->nothingSamples)
            .arg(matching)
            .arg(fit_->taxels.size())
            .arg(figure6->recorded.angleError_deg, 0, 'f', 1)
            .arg(figure6->recorded.positionError_mm, 0, 'f', 2)
            .arg(figure6->simulated.size())
            .arg(figure6->angleMean, 0, 'f', 1)
            .arg(figure6->positionMean, 0, 'f', 2));
    save_->setEnabled(true);
    emit fitFinished(true);
}

QString CalibrationDialog::saveFittedScene(const QString& path) {
    if (!fit_) return tr("nothing is fitted yet");
    SceneSpec written = fit_->fitted;
    written.description = "Fitted by the window's Calibrate to " + recording_.toStdString() + " (" +
                          std::to_string(fit_->taps) + " taps).";
    return writeFileWhole(path, QByteArray::fromStdString(sceneToJson(written).dump(2) + "\n"));
}

}  // namespace activetouch
