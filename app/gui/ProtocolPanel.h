#pragma once
// The protocol panel: the experiment's settings beside its scene. The classifier, the training
// protocol, the valid range's width, every step and limit of the perception-action loop, the
// recognition rule, the seed, and each trial's mode and repeats — the values the experiment runs
// with, defaults included. A run uses what the panel shows: the window writes the panel's values
// into the experiment's document and reads it with the same checks as a file, so a setting the
// file would refuse is refused naming the panel's field, and nothing runs.
#include <QString>
#include <QWidget>
#include <functional>
#include <vector>

#include "core/experiment/Experiment.h"
#include "core/io/JsonFields.h"

class QCheckBox;
class QComboBox;
class QGroupBox;
class QVBoxLayout;
class QLineEdit;
class QSpinBox;
class QTableWidget;

namespace activetouch {

class ProtocolPanel : public QWidget {
    Q_OBJECT
public:
    explicit ProtocolPanel(QWidget* parent = nullptr);

    /// Shows the settings `experiment` runs with; `document` is its file's JSON ("extends"
    /// resolved), whose trials the panel's trial rows copy or remove whole.
    void showExperiment(const ExperimentSpec& experiment, const Json& document);
    /// `document` (an experiment file's JSON, "extends" resolved) with the panel's values written
    /// in; keys the panel does not show are kept as they are. Throws InputError naming the field
    /// for a value that is not a number or a list of set numbers.
    Json patch(Json document) const;
    /// "Group: label" of the field at a JSON pointer the panel writes (or an enclosing one), for
    /// messages; empty for a place the panel does not show.
    QString fieldAt(const std::string& pointer) const;
    /// Shows `value` in the field that writes `key` of `section` (as a person typing it would,
    /// so the experiment reads as modified); false if the panel has no such field.
    bool setField(const std::string& section, const std::string& key, double value);

signals:
    void changed();
    /// The person asked to show the experiment's own values again.
    void resetRequested();

private:
    enum class Kind { Number, Integer, Flag };
    struct Field {
        std::string section;  ///< top-level key ("" for the document itself)
        std::string key;
        QString group, label, tip;
        Kind kind;
        double lo, hi, step;
        std::function<double(const ExperimentSpec&)> value;
        QWidget* widget = nullptr;
    };
    void addField(QGroupBox* box, Field field);
    // The constructor's parts, a group of fields each, in the order shown.
    QGroupBox* addGroup(QVBoxLayout* layout, const QString& title);
    void addRunFields(QVBoxLayout* layout);
    void addClassifierFields(QVBoxLayout* layout);
    void addTrainingFields(QVBoxLayout* layout);
    void addFollowingFields(QVBoxLayout* layout);
    void addTrialsTable(QVBoxLayout* layout);
    void addRecognitionFields(QVBoxLayout* layout);
    void addTrialRow(int row, const QString& what, bool passive, int repeats);
    QComboBox* modeBox(int row) const;
    QSpinBox* repeatsBox(int row) const;
    double valueOf(const Field& f) const;
    /// The comma-separated numbers in `edit`; throws InputError naming `field` for one that is
    /// not `what` (a number) or for an empty list.
    Json numberList(const QLineEdit* edit, const QString& field, const char* what,
                    const char* example) const;
    void setValueOf(const Field& f, double v);

    std::vector<Field> fields_;
    QLineEdit *trainingSets_, *orientations_;
    QGroupBox* recognition_;
    QComboBox* recognitionOf_;
    QTableWidget* trials_;
    std::vector<Json> trialEntries_;  ///< the document's trial objects, one per row
};

}  // namespace activetouch
