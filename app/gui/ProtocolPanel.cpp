#include "app/gui/ProtocolPanel.h"

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

#include "app/gui/ScrolledColumn.h"
#include "core/classify/HistogramClassifier.h"

namespace activetouch {
namespace {

/// A number box that shows a value as written (2, 0.01, 0.99999999) and keeps it exactly: the
/// experiment's values must not be rounded to a spin box's decimals on their way to a run.
class NumberBox : public QDoubleSpinBox {
public:
    NumberBox(double lo, double hi, double step) {
        setDecimals(12);
        setRange(lo, hi);
        setSingleStep(step);
    }
    QString textFromValue(double v) const override { return QString::number(v, 'g', 12); }
    double valueFromText(const QString& text) const override { return text.trimmed().toDouble(); }
    QValidator::State validate(QString& input, int&) const override {
        const QString t = input.trimmed();
        if (t.isEmpty() || t == "-" || t == "." || t == "-." || t.endsWith('e') ||
            t.endsWith('E') || t.endsWith("e-") || t.endsWith("E-"))
            return QValidator::Intermediate;
        bool ok = false;
        const double v = t.toDouble(&ok);
        if (!ok) return QValidator::Invalid;
        return v >= minimum() && v <= maximum() ? QValidator::Acceptable : QValidator::Intermediate;
    }
};

}  // namespace

ProtocolPanel::ProtocolPanel(QWidget* parent) : QWidget(parent) {
    QVBoxLayout* layout = scrolledColumn(this);

    auto* note = new QLabel(
        tr("The experiment's settings beside its scene. Runs, seeds, analysis and replay use "
           "what is shown here; Save as writes it."));
    note->setWordWrap(true);
    layout->addWidget(note);

    addRunFields(layout);
    addClassifierFields(layout);
    addTrainingFields(layout);
    addFollowingFields(layout);
    addTrialsTable(layout);
    addRecognitionFields(layout);

    auto* reset = new QPushButton(tr("Show the file's values"));
    reset->setObjectName("protocol_reset");
    reset->setToolTip(tr("Show the experiment file's settings again, as opened"));
    connect(reset, &QPushButton::clicked, this, &ProtocolPanel::resetRequested);
    layout->addWidget(reset);
    layout->addStretch();
}

QGroupBox* ProtocolPanel::addGroup(QVBoxLayout* layout, const QString& title) {
    auto* box = new QGroupBox(title);
    new QFormLayout(box);
    layout->addWidget(box);
    return box;
}

void ProtocolPanel::addRunFields(QVBoxLayout* layout) {
    using E = const ExperimentSpec&;
    const QString run = tr("Run");
    auto* runBox = addGroup(layout, run);
    addField(runBox, {"", "seed", run, tr("Seed"),
                      tr("The run's seed: its data sets, noise and trials. The Rates over seeds "
                         "tab runs a range of seeds."),
                      Kind::Integer, 0, 2147483647, 1, [](E e) { return double(e.scene.seed); }});
}

void ProtocolPanel::addClassifierFields(QVBoxLayout* layout) {
    using E = const ExperimentSpec&;
    const QString classifier = tr("Classifier");
    auto* classifierBox = addGroup(layout, classifier);
    addField(classifierBox,
             {"classifier", "bins", classifier, tr("Histogram bins"),
              tr("Bins per taxel over its trained range (paper: 100)"), Kind::Integer, 1, 100000,
              10, [](E e) { return double(e.classifier.bins); }});
    addField(classifierBox,
             {"classifier", "smoothing", classifier, tr("Smoothing"),
              tr("Count added to every bin of a likelihood histogram (chosen by the validation: "
                 "0.01)"),
              Kind::Number, 1e-12, 1e6, 0.01, [](E e) { return e.classifier.smoothing; }});
    addField(classifierBox,
             {"classifier", "kernel_sigma_bins", classifier, tr("Kernel width (bins)"),
              tr("0: the paper's histogram; above 0 each training count is spread over its "
                 "neighbouring bins by a Gaussian this wide"),
              Kind::Number, 0.0, kMaxKernelSigma_bins, 0.5,
              [](E e) { return e.classifier.kernelSigma_bins; }});
}

void ProtocolPanel::addTrainingFields(QVBoxLayout* layout) {
    using E = const ExperimentSpec&;
    const QString training = tr("Training and validation");
    auto* trainingBox = addGroup(layout, training);
    orientations_ = new QLineEdit;
    orientations_->setObjectName("protocol_classes_orientations_deg");
    orientations_->setToolTip(
        tr("The edge orientations the classifier knows: outward normals in degrees (lower 270, "
           "right 0, upper 90, left 180), separated by commas. The scene's object needs an edge "
           "facing each to train on: eight, every 45 deg, train on an octagon"));
    static_cast<QFormLayout*>(trainingBox->layout())
        ->addRow(tr("Edge orientations (deg)"), orientations_);
    connect(orientations_, &QLineEdit::editingFinished, this, &ProtocolPanel::changed);
    addField(trainingBox,
             {"classes", "positions", training, tr("Positions across an edge"),
              tr("Classes per orientation, from plane to air (paper: 18)"), Kind::Integer, 2, 200,
              1, [](E e) { return double(e.classes.positions); }});
    addField(trainingBox, {"classes", "position_step_mm", training, tr("Position step (mm)"),
                           tr("Between neighbouring positions (paper: 1)"), Kind::Number, 0.05,
                           10.0, 0.5, [](E e) { return e.classes.positionStep_mm; }});
    addField(trainingBox, {"training", "data_sets", training, tr("Data sets"),
                           tr("Taps at every class, once per data set (paper: 5)"), Kind::Integer,
                           2, 1000, 1, [](E e) { return double(e.training.dataSets); }});
    trainingSets_ = new QLineEdit;
    trainingSets_->setObjectName("protocol_training_training_sets");
    trainingSets_->setToolTip(
        tr("The data sets that train, numbered from 1, separated by commas; the others test "
           "(paper: 1)"));
    static_cast<QFormLayout*>(trainingBox->layout())->addRow(tr("Training sets"), trainingSets_);
    connect(trainingSets_, &QLineEdit::editingFinished, this, &ProtocolPanel::changed);
    addField(trainingBox, {"training", "taps_per_class", training, tr("Taps per class"),
                           tr("Taps at each class in each data set (paper: 1)"), Kind::Integer, 1,
                           1000, 1, [](E e) { return double(e.training.tapsPerClass); }});
    addField(trainingBox,
             {"training", "test_offset_mm", training, tr("Test sets off the grid (mm)"),
              tr("Test taps shifted along the edge normal, off the training grid"), Kind::Number,
              -5.0, 5.0, 0.1, [](E e) { return e.training.testOffset_mm; }});
    addField(trainingBox,
             {"training", "placement_jitter_mm", training, tr("Placement jitter (mm)"),
              tr("Standard deviation of each data set's object displacement, per axis"),
              Kind::Number, 0.0, 5.0, 0.1, [](E e) { return e.training.placementJitter_mm; }});
    addField(trainingBox,
             {"training", "retrain_on_all_sets", training, tr("Follow trained on every set"),
              tr("After the validation, train the classifier the trials follow with again on "
                 "every data set"),
              Kind::Flag, 0, 1, 1, [](E e) { return e.training.retrainOnAllSets ? 1.0 : 0.0; }});
    addField(trainingBox,
             {"validation", "valid_range_positions", training, tr("Valid range (positions)"),
              tr("Width of the window of positions the validation picks as the valid range "
                 "(paper: 4)"),
              Kind::Integer, 1, 200, 1, [](E e) { return double(e.validRangeWidth); }});
}

namespace {

/// A following number's label, tooltip and spin-box step.
struct Step {
    QString label, tip;
    double step;
};

/// The following section's numbers (followingNumbers gives them with their ranges), labelled.
std::map<std::string, Step> followingSteps() {
    return {
        {"follow_step_mm",
         {ProtocolPanel::tr("Follow step (mm)"),
          ProtocolPanel::tr("Along the perceived edge, every tap (paper: 2)"), 0.5}},
        {"reposition_step_mm",
         {ProtocolPanel::tr("Reposition step (mm)"),
          ProtocolPanel::tr("Active: along the edge normal toward the valid range (paper: 1)"),
          0.5}},
        {"plane_step_mm",
         {ProtocolPanel::tr("Plane: outward (mm)"),
          ProtocolPanel::tr("Active, plane percept: outward along the last edge's normal"), 0.5}},
        {"plane_retreat_step_mm",
         {ProtocolPanel::tr("Plane: back (mm)"),
          ProtocolPanel::tr("Active, plane percept: back against the heading"), 0.5}},
        {"air_inward_step_mm",
         {ProtocolPanel::tr("Air: inward (mm)"),
          ProtocolPanel::tr("Active, air percept: inward along the last edge's normal"), 0.5}},
        {"air_retreat_step_mm",
         {ProtocolPanel::tr("Air: back (mm)"),
          ProtocolPanel::tr("Active, air percept: back against the heading"), 0.5}},
        {"orientation_trust_max_error_deg",
         {ProtocolPanel::tr("Orientation trusted up to (deg)"),
          ProtocolPanel::tr(
              "Active: use a percept's orientation only at positions whose mean validation angle "
              "error is at most this; 180 trusts every edge percept, as the paper does"),
          5.0}},
        {"belief_threshold",
         {ProtocolPanel::tr("Belief threshold"),
          ProtocolPanel::tr(
              "Sequential perception: 0 decides from each tap alone (the paper); a value in (0, "
              "1) taps again in place until the belief reaches it"),
          0.01}},
        {"completion_radius_mm",
         {ProtocolPanel::tr("Completed within (mm)"),
          ProtocolPanel::tr("Completed: back within this of the start after a full perimeter"),
          0.5}},
        {"lost_outside_mm",
         {ProtocolPanel::tr("Lost outside (mm)"),
          ProtocolPanel::tr("Lost when this far outside the contour"), 1.0}},
        {"lost_inside_mm",
         {ProtocolPanel::tr("Lost inside (mm)"),
          ProtocolPanel::tr("Lost when this far inside the object"), 1.0}},
        {"tap_cap_perimeters",
         {ProtocolPanel::tr("Tap cap (perimeters)"),
          ProtocolPanel::tr("A trial ends after this many perimeters' worth of follow steps"),
          0.5}},
        {"coverage_radius_mm",
         {ProtocolPanel::tr("Coverage radius (mm)"),
          ProtocolPanel::tr("A point of the contour is covered by a tap this close"), 0.5}},
        {"percept_temperature",
         {ProtocolPanel::tr("Percept temperature"),
          ProtocolPanel::tr(
              "Continuous percept: log-likelihoods are divided by this before the posterior is "
              "formed; 0 takes the tap's samples per taxel"),
          1.0}},
        {"same_edge_tolerance_deg",
         {ProtocolPanel::tr("Same edge within (deg)"),
          ProtocolPanel::tr(
              "Continuous percept: edge angles this close count as the same edge when confirming "
              "it"),
          1.0}},
    };
}

}  // namespace

void ProtocolPanel::addFollowingFields(QVBoxLayout* layout) {
    using E = const ExperimentSpec&;
    const QString following = tr("Following");
    auto* followingBox = addGroup(layout, following);
    const std::map<std::string, Step> steps = followingSteps();
    for (const FollowingNumber& n : followingNumbers()) {
        const auto it = steps.find(n.key);
        const Step s = it != steps.end() ? it->second : Step{QString(n.key), QString(), 1.0};
        const auto member = n.member;
        addField(followingBox, {"following", n.key, following, s.label, s.tip, Kind::Number, n.lo,
                                n.hi, s.step, [member](E e) { return e.following.*member; }});
    }
    addField(
        followingBox,
        {"following", "edge_confirmation_taps", following, tr("Edge confirmed after (taps)"),
         tr("Active: same-orientation edge percepts in a row before memory takes the edge "
            "as the last edge"),
         Kind::Integer, 1, 100, 1, [](E e) { return double(e.following.edgeConfirmationTaps); }});
    addField(followingBox,
             {"following", "curvature_taps", following, tr("Curvature from (taps)"),
              tr("Continuous percept: the contour's turn per mm is estimated from this many recent "
                 "edge angles and anticipated over half a step (0: none)"),
              Kind::Integer, 0, 50, 1, [](E e) { return double(e.following.curvatureTaps); }});
    addField(followingBox,
             {"following", "max_taps_per_decision", following, tr("Taps per decision at most"),
              tr("Sequential perception: taps gathered before deciding anyway"), Kind::Integer, 1,
              1000, 1, [](E e) { return double(e.following.maxTapsPerDecision); }});
    addField(
        followingBox,
        {"following", "reposition_while_sensing", following, tr("Reposition while sensing"),
         tr("Sequential perception, active: move toward the valid range between taps"), Kind::Flag,
         0, 1, 1, [](E e) { return e.following.repositionWhileSensing ? 1.0 : 0.0; }});
    addField(followingBox,
             {"following", "lost_plane_or_air_taps", following, tr("Lost after plane/air taps"),
              tr("Lost after this many plane or air decisions in a row"), Kind::Integer, 1, 100000,
              1, [](E e) { return double(e.following.lostPlaneOrAirTaps); }});
}

void ProtocolPanel::addTrialsTable(QVBoxLayout* layout) {
    auto* trialsBox = new QGroupBox(tr("Trials"));
    auto* trialsLayout = new QVBoxLayout(trialsBox);
    trials_ = new QTableWidget(0, 3);
    trials_->setObjectName("protocol_trials");
    trials_->setHorizontalHeaderLabels({tr("trial"), tr("mode"), tr("repeats")});
    trials_->horizontalHeader()->setSectionResizeMode(0, QHeaderView::Stretch);
    trials_->verticalHeader()->setVisible(false);
    trials_->setEditTriggers(QAbstractItemView::NoEditTriggers);
    trials_->setSelectionBehavior(QAbstractItemView::SelectRows);
    trials_->setSelectionMode(QAbstractItemView::SingleSelection);
    trials_->setToolTip(
        tr("Each trial's object is the experiment file's; its mode and repeats can be changed "
           "here, and a trial copied (say, to follow the same object passively too) or removed"));
    trialsLayout->addWidget(trials_);
    auto* trialButtons = new QHBoxLayout;
    auto* copyTrial = new QPushButton(tr("Copy trial"));
    copyTrial->setObjectName("protocol_copy_trial");
    copyTrial->setToolTip(
        tr("Add a copy of the selected trial below it: the same object, mode "
           "and repeats"));
    auto* removeTrial = new QPushButton(tr("Remove trial"));
    removeTrial->setObjectName("protocol_remove_trial");
    trialButtons->addWidget(copyTrial);
    trialButtons->addWidget(removeTrial);
    trialButtons->addStretch();
    trialsLayout->addLayout(trialButtons);
    layout->addWidget(trialsBox);
    auto enableTrialButtons = [this, copyTrial, removeTrial] {
        const bool selected = trials_->currentRow() >= 0 && !trials_->selectedItems().isEmpty();
        copyTrial->setEnabled(selected);
        removeTrial->setEnabled(selected);
    };
    connect(trials_, &QTableWidget::itemSelectionChanged, this, enableTrialButtons);
    enableTrialButtons();
    connect(copyTrial, &QPushButton::clicked, this, [this] {
        const int row = trials_->currentRow();
        if (row < 0) return;
        trialEntries_.insert(trialEntries_.begin() + row + 1, trialEntries_[std::size_t(row)]);
        addTrialRow(row + 1, trials_->item(row, 0)->text(), modeBox(row)->currentIndex() == 1,
                    repeatsBox(row)->value());
        trials_->selectRow(row + 1);
        emit changed();
    });
    connect(removeTrial, &QPushButton::clicked, this, [this] {
        const int row = trials_->currentRow();
        if (row < 0) return;
        trialEntries_.erase(trialEntries_.begin() + row);
        trials_->removeRow(row);
        emit changed();
    });
}

void ProtocolPanel::addRecognitionFields(QVBoxLayout* layout) {
    using E = const ExperimentSpec&;
    recognition_ = new QGroupBox(tr("Recognition"));
    recognition_->setObjectName("protocol_recognition");
    recognition_->setCheckable(true);
    recognition_->setToolTip(tr("Recognise the shapes from the traced paths (paper §3.4)"));
    new QFormLayout(recognition_);
    layout->addWidget(recognition_);
    const QString recognition = tr("Recognition");
    addField(recognition_,
             {"recognition", "bins", recognition, tr("Histogram bins"),
              tr("Bins along each axis of the path histogram (paper: 20)"), Kind::Integer, 2, 200,
              1, [](E e) { return double(e.recognition.bins); }});
    addField(recognition_,
             {"recognition", "smoothing_sigma_bins", recognition, tr("Smoothed rule (bins)"),
              tr("Width of the Gaussian that blurs the histograms for the rule reported beside "
                 "the paper's"),
              Kind::Number, 0.0, 20.0, 0.5, [](E e) { return e.recognition.smoothingSigmaBins; }});
    recognitionOf_ = new QComboBox;
    recognitionOf_->setObjectName("protocol_recognition_of_mode");
    recognitionOf_->addItems({"active", "passive"});
    recognitionOf_->setToolTip(tr("Which trials' paths are recognised"));
    static_cast<QFormLayout*>(recognition_->layout())->addRow(tr("Of the trials"), recognitionOf_);
    connect(recognition_, &QGroupBox::toggled, this, &ProtocolPanel::changed);
    connect(recognitionOf_, &QComboBox::currentIndexChanged, this, &ProtocolPanel::changed);
}

void ProtocolPanel::addField(QGroupBox* box, Field f) {
    QWidget* w = nullptr;
    if (f.kind == Kind::Flag) {
        auto* c = new QCheckBox;
        connect(c, &QCheckBox::toggled, this, &ProtocolPanel::changed);
        w = c;
    } else if (f.kind == Kind::Integer) {
        auto* s = new QSpinBox;
        s->setRange(int(f.lo), int(f.hi));
        s->setSingleStep(int(f.step));
        connect(s, &QSpinBox::valueChanged, this, &ProtocolPanel::changed);
        w = s;
    } else {
        auto* s = new NumberBox(f.lo, f.hi, f.step);
        connect(s, &QDoubleSpinBox::valueChanged, this, &ProtocolPanel::changed);
        w = s;
    }
    w->setObjectName(
        QString::fromStdString("protocol_" + (f.section.empty() ? "" : f.section + "_") + f.key));
    w->setToolTip(f.tip);
    static_cast<QFormLayout*>(box->layout())->addRow(f.label, w);
    f.widget = w;
    fields_.push_back(std::move(f));
}

double ProtocolPanel::valueOf(const Field& f) const {
    if (f.kind == Kind::Flag) return static_cast<QCheckBox*>(f.widget)->isChecked() ? 1.0 : 0.0;
    if (f.kind == Kind::Integer) return static_cast<QSpinBox*>(f.widget)->value();
    return static_cast<QDoubleSpinBox*>(f.widget)->value();
}

bool ProtocolPanel::setField(const std::string& section, const std::string& key, double value) {
    for (const Field& f : fields_)
        if (f.section == section && f.key == key) {
            setValueOf(f, value);
            return true;
        }
    return false;
}

void ProtocolPanel::setValueOf(const Field& f, double v) {
    if (f.kind == Kind::Flag)
        static_cast<QCheckBox*>(f.widget)->setChecked(v != 0.0);
    else if (f.kind == Kind::Integer)
        static_cast<QSpinBox*>(f.widget)->setValue(int(v));
    else
        static_cast<QDoubleSpinBox*>(f.widget)->setValue(v);
}

}  // namespace activetouch
