#include "app/gui/PlotPanel.h"

#include <QApplication>
#include <QClipboard>
#include <QComboBox>
#include <QDialog>
#include <QDialogButtonBox>
#include <QFileDialog>
#include <QFormLayout>
#include <QMenu>
#include <QSpinBox>
#include <QTextStream>
#include <QVBoxLayout>
#include <stdexcept>

#include "app/gui/WholeFile.h"
#include "qcustomplot.h"

namespace activetouch {

PlotPanel::PlotPanel(const QString& name, QWidget* parent)
    : QWidget(parent), name_(name), plot_(new QCustomPlot(this)), hint_(new QLabel(plot_)) {
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->addWidget(plot_);
    plot_->setContextMenuPolicy(Qt::CustomContextMenu);
    plot_->setNoAntialiasingOnDrag(true);
    connect(plot_, &QWidget::customContextMenuRequested, this, &PlotPanel::showMenu);
    hint_->setObjectName("emptyHint");
    hint_->setAlignment(Qt::AlignCenter);
    hint_->setWordWrap(true);
    hint_->setAttribute(Qt::WA_TransparentForMouseEvents);  // the context menu still works
    hint_->setStyleSheet("QLabel { color: #606060; font-size: 12pt; padding: 40px; }");
    hint_->hide();
    connect(plot_, &QCustomPlot::afterReplot, this, &PlotPanel::updateEmptyHint);
    // An empty figure shows its hint alone: no bare 0..5 axis frame behind the words.
    connect(plot_, &QCustomPlot::beforeReplot, this, [this] {
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
    // Equal-aspect panels and legends under panels follow the plot's size: once a layout shows a
    // panel's shape or a legend's room has changed, they are refitted and the plot drawn again.
    // New tick labels can move the margins and so the shape again; a few rounds settle it, and
    // more are never asked for.
    connect(plot_, &QCustomPlot::afterLayout, this, [this] {
        if (!fitToLayout(*plot_)) {
            refits_ = 0;
            return;
        }
        if (++refits_ <= 3) plot_->replot(QCustomPlot::rpQueuedReplot);
    });
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

QStringList PlotPanel::exportTo(const QString& basePath, const QStringList& formats,
                                const FigureSize& size) {
    // Export at the requested size, then restore the on-screen layout.
    const QSize shown = plot_->size();
    QStringList files;
    try {
        files = exportFigure(*plot_, basePath, formats, size);
    } catch (...) {
        plot_->resize(shown);
        plot_->replot(QCustomPlot::rpImmediateRefresh);
        throw;
    }
    plot_->resize(shown);
    plot_->replot(QCustomPlot::rpImmediateRefresh);
    return files;
}

void PlotPanel::exportCsv(const QString& path) const {
    QByteArray bytes;
    QTextStream out(&bytes);
    out << "plottable,name,x,y,value\n";
    for (int i = 0; i < plot_->plottableCount(); ++i) {
        QCPAbstractPlottable* p = plot_->plottable(i);
        const QString name = QString(p->name()).replace(',', ';');
        if (auto* g = qobject_cast<QCPGraph*>(p)) {
            for (auto it = g->data()->constBegin(); it != g->data()->constEnd(); ++it)
                if (!qIsNaN(it->value))
                    out << i << ',' << name << ',' << it->key << ',' << it->value << ",\n";
        } else if (auto* c = qobject_cast<QCPCurve*>(p)) {
            for (auto it = c->data()->constBegin(); it != c->data()->constEnd(); ++it)
                out << i << ',' << name << ',' << it->key << ',' << it->value << ",\n";
        } else if (auto* b = qobject_cast<QCPBars*>(p)) {
            for (auto it = b->data()->constBegin(); it != b->data()->constEnd(); ++it)
                out << i << ',' << name << ',' << it->key << ",," << it->value << '\n';
        } else if (auto* m = qobject_cast<QCPColorMap*>(p)) {
            QCPColorMapData* d = m->data();
            for (int x = 0; x < d->keySize(); ++x)
                for (int y = 0; y < d->valueSize(); ++y) {
                    double kx, vy;
                    d->cellToCoord(x, y, &kx, &vy);
                    out << i << ',' << name << ',' << kx << ',' << vy << ',' << d->cell(x, y)
                        << '\n';
                }
        } else if (auto* e = qobject_cast<QCPErrorBars*>(p)) {
            for (int k = 0; k < e->dataCount(); ++k)
                out << i << ",error bars,," << ',' << e->data()->at(k).errorPlus << '\n';
        }
    }
    out.flush();
    const QString failed = writeFileWhole(path, bytes);
    if (!failed.isEmpty())
        throw std::runtime_error("could not write " + path.toStdString() + " (" +
                                 failed.toStdString() +
                                 "); free space on its disk or choose a writable place");
}

void PlotPanel::copyToClipboard() {
    QApplication::clipboard()->setPixmap(plot_->toPixmap());
}

void PlotPanel::showMenu(const QPoint& where) {
    QMenu menu(this);
    menu.addAction(tr("Export figure..."), this, &PlotPanel::exportWithDialog);
    menu.addAction(tr("Copy to clipboard"), this, [this] {
        copyToClipboard();
        emit exported(tr("%1 copied to the clipboard").arg(name_));
    });
    menu.addAction(tr("Export data as CSV..."), this, [this] {
        const QString path = QFileDialog::getSaveFileName(
            this, tr("Export the data behind %1").arg(name_), name_ + ".csv", tr("CSV (*.csv)"));
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
    QDialog dialog(this);
    dialog.setWindowTitle(tr("Export %1").arg(name_));
    auto* form = new QFormLayout(&dialog);
    auto* format = new QComboBox;
    format->addItems({"png", "pdf", "svg"});
    auto* width = new QSpinBox;
    width->setRange(200, 10000);
    width->setValue(1600);
    width->setSuffix(" px");
    auto* height = new QSpinBox;
    height->setRange(200, 10000);
    height->setValue(1100);
    height->setSuffix(" px");
    auto* dpi = new QSpinBox;
    dpi->setRange(50, 1200);
    dpi->setValue(150);
    form->addRow(tr("Format"), format);
    form->addRow(tr("Width"), width);
    form->addRow(tr("Height"), height);
    form->addRow(tr("Resolution (DPI)"), dpi);
    auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel);
    form->addRow(buttons);
    connect(buttons, &QDialogButtonBox::accepted, &dialog, &QDialog::accept);
    connect(buttons, &QDialogButtonBox::rejected, &dialog, &QDialog::reject);
    if (dialog.exec() != QDialog::Accepted) return;
    const QString path = QFileDialog::getSaveFileName(this, tr("Export %1").arg(name_),
                                                      name_ + "." + format->currentText());
    if (path.isEmpty()) return;
    QString base = path;
    if (base.endsWith("." + format->currentText())) base.chop(format->currentText().size() + 1);
    try {
        const QStringList files = exportTo(base, {format->currentText()},
                                           {width->value(), height->value(), dpi->value()});
        emit exported(tr("%1 written to %2").arg(name_, files.join(", ")));
    } catch (const std::exception& e) {
        emit failed(QString::fromStdString(e.what()));
    }
}

}  // namespace activetouch
