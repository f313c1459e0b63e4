// The protocol panel and its experiment: the document shown in the fields, and the fields written
// back as a patch of the document (ProtocolPanel.h).
#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QSignalBlocker>
#include <QSpinBox>
#include <QTableWidget>
#include <QVBoxLayout>
#include <cmath>
#include <map>

#include "app/gui/ProtocolPanel.h"
#include "app/gui/ScrolledColumn.h"
#include "core/classify/HistogramClassifier.h"

namespace activetouch {

void ProtocolPanel::showExperiment(const ExperimentSpec& e, const Json& document) {
    const QSignalBlocker block(this);
    for (const Field& f : fields_) {
        setValueOf(f, f.value(e));
    }
    QStringList sets, orientations;
    for (int s : e.training.trainingSets) sets << QString::number(s);
    trainingSets_->setText(sets.join(", "));
    for (double deg : e.classes.orientationsDeg) orientations << QString::number(deg, 'g', 12);
    orientations_->setText(orientations.join(", "));
    recognition_->setChecked(e.recognition.enabled);
    recognitionOf_->setCurrentIndex(e.recognition.ofMode == FollowingMode::Passive ? 1 : 0);
    trialEntries_.clear();
    if (document.contains("following") && document["following"].contains("trials"))
        for (const Json& t : document["following"]["trials"]) trialEntries_.push_back(t);
    trials_->setRowCount(0);
    for (int i = 0; i < int(e.trials.size()) && i < int(trialEntries_.size()); ++i) {
        const TrialSpec& t = e.trials[std::size_t(i)];
        QString what = QString::fromStdString(t.label);
        if (t.label != t.object.shape) what += " (" + QString::fromStdString(t.object.shape) + ")";
        addTrialRow(i, what, t.mode == FollowingMode::Passive, t.repeats);
    }
    trials_->setMinimumHeight(std::min(8, std::max(1, int(e.trials.size()))) *
                                  trials_->verticalHeader()->defaultSectionSize() +
                              trials_->horizontalHeader()->height() + 4);
}

void ProtocolPanel::addTrialRow(int row, const QString& what, bool passive, int repeats) {
    trials_->insertRow(row);
    trials_->setItem(row, 0, new QTableWidgetItem(what));
    auto* mode = new QComboBox;
    mode->addItems({"active", "passive"});
    mode->setCurrentIndex(passive ? 1 : 0);
    connect(mode, &QComboBox::currentIndexChanged, this, &ProtocolPanel::changed);
    trials_->setCellWidget(row, 1, mode);
    auto* count = new QSpinBox;
    count->setRange(1, 1000);
    count->setValue(repeats);
    connect(count, &QSpinBox::valueChanged, this, &ProtocolPanel::changed);
    trials_->setCellWidget(row, 2, count);
}

QComboBox* ProtocolPanel::modeBox(int row) const {
    return static_cast<QComboBox*>(trials_->cellWidget(row, 1));
}

QSpinBox* ProtocolPanel::repeatsBox(int row) const {
    return static_cast<QSpinBox*>(trials_->cellWidget(row, 2));
}

Json ProtocolPanel::patch(Json j) const {
    for (const Field& f : fields_) {
        if (f.section == "recognition" && !recognition_->isChecked()) continue;
        Json& at = f.section.empty() ? j : j[f.section];
        const double v = valueOf(f);
        if (f.kind == Kind::Flag)
            at[f.key] = v != 0.0;
        else if (f.kind == Kind::Integer)
            at[f.key] = static_cast<long long>(std::llround(v));
        else
            at[f.key] = v;
    }
    j["classes"]["orientations_deg"] =
        numberList(orientations_, tr("Training and validation: Edge orientations (deg)"),
                   "an angle in degrees", "90");
    j["training"]["training_sets"] = numberList(
        trainingSets_, tr("Training and validation: Training sets"), "a data set number", "1");
    if (recognition_->isChecked())
        j["recognition"]["of_mode"] = recognitionOf_->currentText().toStdString();
    else
        j.erase("recognition");
    if (!trialEntries_.empty() || (j.contains("following") && j["following"].contains("trials"))) {
        Json trials = Json::array();
        for (int i = 0; i < trials_->rowCount(); ++i) {
            Json t = trialEntries_[std::size_t(i)];
            t["mode"] = modeBox(i)->currentText().toStdString();
            t["repeats"] = repeatsBox(i)->value();
            trials.push_back(std::move(t));
        }
        j["following"]["trials"] = std::move(trials);
    }
    return j;
}

Json ProtocolPanel::numberList(const QLineEdit* edit, const QString& field, const char* what,
                               const char* example) const {
    Json list = Json::array();
    for (const QString& part : edit->text().split(',', Qt::SkipEmptyParts)) {
        bool ok = false;
        const double v = part.trimmed().toDouble(&ok);
        if (!ok || !std::isfinite(v))
            throw InputError("protocol panel", field.toStdString(),
                             "'" + part.trimmed().toStdString() + "' is not " + what +
                                 "; list numbers separated by commas, such as " + example);
        if (v == std::floor(v) && std::abs(v) < 1e9)
            list.push_back(static_cast<long long>(v));
        else
            list.push_back(v);
    }
    if (list.empty())
        throw InputError("protocol panel", field.toStdString(),
                         std::string("the list is empty; give at least one, such as ") + example);
    return list;
}

QString ProtocolPanel::fieldAt(const std::string& pointer) const {
    for (const Field& f : fields_) {
        const std::string place = (f.section.empty() ? "" : "/" + f.section) + "/" + f.key;
        if (pointer == place) return f.group + ": " + f.label;
    }
    if (pointer == "/training/training_sets") return tr("Training and validation: Training sets");
    if (pointer.rfind("/classes/orientations_deg", 0) == 0)
        return tr("Training and validation: Edge orientations (deg)");
    if (pointer.rfind("/training", 0) == 0) return tr("Training and validation");
    if (pointer == "/recognition/of_mode") return tr("Recognition: Of the trials");
    if (pointer.rfind("/recognition", 0) == 0) return tr("Recognition");
    const std::string trials = "/following/trials/";
    if (pointer.rfind(trials, 0) == 0) {
        const int row = std::atoi(pointer.c_str() + trials.size());
        if (row >= 0 && row < trials_->rowCount() && trials_->item(row, 0))
            return tr("Trials: %1 (row %2)").arg(trials_->item(row, 0)->text()).arg(row + 1);
        return tr("Trials");
    }
    if (pointer.rfind("/following", 0) == 0) return tr("Following");
    return {};
}

}  // namespace activetouch
