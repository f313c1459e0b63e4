#pragma once
// The scene panel (docs/window.md): the training object (library shape or polygon file), its pose,
// and every effect of the simulated rig as a toggle with its parameters. A run uses exactly what
// the panel shows.
#include <QWidget>
#include <map>

#include "core/scene/Scene.h"

class QComboBox;
class QDoubleSpinBox;
class QGroupBox;
class QLineEdit;
class QLabel;

namespace activetouch {

class ScenePanel : public QWidget {
    Q_OBJECT
public:
    explicit ScenePanel(QWidget* parent = nullptr);

    /// Shows `scene` (object and effects).
    void showScene(const SceneSpec& scene);
    /// The scene as shown: `base` with the panel's object and effects. Throws InputError naming
    /// the panel's field if what is shown is not a valid scene.
    SceneSpec sceneFromPanel(const SceneSpec& base) const;

    /// Loads the object's outline from `path` (core/scene/OutlineFile.h: a JSON polygon, object or
    /// scene, an SVG drawing, or an STL or OBJ mesh in `meshUnits`, whose height becomes the top
    /// height) and shows it as a polygon. On bad input emits failed() with the file and the
    /// problem, keeps what was shown and returns false.
    bool loadOutlineFrom(const QString& path, const QString& meshUnits = {});
    bool loadPolygonFrom(const QString& path) { return loadOutlineFrom(path); }
    /// What the panel says of the shown object's features the fingertip cannot resolve
    /// (core/experiment/ReachCautions.h); empty when it can resolve all of them.
    QString reachNote() const;
    /// The polygon last loaded (empty before any).
    const std::vector<Vec2>& polygon() const { return polygon_; }

signals:
    void changed();
    void failed(const QString& message);
    /// Something worth a line in the log (what an outline file holds beside the outline).
    void noted(const QString& message);

private:
    QGroupBox* buildObjectBox();
    QGroupBox* buildEffectsBox();
    void loadPolygon();
    void updateReach();
    SceneSpec base_;
    double contactRadius_mm_ = 0.0;
    QLabel* reachLabel_;
    QComboBox* shape_;
    QDoubleSpinBox *width_, *height_, *arm_, *opening_, *x_, *y_, *rotation_, *top_;
    QLabel* polygonLabel_;
    std::vector<Vec2> polygon_;
    struct EffectWidgets {
        QGroupBox* box;
        std::map<std::string, QDoubleSpinBox*> parameters;
        QLineEdit* taxels = nullptr;
        /// A scene's measured gains (taxel_gain's "gains", as calibrate writes them): kept as
        /// they are, in place of the spread the panel edits.
        std::vector<double> gains;
    };
    std::map<std::string, EffectWidgets> effects_;
};

}  // namespace activetouch
