#include "app/gui/PlotPanel.h"

#include <QApplication>
#include <QClipboard>
#include <QDir>
#include <QFileDialog>
#include <QMenu>
#include <QMouseEvent>
#include <QScrollArea>
#include <QTextStream>
#include <QVBoxLayout>
#include <stdexcept>

#include "app/figures/ComparisonFigures.h"
#include "app/figures/FigureFitting.h"
#include "app/figures/FollowingFigures.h"
#include "app/figures/SeedFigures.h"
#include "app/gui/ExportDialog.h"
#include "app/gui/PlotReadout.h"
#include "app/gui/PlotTheme.h"
#include "app/gui/WholeFile.h"
#include "qcustomplot.h"

namespace activetouch {

PlotPanel::PlotPanel(const QString& name, QWidget* parent)
    : QWidget(parent), name_(name), plot_(new QCustomPlot(this)), hint_(new QLabel(plot_)) {
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    // A figure of many panels may ask for more room than a laptop has: it keeps the room its
    // layout needs and scrolls within the panel, rather than making the window larger.
    auto* scroll = new QScrollArea;
    scroll->setObjectName("plotScroll");
    scroll->setWidgetResizable(true);
    scroll->setFrameShape(QFrame::NoFrame);
    scroll->setWidget(plot_);
    layout->addWidget(scroll);
    plot_->setMinimumSize(160, 120);
    connect(plot_, &QCustomPlot::afterReplot, this, [this] {
        const QSize least = plot_->plotLayout()->minimumOuterSizeHint().expandedTo(QSize(160, 120));
        if (plot_->minimumSize() != least) plot_->setMinimumSize(least);
    });
    plot_->setContextMenuPolicy(Qt::CustomContextMenu);
    plot_->setNoAntialiasingOnDrag(true);
    connect(plot_, &QWidget::customContextMenuRequested, this, &PlotPanel::showMenu);
    // Exploring: the wheel zooms and a drag pans the panel under the cursor (both axes), a
    // double-click goes back to the plot's own ranges, the value under the cursor is traced.
    plot_->setInteractions(QCP::iRangeDrag | QCP::iRangeZoom);
    plot_->setMouseTracking(true);
    plot_->installEventFilter(this);
    plot_->setToolTip(
        tr("Wheel: zoom; drag: pan; double-click: back to the whole plot; right "
           "click: export"));
    connect(plot_, &QCustomPlot::mouseDoubleClick, this, [this] { resetView(); });
    hint_->setObjectName("emptyHint");
    hint_->setAlignment(Qt::AlignCenter);
    hint_->setWordWrap(true);
    hint_->setAttribute(Qt::WA_TransparentForMouseEvents);  // the context menu still works
    hint_->setStyleSheet("QLabel { color: #606060; font-size: 12pt; padding: 40px; }");
    hint_->hide();
    connect(plot_, &QCustomPlot::afterReplot, this, &PlotPanel::updateEmptyHint);
    // An empty figure shows its hint alone: no bare 0..5 axis frame behind the words.
    connect(plot_, &QCustomPlot::beforeReplot, this, [this] {
        // A figure drawn anew has ranges of its own: the last one's zoom no longer applies.
        const void* first = plot_->plottableCount() > 0 ? plot_->plottable(0) : nullptr;
        if (first != shownFigure_) {
            shownFigure_ = first;
            zoomed_ = false;
            home_.clear();
        }
        const bool shown = !waitsForData();
        QCPLayoutGrid* layout = plot_->plotLayout();
        for (int i = 0; i < layout->elementCount(); ++i)
            if (QCPLayoutElement* e = layout->elementAt(i)) e->setVisible(shown);
    });
    replotTimer_.setInterval(20);  // at most 50 redraws a second, whatever the data rate
    connect(&replotTimer_, &QTimer::timeout, this, [this] {
        if (!dirty_) return;
        dirty_ = false;
        plot_->replot(QCustomPlot::rpQueuedReplot);
    });
    replotTimer_.start();
    // Everything fitted to the plot's size (panels per line, legends, labels, ticks, equal
    // aspect) follows it: after each layout the figure is refitted and laid out again, within the
    // same replot, until nothing changes; the plot is drawn once, settled.
    connect(plot_, &QCustomPlot::afterLayout, this, [this] {
        QCPLayoutGrid* layout = plot_->plotLayout();
        for (int round = 0; round < kLayoutRounds && !zoomed_ && fitToLayout(*plot_); ++round)
            for (auto phase : {QCPLayoutElement::upPreparation, QCPLayoutElement::upMargins,
                               QCPLayoutElement::upLayout})
                layout->update(phase);
        // Drawn in the desktop's ink, parts the fit added included; a page is always light.
        setDarkInk(*plot_, !onPage_ && isDarkPalette(palette()));
    });
}

void PlotPanel::changeEvent(QEvent* event) {
    if (event->type() == QEvent::PaletteChange) plot_->replot(QCustomPlot::rpQueuedReplot);
    QWidget::changeEvent(event);
}

bool PlotPanel::eventFilter(QObject* watched, QEvent* event) {
    if (watched == plot_) {
        switch (event->type()) {
            case QEvent::MouseButtonPress:
            case QEvent::Wheel:
                rememberHome();
                break;
            case QEvent::MouseMove:
                traceAt(static_cast<QMouseEvent*>(event)->position());
                break;
            case QEvent::Leave:
                hideTracer();
                break;
            default:
                break;
        }
    }
    return QWidget::eventFilter(watched, event);
}

void PlotPanel::rememberHome() {
    if (zoomed_ || waitsForData()) return;
    home_.clear();
    for (QCPAxisRect* rect : plot_->axisRects())
        for (QCPAxis* axis : rect->axes())
            home_.append({axis, {axis->range().lower, axis->range().upper}});
    zoomed_ = true;
}

void PlotPanel::resetView() {
    for (const auto& [axis, range] : home_)
        if (plot_->axisRects().contains(axis->axisRect()))
            axis->setRange(range.first, range.second);
    home_.clear();
    zoomed_ = false;
    plot_->replot(QCustomPlot::rpQueuedReplot);
}

namespace {
/// A number in a CSV: six significant figures.
QString numberText(double v) {
    return QString::number(v, 'g', 6);
}
}  // namespace

void PlotPanel::ensureTracer() {
    if (tracer_) return;
    tracer_ = new QCPItemTracer(plot_);
    tracer_->setObjectName("valueTracer");
    tracer_->setLayer("overlay");
    tracer_->setStyle(QCPItemTracer::tsCircle);
    tracer_->setSize(9);
    tracer_->setPen(QPen(QColor(20, 20, 20), 1.5));
    tracer_->setBrush(Qt::NoBrush);
    tracer_->setInterpolating(false);
    tracer_->setSelectable(false);
    cursorLabel_ = new QCPItemText(plot_);
    cursorLabel_->setObjectName("valueLabel");
    cursorLabel_->setLayer("overlay");
    cursorLabel_->setPadding(QMargins(4, 2, 4, 2));
    cursorLabel_->setBrush(QColor(255, 255, 255, 230));
    cursorLabel_->setPen(QPen(QColor(120, 120, 120)));
    cursorLabel_->setPositionAlignment(Qt::AlignLeft | Qt::AlignTop);
    cursorLabel_->position->setType(QCPItemPosition::ptAbsolute);
    cursorLabel_->setSelectable(false);
}

QString PlotPanel::describePoint(QCPAbstractPlottable* p, int index, const QPointF& pos) {
    double key = 0, value = 0;
    QString extra;
    if (auto* g = qobject_cast<QCPGraph*>(p); g && index < g->dataCount()) {
        key = g->dataMainKey(index);
        value = g->dataMainValue(index);
        tracer_->setGraph(g);
        tracer_->setGraphKey(key);
    } else if (auto* m = qobject_cast<QCPColorMap*>(p)) {
        key = p->keyAxis()->pixelToCoord(pos.x());
        value = p->valueAxis()->pixelToCoord(pos.y());
        int kx = 0, vy = 0;
        m->data()->coordToCell(key, value, &kx, &vy);
        m->data()->cellToCoord(kx, vy, &key, &value);
        const double cell = m->data()->cell(kx, vy);
        const QString scale = m->colorScale() ? m->colorScale()->axis()->label() : QString();
        const auto [name, unit] = quantityOf(scale);
        extra = QString("\n%1 %2%3")
                    .arg(name.isEmpty() ? tr("value") : name, readoutNumber(cell),
                         unit.isEmpty() ? QString() : " " + unit);
    } else if (auto* d = dynamic_cast<QCPPlottableInterface1D*>(p); d && index < d->dataCount()) {
        key = d->dataMainKey(index);
        value = d->dataMainValue(index);
    } else {
        key = p->keyAxis()->pixelToCoord(pos.x());
        value = p->valueAxis()->pixelToCoord(pos.y());
    }
    if (!tracer_->graph()) tracer_->position->setCoords(key, value);
    const QString series = seriesName(p).isEmpty() ? QString() : seriesName(p) + "\n";
    return series + axisValueText(p->keyAxis(), key) + "\n" + axisValueText(p->valueAxis(), value) +
           extra;
}

QString PlotPanel::traceAt(const QPointF& pos) {
    QCPAxisRect* rect = plot_->axisRectAt(pos);
    if (!rect || waitsForData()) {
        hideTracer();
        return {};
    }
    ensureTracer();
    QCPAxis* xAxis = rect->axis(QCPAxis::atBottom);
    QCPAxis* yAxis = rect->axis(QCPAxis::atLeft);
    tracer_->setClipAxisRect(rect);
    tracer_->position->setAxes(xAxis, yAxis);
    tracer_->setGraph(nullptr);
    QString text;
    int index = -1;
    QCPAbstractPlottable* p = plot_->plottableAt(pos, false, &index);
    if (p && p->keyAxis() && p->keyAxis()->axisRect() == rect && index >= 0) {
        text = describePoint(p, index, pos);
        tracer_->setVisible(true);
    } else {
        // Nothing within reach: the axes' values under the cursor.
        text = axisValueText(xAxis, xAxis->pixelToCoord(pos.x())) + "\n" +
               axisValueText(yAxis, yAxis->pixelToCoord(pos.y()));
        tracer_->setVisible(false);
    }
    cursorLabel_->setText(text);
    cursorLabel_->setClipToAxisRect(false);
    // Beside the cursor, kept whole inside the plot.
    const QSizeF size = textSize(*cursorLabel_).grownBy(cursorLabel_->padding()) + QSizeF(2, 2);
    cursorLabel_->position->setCoords(readoutPlace(plot_->rect(), pos, size).topLeft());
    cursorLabel_->setVisible(true);
    plot_->layer("overlay")->replot();
    return text;
}

QString PlotPanel::cursorText() const {
    return cursorLabel_ && cursorLabel_->visible() ? cursorLabel_->text() : QString();
}

void PlotPanel::hideTracer() {
    if (!tracer_ || !cursorLabel_) return;
    if (!tracer_->visible() && !cursorLabel_->visible()) return;
    tracer_->setVisible(false);
    cursorLabel_->setVisible(false);
    plot_->layer("overlay")->replot();
}

void PlotPanel::setEmptyHint(const QString& text) {
    hint_->setText(text);
    updateEmptyHint();
    requestReplot();
}

bool PlotPanel::waitsForData() const {
    return plot_->plottableCount() == 0 && !hint_->text().isEmpty();
}

void PlotPanel::updateEmptyHint() {
    const bool empty = waitsForData();
    if (empty) hint_->setGeometry(plot_->rect());
    hint_->setHidden(!empty);
}

void PlotPanel::requestReplot() {
    dirty_ = true;
}

void PlotPanel::offScreen(const std::function<void()>& work) {
    // The cursor's label is not part of a figure; a page is white whatever the screen shows.
    hideTracer();
    onPage_ = true;
    setDarkInk(*plot_, false);
    const QSize shown = plot_->size();
    const QRect viewport = plot_->viewport();
    const double ratio = plot_->bufferDevicePixelRatio();
    auto back = [&] {
        drawnFor(shown);
        // The work laid the plot out on a page of its own: its size, viewport and paint buffers
        // go back to the screen's, and the figure is refitted to them (a new size starts afresh,
        // so the screen shows what it showed).
        plot_->resize(shown);
        plot_->setViewport(viewport);
        plot_->setBufferDevicePixelRatio(ratio);
        onPage_ = false;
        plot_->replot(QCustomPlot::rpImmediateRefresh);
        for (int round = 0; round < kLayoutRounds && !zoomed_ && fitToLayout(*plot_); ++round)
            plot_->replot(QCustomPlot::rpImmediateRefresh);
        plot_->update();
    };
    try {
        work();
    } catch (...) {
        back();
        throw;
    }
    back();
}

void PlotPanel::drawnFor(QSize shape) {
    if (!rebuild_) return;
    plot_->resize(shape);
    rebuild_(*plot_);
}

QStringList PlotPanel::exportTo(const QString& basePath, const QStringList& formats,
                                const FigureSize& size) {
    QStringList files;
    offScreen([&] {
        drawnFor(layoutSize(*plot_, size));
        files = exportFigure(*plot_, basePath, formats, size);
    });
    return files;
}

FigureSize PlotPanel::usualSize() const {
    for (const RunFigure& figure : runFigures())
        if (name_ == figure.file) return figure.size;
    if (name_ == "seed_rates") return kSeedFigureSize;
    if (name_ == "compare") return kComparisonFigureSize;
    if (name_ == "compare_trial_pair") return kTrialPairFigureSize;
    if (name_.startsWith("seeds_sweep"))
        return FigureSize::physical(kDoubleColumn_mm, 120, kFigureDpi);
    // A plot with no figure of its own keeps the screen's shape at a double column.
    const double shape = plot_->width() > 0 ? double(plot_->height()) / plot_->width() : 0.7;
    return FigureSize::physical(kDoubleColumn_mm, kDoubleColumn_mm * std::clamp(shape, 0.2, 2.0),
                                kFigureDpi);
}

double PlotPanel::ownHeightAt(double widthMm) {
    const FigureSize usual = usualSize();
    double height = usual.height_mm;
    offScreen([&] {
        drawnFor(layoutSize(*plot_, FigureSize::physical(widthMm, usual.height_mm, usual.dpi)));
        const std::function<void()> screenFonts = setJournalText(*plot_);
        height = figureSizeFor(*plot_, usual, widthMm).height_mm;
        screenFonts();
    });
    return height;
}

void PlotPanel::exportCsv(const QString& path) const {
    QByteArray bytes;
    QTextStream out(&bytes);
    auto field = [](QString text) {
        text.replace('"', "\"\"");
        return text.contains(',') || text.contains('"') || text.contains('\n') ? '"' + text + '"'
                                                                               : text;
    };
    out << "panel,series,x_quantity,x_unit,x,y_quantity,y_unit,y,value_quantity,value_unit,value\n";
    for (int i = 0; i < plot_->plottableCount(); ++i) {
        QCPAbstractPlottable* p = plot_->plottable(i);
        if (!p->keyAxis() || !p->valueAxis()) continue;
        QCPAxisRect* rect = p->keyAxis()->axisRect();
        const QString panel = rect->axis(QCPAxis::atTop)->label();
        const QString series =
            seriesName(p).isEmpty() ? QString("series %1").arg(i) : seriesName(p);
        const auto [xName, xUnit] = quantityOf(p->keyAxis()->label());
        const auto [yName, yUnit] = quantityOf(p->valueAxis()->label());
        const QString head = field(panel) + ',' + field(series) + ',';
        const QString xHead = field(xName) + ',' + field(xUnit) + ',';
        const QString yHead = field(yName) + ',' + field(yUnit) + ',';
        auto row = [&](double x, double y) {
            out << head << xHead << numberText(x) << ',' << yHead << numberText(y) << ",,,\n";
        };
        if (auto* g = qobject_cast<QCPGraph*>(p)) {
            for (auto it = g->data()->constBegin(); it != g->data()->constEnd(); ++it)
                if (!qIsNaN(it->value)) row(it->key, it->value);
        } else if (auto* c = qobject_cast<QCPCurve*>(p)) {
            for (auto it = c->data()->constBegin(); it != c->data()->constEnd(); ++it)
                if (!qIsNaN(it->value)) row(it->key, it->value);
        } else if (auto* b = qobject_cast<QCPBars*>(p)) {
            for (auto it = b->data()->constBegin(); it != b->data()->constEnd(); ++it)
                row(it->key, it->value);
        } else if (auto* m = qobject_cast<QCPColorMap*>(p)) {
            const QString scale = m->colorScale() ? m->colorScale()->axis()->label() : QString();
            const auto [vName, vUnit] = quantityOf(scale);
            QCPColorMapData* d = m->data();
            for (int x = 0; x < d->keySize(); ++x)
                for (int y = 0; y < d->valueSize(); ++y) {
                    double kx, vy;
                    d->cellToCoord(x, y, &kx, &vy);
                    out << head << xHead << numberText(kx) << ',' << yHead << numberText(vy) << ','
                        << field(vName.isEmpty() ? QString("value") : vName) << ',' << field(vUnit)
                        << ',' << numberText(d->cell(x, y)) << '\n';
                }
        } else if (auto* e = qobject_cast<QCPErrorBars*>(p)) {
            // The half-width of each error bar, at its point of the series it belongs to.
            QCPAbstractPlottable* of = e->dataPlottable();
            auto* points = of ? dynamic_cast<QCPPlottableInterface1D*>(of) : nullptr;
            for (int k = 0; k < e->dataCount(); ++k) {
                const double x = points && k < points->dataCount() ? points->dataMainKey(k) : k;
                const double y = points && k < points->dataCount() ? points->dataMainValue(k) : 0;
                out << head << xHead << numberText(x) << ',' << yHead << numberText(y) << ','
                    << "error (half-width)," << field(yUnit) << ','
                    << numberText(e->data()->at(k).errorPlus) << '\n';
            }
        }
    }
    out.flush();
    writeWholeOrThrow(path, bytes);
}

void PlotPanel::copyToClipboard() {
    // The clipboard takes the figure as a page shows it: light, whatever the screen's theme.
    QPixmap figure;
    offScreen([&] { figure = plot_->toPixmap(); });
    QApplication::clipboard()->setPixmap(figure);
}

namespace {
QString& exportFolder() {
    static QString folder;
    return folder;
}
}  // namespace

void PlotPanel::setExportFolder(const QString& folder) {
    exportFolder() = folder;
}

QString PlotPanel::suggestedPath(const QString& extension) const {
    const QString file = name_ + "." + extension;
    const QString& folder = exportFolder();
    return folder.isEmpty() ? file : QDir(folder).filePath(file);
}

void PlotPanel::showMenu(const QPoint& where) {
    QMenu menu(this);
    menu.addAction(tr("Export figure..."), this, &PlotPanel::exportWithDialog);
    menu.addAction(tr("Copy to clipboard"), this, [this] {
        copyToClipboard();
        emit exported(tr("%1 copied to the clipboard").arg(name_));
    });
    menu.addAction(tr("Export data as CSV..."), this, [this] {
        const QString path =
            QFileDialog::getSaveFileName(this, tr("Export the data behind %1").arg(name_),
                                         suggestedPath("csv"), tr("CSV (*.csv)"));
        if (path.isEmpty()) return;
        try {
            exportCsv(path);
            emit exported(tr("%1 data written to %2").arg(name_, path));
        } catch (const std::exception& e) {
            emit failed(QString::fromStdString(e.what()));
        }
    });
    menu.exec(plot_->mapToGlobal(where));
}

void PlotPanel::exportWithDialog() {
    ExportDialog dialog(
        name_, [this](double widthMm) { return ownHeightAt(widthMm); }, this);
    if (dialog.exec() != QDialog::Accepted) return;
    const QString format = dialog.format();
    const QString path =
        QFileDialog::getSaveFileName(this, tr("Export %1").arg(name_), suggestedPath(format));
    if (path.isEmpty()) return;
    QString base = path;
    if (base.endsWith("." + format)) base.chop(format.size() + 1);
    try {
        const QStringList files = exportTo(base, {format}, dialog.size());
        emit exported(tr("%1 written to %2").arg(name_, files.join(", ")));
    } catch (const std::exception& e) {
        emit failed(QString::fromStdString(e.what()));
    }
}

}  // namespace activetouch
