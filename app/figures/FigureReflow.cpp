#include "app/figures/FigureReflow.h"

#include <QFontMetricsF>
#include <QVariantList>
#include <algorithm>
#include <cmath>
#include <vector>

#include "app/figures/FigureFitting.h"
#include "qcustomplot.h"

namespace activetouch {

namespace {
/// The least width of a panel's data between its axes, pixels.
constexpr double kLeastData_px = 60.0;
/// Room between an inside legend and the panel's edge, pixels.
constexpr double kLegendRoom_px = 8.0;
/// How much more room than they need panels must find to go back to more a line.
constexpr double kUnwrapRoom = 1.1;
/// The least height of a wrapped panel, as a share of its column's width.
constexpr double kWrappedAspect = 0.45;

/// The width `e` needs: a panel its margins and some data, or its inside legend beside its axis;
/// a legend its widest entry; a cell the most any of its parts needs.
double widthNeeded(QCPLayoutElement* e) {
    if (auto* rect = qobject_cast<QCPAxisRect*>(e)) {
        const QMargins m = rect->margins();
        double need = m.left() + m.right() + kLeastData_px;
        // A label kept above the data (keepTextAboveData) fits across the panel.
        QCustomPlot* plot = rect->parentPlot();
        for (int i = 0; i < plot->itemCount(); ++i)
            if (auto* label = qobject_cast<QCPItemText*>(plot->item(i));
                label && label->property("headroomOver").value<QObject*>() == rect)
                need = std::max(need, m.left() + m.right() + 8.0 + textSize(*label).width());
        for (QCPLayoutElement* inset : rect->insetLayout()->elements(false))
            if (auto* legend = qobject_cast<QCPLegend*>(inset);
                legend && legend->visible() && legend->itemCount() > 0)
                need = std::max(need, m.left() + m.right() + kLegendRoom_px +
                                          legend->minimumOuterSizeHint().width());
        return need;
    }
    if (auto* legend = qobject_cast<QCPLegend*>(e)) {
        double widest = 0.0;
        for (int i = 0; i < legend->itemCount(); ++i)
            if (QCPAbstractLegendItem* item = legend->item(i))
                widest = std::max<double>(widest, item->minimumOuterSizeHint().width());
        return widest + legend->margins().left() + legend->margins().right();
    }
    if (auto* grid = qobject_cast<QCPLayoutGrid*>(e)) {
        double need = 0.0;
        for (QCPLayoutElement* part : grid->elements(false))
            if (part) need = std::max(need, widthNeeded(part));
        return need;
    }
    return e->minimumOuterSizeHint().width();
}

QVariantList asList(const QList<double>& values) {
    QVariantList list;
    for (double v : values) list << v;
    return list;
}

/// Keeps the arrangement the figure's code made of `grid` (once): each element's row and
/// column, the grid's size and stretch factors.
void remember(QCPLayoutGrid* grid, QCPLayoutGrid* figure, int figureRow) {
    if (grid->property("askedRows").isValid()) return;
    grid->setProperty("askedRows", grid->rowCount());
    grid->setProperty("askedColumns", grid->columnCount());
    grid->setProperty("askedRowStretch", asList(grid->rowStretchFactors()));
    grid->setProperty("askedColumnStretch", asList(grid->columnStretchFactors()));
    grid->setProperty("askedFigureStretch", figure->rowStretchFactors().value(figureRow, 1.0));
    grid->setProperty("panelsPerLine", grid->columnCount());
    grid->setProperty("lines", 1);
    for (int i = 0; i < grid->elementCount(); ++i) {
        QCPLayoutElement* e = grid->elementAt(i);
        if (!e) continue;
        int row = 0, column = 0;
        grid->indexToRowCol(i, row, column);
        e->setProperty("askedRow", row);
        e->setProperty("askedColumn", column);
    }
}

/// The most columns of `needs` (in order) that fit `width` on every line.
int columnsThatFit(const std::vector<double>& needs, double width, double spacing) {
    const int all = static_cast<int>(needs.size());
    for (int k = all; k > 1; --k) {
        bool fits = true;
        for (int first = 0; first < all && fits; first += k) {
            double line = 0.0;
            for (int c = first; c < std::min(all, first + k); ++c)
                line += needs[std::size_t(c)] + (c > first ? spacing : 0.0);
            fits = line <= width;
        }
        if (fits) return k;
    }
    return 1;
}

/// Puts `grid`'s elements `perLine` groups of asked columns to a line; the figure's row grows
/// with it.
/// Every panel in `e` (itself, or in a cell).
void panelsIn(QCPLayoutElement* e, std::vector<QCPAxisRect*>& panels) {
    if (auto* rect = qobject_cast<QCPAxisRect*>(e)) panels.push_back(rect);
    if (auto* grid = qobject_cast<QCPLayoutGrid*>(e); grid && !qobject_cast<QCPLegend*>(e))
        for (QCPLayoutElement* part : grid->elements(false))
            if (part) panelsIn(part, panels);
}

/// Panels wrapped into lines keep a height in proportion to their width (kWrappedAspect), so
/// that a plot of fixed height grows (and scrolls) rather than squashing them; unwrapped, the
/// least height the figure's code gave them.
void keepWrappedPanelsTall(const std::vector<QCPLayoutElement*>& elements, int lines,
                           double columnWidth) {
    std::vector<QCPAxisRect*> panels;
    for (QCPLayoutElement* e : elements) panelsIn(e, panels);
    for (QCPAxisRect* rect : panels) {
        if (!rect->property("askedLeastHeight").isValid())
            rect->setProperty("askedLeastHeight", rect->minimumSize().height());
        const int asked = rect->property("askedLeastHeight").toInt();
        const int least =
            lines > 1 ? std::max(asked, static_cast<int>(kWrappedAspect * columnWidth)) : asked;
        rect->setMinimumSize(rect->minimumSize().width(), least);
    }
}

void arrange(QCPLayoutGrid* grid, QCPLayoutGrid* figure, int figureRow, int perLine, double width) {
    const int rows = grid->property("askedRows").toInt();
    const int columns = grid->property("askedColumns").toInt();
    const int group = std::max(1, grid->property(kColumnGroup).toInt());
    const QVariantList rowStretch = grid->property("askedRowStretch").toList();
    const QVariantList columnStretch = grid->property("askedColumnStretch").toList();
    std::vector<QCPLayoutElement*> elements;
    for (int i = 0; i < grid->elementCount(); ++i)
        if (QCPLayoutElement* e = grid->elementAt(i)) elements.push_back(e);
    for (QCPLayoutElement* e : elements) grid->take(e);
    grid->simplify();
    for (QCPLayoutElement* e : elements) {
        const int row = e->property("askedRow").toInt(),
                  column = e->property("askedColumn").toInt();
        const int g = column / group;
        grid->addElement((g / perLine) * rows + row, (g % perLine) * group + column % group, e);
    }
    const int groups = (columns + group - 1) / group;
    const int lines = (groups + perLine - 1) / perLine;
    for (int line = 0; line < lines; ++line)
        for (int r = 0; r < rows && line * rows + r < grid->rowCount(); ++r)
            grid->setRowStretchFactor(line * rows + r, rowStretch.value(r, 1.0).toDouble());
    for (int c = 0; c < grid->columnCount(); ++c)
        grid->setColumnStretchFactor(c, columnStretch.value(c, 1.0).toDouble());
    figure->setRowStretchFactor(figureRow, grid->property("askedFigureStretch").toDouble() * lines);
    grid->setProperty("panelsPerLine", perLine);
    grid->setProperty("lines", lines);
    keepWrappedPanelsTall(elements, lines, width / perLine);
}
}  // namespace

bool reflowPanels(QCustomPlot& plot, bool fresh) {
    QCPLayoutGrid* figure = plot.plotLayout();
    bool changed = false;
    for (int row = 0; row < figure->rowCount(); ++row) {
        auto* grid = qobject_cast<QCPLayoutGrid*>(figure->element(row, 0));
        if (!grid || qobject_cast<QCPLegend*>(grid) || grid->elementCount() == 0) continue;
        remember(grid, figure, row);
        const int columns = grid->property("askedColumns").toInt();
        const int group = std::max(1, grid->property(kColumnGroup).toInt());
        std::vector<double> columnNeeds(std::size_t(columns), 0.0);
        for (QCPLayoutElement* e : grid->elements(false)) {
            if (!e) continue;
            double& need = columnNeeds[std::size_t(e->property("askedColumn").toInt())];
            need = std::max(need, widthNeeded(e));
        }
        // Columns kept together wrap as one: their needs and the spacing between them.
        std::vector<double> needs((columnNeeds.size() + group - 1) / group, 0.0);
        for (std::size_t c = 0; c < columnNeeds.size(); ++c)
            needs[c / group] += columnNeeds[c] + (c % group ? grid->columnSpacing() : 0);
        const double width = plot.viewport().width() - figure->margins().left() -
                             figure->margins().right() - grid->margins().left() -
                             grid->margins().right();
        // More to a line only with room to spare: margins differ between arrangements, and a
        // need that shrank once the panels wrapped must not unwrap them again.
        const int now = grid->property("panelsPerLine").toInt();
        const int all = static_cast<int>(needs.size());
        if (fresh) {
            // A new size starts from the arrangement the figure's code made, so that what a size
            // shows never depends on the sizes before it.
            if (now != all) {
                arrange(grid, figure, row, all, width);
                changed = true;
            }
            continue;
        }
        int perLine = columnsThatFit(needs, width, grid->columnSpacing());
        if (perLine > now) {
            std::vector<double> roomier = needs;
            for (double& n : roomier) n *= kUnwrapRoom;
            perLine = std::max(now, columnsThatFit(roomier, width, grid->columnSpacing()));
        }
        if (perLine == now) continue;
        arrange(grid, figure, row, perLine, width);
        changed = true;
    }
    return changed;
}

double reflowGrowth(const QCustomPlot& plot) {
    const QCPLayoutGrid* figure = plot.plotLayout();
    double asked = 0.0, now = 0.0;
    for (int row = 0; row < figure->rowCount(); ++row) {
        auto* grid = qobject_cast<QCPLayoutGrid*>(figure->element(row, 0));
        if (!grid || !grid->property("askedFigureStretch").isValid()) continue;
        const double stretch = grid->property("askedFigureStretch").toDouble();
        // A row holding more rows of panels than its figure's usual height was made for grows
        // by as many.
        const QVariant usual = grid->property(kUsualRows);
        const double rows = grid->property("askedRows").toDouble();
        const double more = usual.isValid() ? std::max(1.0, rows / usual.toDouble()) : 1.0;
        asked += stretch;
        now += stretch * more * grid->property("lines").toInt();
    }
    return asked > 0.0 ? now / asked : 1.0;
}

void keepTextAboveData(QCPAxisRect* rect, QCPItemText* label, double bottom, double dataTop) {
    label->setProperty("headroomOver", QVariant::fromValue<QObject*>(rect));
    label->setProperty("headroomData", QPointF(bottom, dataTop));
    label->setClipAxisRect(rect);
    label->position->setAxisRect(rect);
    // Changing the type keeps the pixel position, which a panel not yet laid out has not got:
    // the coordinates are set after it.
    const double x = label->position->coords().x();
    label->setProperty("headroomCentre", x);
    label->position->setTypeY(QCPItemPosition::ptAxisRectRatio);
    label->position->setCoords(x, 0.02);
    label->setPositionAlignment(Qt::AlignTop |
                                (label->positionAlignment() & Qt::AlignHorizontal_Mask));
}

bool fitHeadroom(QCustomPlot& plot) {
    bool changed = false;
    for (int i = 0; i < plot.itemCount(); ++i) {
        auto* label = qobject_cast<QCPItemText*>(plot.item(i));
        if (!label || !label->property("headroomOver").isValid()) continue;
        auto* rect = qobject_cast<QCPAxisRect*>(label->property("headroomOver").value<QObject*>());
        if (!rect || rect->height() <= 0) continue;
        // Centred where it was asked, but inside the panel however wide it is.
        QCPAxis* across = rect->axis(QCPAxis::atBottom);
        const double width = textSize(*label).width() + 4.0;
        const double asked = across->coordToPixel(label->property("headroomCentre").toDouble());
        const double centre = width >= rect->width() ? rect->center().x()
                                                     : std::clamp(asked, rect->left() + width / 2,
                                                                  rect->right() - width / 2);
        const double x = across->pixelToCoord(centre);
        if (std::abs(label->position->coords().x() - x) > 1e-9 * std::max(1.0, std::abs(x))) {
            label->position->setCoords(x, 0.02);
            changed = true;
        }
        const QPointF data = label->property("headroomData").toPointF();
        const double room = QFontMetricsF(label->font()).height() + 0.02 * rect->height() + 6.0;
        const double share = std::min(0.6, room / rect->height());
        const double top = data.x() + (data.y() - data.x()) / (1.0 - share);
        QCPAxis* axis = rect->axis(QCPAxis::atLeft);
        if (std::abs(axis->range().upper - top) <= 1e-9 * std::max(1.0, std::abs(top))) continue;
        axis->setRange(data.x(), top);
        changed = true;
    }
    return changed;
}

void alignWithPanel(QCPColorScale* scale, QCPAxisRect* rect) {
    scale->setProperty("alignedWith", QVariant::fromValue<QObject*>(rect));
    scale->setAutoMargins(QCP::msLeft | QCP::msRight);
}

bool fitColourScales(QCustomPlot& plot) {
    bool changed = false;
    for (QCPLayoutElement* e : plot.plotLayout()->elements(true)) {
        auto* scale = qobject_cast<QCPColorScale*>(e);
        if (!scale) continue;
        auto* rect = qobject_cast<QCPAxisRect*>(scale->property("alignedWith").value<QObject*>());
        if (!rect) continue;
        QMargins m = scale->margins();
        if (m.top() == rect->margins().top() && m.bottom() == rect->margins().bottom()) continue;
        m.setTop(rect->margins().top());
        m.setBottom(rect->margins().bottom());
        scale->setMargins(m);
        changed = true;
    }
    return changed;
}

}  // namespace activetouch
