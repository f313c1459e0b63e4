#include "app/gui/ExportDialog.h"

#include <QComboBox>
#include <QDialogButtonBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QSpinBox>
#include <algorithm>
#include <cmath>

namespace activetouch {

namespace {
constexpr double kMmPerInch = 25.4;
}

ExportDialog::ExportDialog(const QString& figure, std::function<double(double)> heightFor,
                           QWidget* parent)
    : QDialog(parent), heightFor_(std::move(heightFor)) {
    setObjectName("exportDialog");
    setWindowTitle(tr("Export %1").arg(figure));
    auto* form = new QFormLayout(this);
    format_ = new QComboBox;
    format_->setObjectName("exportFormat");
    format_->addItem(tr("PDF (vector, fonts embedded)"), "pdf");
    format_->addItem(tr("SVG (vector)"), "svg");
    format_->addItem(tr("PNG (image)"), "png");
    preset_ = new QComboBox;
    preset_->setObjectName("exportPreset");
    preset_->addItems({tr("Single column (%1 mm)").arg(kSingleColumn_mm),
                       tr("Double column (%1 mm)").arg(kDoubleColumn_mm), tr("Custom size")});
    unit_ = new QComboBox;
    unit_->setObjectName("exportUnit");
    unit_->addItems({tr("mm"), tr("in"), tr("px")});
    width_ = new QDoubleSpinBox;
    width_->setObjectName("exportWidth");
    height_ = new QDoubleSpinBox;
    height_->setObjectName("exportHeight");
    for (QDoubleSpinBox* s : {width_, height_}) {
        s->setDecimals(1);
        s->setRange(10, 10000);
    }
    dpi_ = new QSpinBox;
    dpi_->setObjectName("exportDpi");
    dpi_->setRange(72, 1200);
    dpi_->setValue(kFigureDpi);
    dpi_->setSuffix(tr(" dpi"));
    auto* sizeRow = new QHBoxLayout;
    sizeRow->addWidget(width_);
    sizeRow->addWidget(new QLabel(QStringLiteral("×")));
    sizeRow->addWidget(height_);
    sizeRow->addWidget(unit_);
    note_ = new QLabel;
    note_->setWordWrap(true);
    form->addRow(tr("Format"), format_);
    form->addRow(tr("Size"), preset_);
    form->addRow(tr("Width × height"), sizeRow);
    form->addRow(tr("Resolution"), dpi_);
    form->addRow(note_);
    auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel);
    form->addRow(buttons);
    connect(buttons, &QDialogButtonBox::accepted, this, &QDialog::accept);
    connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
    connect(preset_, &QComboBox::currentIndexChanged, this, &ExportDialog::applyPreset);
    connect(unit_, &QComboBox::currentIndexChanged, this, [this](int) {
        preset_->setCurrentIndex(2);
        updateNote();
    });
    for (QDoubleSpinBox* s : {width_, height_})
        connect(s, &QDoubleSpinBox::editingFinished, this, [this] {
            preset_->setCurrentIndex(2);
            updateNote();
        });
    connect(dpi_, &QSpinBox::valueChanged, this, &ExportDialog::updateNote);
    connect(format_, &QComboBox::currentIndexChanged, this, &ExportDialog::updateNote);
    applyPreset();
}

void ExportDialog::applyPreset() {
    const int preset = preset_->currentIndex();
    if (preset > 1) return;  // custom: the fields as they are
    const double width = preset == 0 ? kSingleColumn_mm : kDoubleColumn_mm;
    QSignalBlocker block(unit_);
    unit_->setCurrentIndex(0);
    width_->setValue(width);
    const double height = heightFor_ ? heightFor_(width) : 0.0;
    height_->setValue(std::isfinite(height) && height > 0.0 ? std::round(height * 10.0) / 10.0
                                                            : std::round(width * 0.7));
    updateNote();
}

void ExportDialog::updateNote() {
    const FigureSize s = size();
    note_->setText(
        s.isPhysical()
            ? tr("Laid out at %1 × %2 mm with text at %3-%4 pt; a PNG has %5 × %6 pixels.")
                  .arg(s.width_mm, 0, 'f', 1)
                  .arg(s.height_mm, 0, 'f', 1)
                  .arg(kSmallestText_pt)
                  .arg(kLargestText_pt)
                  .arg(s.width_px)
                  .arg(s.height_px)
            : tr("The plot as laid out on a screen of %1 × %2 pixels (the text keeps its screen "
                 "size); the resolution is only recorded in a PNG.")
                  .arg(s.width_px)
                  .arg(s.height_px));
}

QString ExportDialog::format() const {
    return format_->currentData().toString();
}

FigureSize ExportDialog::sizeFrom(double width, double height, Unit unit, int dpi) {
    switch (unit) {
        case Unit::Millimetre:
            return FigureSize::physical(width, height, dpi);
        case Unit::Inch:
            return FigureSize::physical(width * kMmPerInch, height * kMmPerInch, dpi);
        case Unit::Pixel:
            break;
    }
    return FigureSize{static_cast<int>(std::lround(width)), static_cast<int>(std::lround(height)),
                      dpi};
}

FigureSize ExportDialog::size() const {
    return sizeFrom(width_->value(), height_->value(), static_cast<Unit>(unit_->currentIndex()),
                    dpi_->value());
}

void ExportDialog::choosePreset(int preset) {
    preset_->setCurrentIndex(preset);
    applyPreset();
}

void ExportDialog::chooseSize(double width, double height, Unit unit, int dpi) {
    preset_->setCurrentIndex(2);
    unit_->setCurrentIndex(static_cast<int>(unit));
    width_->setValue(width);
    height_->setValue(height);
    dpi_->setValue(dpi);
    updateNote();
}

}  // namespace activetouch
