#pragma once
// Asking how to export a figure: the format, a journal preset (single column, double column) or a
// size in mm, inches or pixels, and the resolution. A physical size lays the figure out at that
// size with its text at 7-9 pt; pixels keep the plot's screen layout.
#include <QDialog>
#include <functional>

#include "app/figures/FigureExport.h"

class QComboBox;
class QDoubleSpinBox;
class QSpinBox;
class QLabel;

namespace activetouch {

class ExportDialog : public QDialog {
    Q_OBJECT
public:
    enum class Unit { Millimetre, Inch, Pixel };
    /// `heightFor`: the figure's own height (mm) at a width (mm), which the presets take; never
    /// the window's shape.
    ExportDialog(const QString& figure, std::function<double(double)> heightFor,
                 QWidget* parent = nullptr);

    QString format() const;
    FigureSize size() const;
    /// The size `width` by `height` in `unit` at `dpi`: physical for mm and inches.
    static FigureSize sizeFrom(double width, double height, Unit unit, int dpi);

    /// Sets the dialog as a person would: a preset by index (0 single column, 1 double column,
    /// 2 custom), then a unit and a size for a custom one.
    void choosePreset(int preset);
    void chooseSize(double width, double height, Unit unit, int dpi);

private:
    void applyPreset();
    void updateNote();
    std::function<double(double)> heightFor_;
    QComboBox *format_, *preset_, *unit_;
    QDoubleSpinBox *width_, *height_;
    QSpinBox* dpi_;
    QLabel* note_;
};

}  // namespace activetouch
