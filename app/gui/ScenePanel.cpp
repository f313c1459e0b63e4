#include "app/gui/ScenePanel.h"

#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QGroupBox>
#include <QInputDialog>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QVBoxLayout>

#include "app/gui/ScrolledColumn.h"
#include "core/experiment/ReachCautions.h"
#include "core/geometry/ShapeLibrary.h"
#include "core/scene/OutlineFile.h"
#include "devices/simulated/effects/Effect.h"

namespace activetouch {

namespace {
/// A scene file's key as a person reads it: "sigma_mm" -> "σ (mm)", "rate_counts_per_sqrt_s" ->
/// "Rate (counts/√s)", "taxel_noise" -> "Taxel noise".
QString humanLabel(const std::string& key) {
    QStringList words = QString::fromStdString(key).split('_', Qt::SkipEmptyParts);
    static const QStringList units{"mm", "deg", "counts", "s", "ms", "hz", "bins"};
    auto unitText = [](const QString& u) {
        return u == "deg" ? QString("°") : u == "hz" ? QString("Hz") : u;
    };
    QString unit;
    // "<unit> per [sqrt] <unit>", then a lone trailing unit.
    for (int i = 0; i + 2 < words.size(); ++i)
        if (units.contains(words[i]) && words[i + 1] == "per") {
            QString below = words.mid(i + 2).join(' ');
            below.replace("sqrt ", "√");
            unit = unitText(words[i]) + "/" + unitText(below);
            words = words.mid(0, i);
            break;
        }
    if (unit.isEmpty() && words.size() > 1 && units.contains(words.back()))
        unit = unitText(words.takeLast());
    if (words.size() > 1 && words.front() == "probability" && words[1] == "per") {
        unit = "per " + words.mid(2).join(' ');
        words = {"probability"};
    }
    for (QString& w : words)
        if (w == "sigma") w = "σ";
    QString name = words.join(' ');
    if (!name.isEmpty() && name.front() != QChar(0x3c3)) name[0] = name[0].toUpper();
    return unit.isEmpty() ? name : QString("%1 (%2)").arg(name, unit);
}
}  // namespace

namespace {
QDoubleSpinBox* spin(double lo, double hi, double value, const QString& suffix, int decimals = 2) {
    auto* s = new QDoubleSpinBox;
    s->setRange(lo, hi);
    s->setDecimals(decimals);
    s->setValue(value);
    s->setSuffix(suffix);
    return s;
}
}  // namespace

ScenePanel::ScenePanel(QWidget* parent) : QWidget(parent) {
    QVBoxLayout* layout = scrolledColumn(this);
    layout->addWidget(buildObjectBox());
    layout->addWidget(buildEffectsBox());
    layout->addStretch();
    for (auto* s : {width_, height_, arm_, opening_, x_, y_, rotation_, top_})
        connect(s, &QDoubleSpinBox::valueChanged, this, &ScenePanel::changed);
    connect(shape_, &QComboBox::currentTextChanged, this, &ScenePanel::changed);
    // Only the sizes the chosen shape has are editable.
    auto enableSizes = [this](const QString& shape) {
        const bool library = shape != "polygon";
        width_->setEnabled(library);
        height_->setEnabled(library);
        arm_->setEnabled(shape == "cross" || shape == "C" || shape == "L");
        opening_->setEnabled(shape == "C");
    };
    connect(shape_, &QComboBox::currentTextChanged, this, enableSizes);
    enableSizes(shape_->currentText());
    connect(this, &ScenePanel::changed, this, &ScenePanel::updateReach);
}

QGroupBox* ScenePanel::buildObjectBox() {
    auto* object = new QGroupBox(tr("Object"));
    auto* form = new QFormLayout(object);
    shape_ = new QComboBox;
    for (const std::string& name : libraryShapeNames())
        shape_->addItem(QString::fromStdString(name));
    shape_->addItem("polygon");
    width_ = spin(1, 1000, 48, " mm");
    height_ = spin(1, 1000, 58, " mm");
    arm_ = spin(1, 1000, 20, " mm");
    opening_ = spin(1, 1000, 20, " mm");
    x_ = spin(0, 5000, 150, " mm");
    y_ = spin(0, 5000, 150, " mm");
    x_->setObjectName("objectCentreX");
    y_->setObjectName("objectCentreY");
    rotation_ = spin(-360, 360, 0, " °");
    top_ = spin(0.1, 500, 10, " mm");
    polygonLabel_ = new QLabel(tr("no outline loaded"));
    polygonLabel_->setWordWrap(true);
    auto* loadButton = new QPushButton(tr("Load outline..."));
    loadButton->setToolTip(
        tr("A polygon (.json), an SVG drawing (.svg: its largest closed "
           "outline) or a 3D-printed object's mesh (.stl, .obj: sliced under "
           "its top)"));
    reachLabel_ = new QLabel;
    reachLabel_->setObjectName("reachNote");
    reachLabel_->setWordWrap(true);
    reachLabel_->setVisible(false);
    connect(loadButton, &QPushButton::clicked, this, &ScenePanel::loadPolygon);
    form->addRow(tr("Shape"), shape_);
    form->addRow(tr("Width"), width_);
    form->addRow(tr("Height"), height_);
    form->addRow(tr("Arm width"), arm_);
    form->addRow(tr("C opening"), opening_);
    form->addRow(tr("Centre x"), x_);
    form->addRow(tr("Centre y"), y_);
    form->addRow(tr("Rotation"), rotation_);
    form->addRow(tr("Top height"), top_);
    form->addRow(polygonLabel_, loadButton);
    form->addRow(reachLabel_);
    return object;
}

QGroupBox* ScenePanel::buildEffectsBox() {
    auto* effectsBox = new QGroupBox(tr("Effects (each runs only when ticked)"));
    auto* effectsLayout = new QVBoxLayout(effectsBox);
    for (const EffectDescription& d : effectCatalogue()) {
        EffectWidgets w;
        w.box = new QGroupBox(humanLabel(d.name));
        w.box->setObjectName(QString::fromStdString("effect_" + d.name));
        w.box->setCheckable(true);
        w.box->setChecked(false);
        w.box->setToolTip(
            QString::fromStdString(d.models + " (in a scene file: \"" + d.name + "\")"));
        auto* f = new QFormLayout(w.box);
        for (const EffectParameter& p : d.parameters) {
            auto* s = spin(p.lo, p.hi, p.typical, "", 3);
            s->setToolTip(
                QString::fromStdString(p.meaning + " (in a scene file: \"" + p.key + "\")"));
            f->addRow(humanLabel(p.key), s);
            w.parameters[p.key] = s;
            connect(s, &QDoubleSpinBox::valueChanged, this, &ScenePanel::changed);
        }
        if (d.takesTaxelList) {
            w.taxels = new QLineEdit("3");
            w.taxels->setToolTip(tr("taxel indices, separated by commas"));
            f->addRow(tr("Taxels"), w.taxels);
        }
        connect(w.box, &QGroupBox::toggled, this, &ScenePanel::changed);
        effectsLayout->addWidget(w.box);
        effects_[d.name] = w;
    }
    return effectsBox;
}

void ScenePanel::showScene(const SceneSpec& scene) {
    const QSignalBlocker block(this);
    const ObjectSpec& o = scene.object;
    shape_->setCurrentText(QString::fromStdString(o.shape));
    width_->setValue(o.size.width);
    height_->setValue(o.size.height);
    arm_->setValue(o.size.arm);
    opening_->setValue(o.size.opening);
    x_->setValue(o.offset.x);
    y_->setValue(o.offset.y);
    rotation_->setValue(o.rotationDeg);
    top_->setValue(o.height_mm);
    polygon_ = o.polygon;
    polygonLabel_->setText(polygon_.empty() ? tr("no outline loaded")
                                            : tr("polygon of %1 vertices").arg(polygon_.size()));
    base_ = scene;
    contactRadius_mm_ = sceneContactRadius(scene);
    for (auto& [name, w] : effects_) {
        w.box->setChecked(false);
        w.gains.clear();
        for (auto& [key, s] : w.parameters) s->setEnabled(true);
        w.box->setToolTip(QString());
    }
    for (const EffectSpec& e : scene.effects) {
        auto it = effects_.find(e.name);
        if (it == effects_.end()) continue;
        it->second.box->setChecked(true);
        if (e.parameters.contains("gains") && e.parameters["gains"].is_array()) {
            QStringList shown;
            for (const auto& v : e.parameters["gains"]) {
                it->second.gains.push_back(v.get<double>());
                shown << QString::number(v.get<double>(), 'g', 4);
            }
            for (auto& [key, s] : it->second.parameters) s->setEnabled(false);
            it->second.box->setToolTip(
                tr("Measured gains from the scene file, kept as they are: %1")
                    .arg(shown.join(", ")));
        }
        for (auto& [key, s] : it->second.parameters)
            if (e.parameters.contains(key) && e.parameters[key].is_number())
                s->setValue(e.parameters[key].get<double>());
        if (it->second.taxels && e.parameters.contains("taxels")) {
            QStringList list;
            for (const auto& v : e.parameters["taxels"]) list << QString::number(v.get<int>());
            it->second.taxels->setText(list.join(", "));
        }
    }
    updateReach();
}

SceneSpec ScenePanel::sceneFromPanel(const SceneSpec& base) const {
    Json j = sceneToJson(base);
    Json o;
    o["shape"] = shape_->currentText().toStdString();
    if (o["shape"] == "polygon") {
        Json poly = Json::array();
        for (Vec2 v : polygon_) poly.push_back({v.x, v.y});
        o["polygon_mm"] = poly;
    } else {
        o["width_mm"] = width_->value();
        o["height_mm"] = height_->value();
        if (o["shape"] != "rectangle") o["arm_mm"] = arm_->value();
        if (o["shape"] == "C") o["opening_mm"] = opening_->value();
    }
    o["rotation_deg"] = rotation_->value();
    o["offset_mm"] = {x_->value(), y_->value()};
    o["top_height_mm"] = top_->value();
    j["object"] = o;
    Json effects = Json::array();
    for (const EffectDescription& d : effectCatalogue()) {
        const EffectWidgets& w = effects_.at(d.name);
        if (!w.box->isChecked()) continue;
        Json e{{"name", d.name}};
        if (!w.gains.empty())
            e["gains"] = w.gains;
        else
            for (const auto& [key, s] : w.parameters) e[key] = s->value();
        if (w.taxels) {
            Json list = Json::array();
            for (const QString& part : w.taxels->text().split(',', Qt::SkipEmptyParts)) {
                bool ok = false;
                const int k = part.trimmed().toInt(&ok);
                if (!ok)
                    throw InputError("scene panel", d.name + " taxels",
                                     "'" + part.trimmed().toStdString() + "' is not a taxel index");
                list.push_back(k);
            }
            e["taxels"] = list;
        }
        effects.push_back(e);
    }
    j["effects"] = effects;
    return parseScene(j, "scene panel", "", ".");
}

void ScenePanel::loadPolygon() {
    const QString path = QFileDialog::getOpenFileName(
        this, tr("Load an outline"), QString(),
        tr("Outlines (*.json *.svg *.stl *.obj);;Polygons (*.json);;SVG drawings (*.svg);;"
           "Meshes (*.stl *.obj)"));
    if (path.isEmpty()) return;
    QString units;
    if (isMeshFileName(path.toStdString())) {
        bool ok = false;
        // STL and OBJ files do not say their units: printing software mostly writes mm, CAD
        // exports often m.
        units = QInputDialog::getItem(
            this, tr("Mesh units"), tr("The units %1 is drawn in:").arg(QFileInfo(path).fileName()),
            {"mm", "cm", "m", "in"}, 0, false, &ok);
        if (!ok) return;
    }
    loadOutlineFrom(path, units);
}

bool ScenePanel::loadOutlineFrom(const QString& path, const QString& meshUnits) {
    OutlineFile loaded;
    try {
        if (isMeshFileName(path.toStdString()) && meshUnits.isEmpty())
            throw InputError(path.toStdString(), "",
                             "a mesh does not say its units; give them (mm, cm, m or in)");
        loaded = loadOutlineFile(path.toStdString(), meshUnits.toStdString());
    } catch (const InputError& e) {
        emit failed(QString::fromStdString(e.what()));
        return false;
    }
    {
        const QSignalBlocker block(this);
        polygon_ = loaded.polygon;
        shape_->setCurrentText("polygon");
        if (loaded.height_mm) top_->setValue(*loaded.height_mm);
    }
    polygonLabel_->setText(
        tr("%1, %2 vertices").arg(QString::fromStdString(loaded.description)).arg(polygon_.size()));
    for (const std::string& note : loaded.notes)
        emit noted(tr("%1: %2").arg(path, QString::fromStdString(note)));
    emit changed();
    return true;
}

QString ScenePanel::reachNote() const {
    return reachLabel_->text();
}

void ScenePanel::updateReach() {
    QString note;
    try {
        const Polygon outline = sceneFromPanel(base_).object.outline();
        note = QString::fromStdString(
            reachCaution(outline, *ContourReach::shared(outline, contactRadius_mm_), "The object"));
    } catch (const std::exception&) {
        // A panel mid-edit (no polygon yet, sizes that make no outline): nothing to judge; the
        // run refuses such a scene by name.
    }
    reachLabel_->setText(note);
    reachLabel_->setVisible(!note.isEmpty());
}

}  // namespace activetouch
