// The window as a desktop application (docs/window.md): it fits a laptop screen, every menu
// action answers its shortcut, plots can be explored, the live view pauses and draws the
// fingertip, a device failure shows on its panel, and the results folder is a preference.
#include <QDesktopServices>
#include <QDockWidget>
#include <QMenuBar>
#include <QMimeData>
#include <QTabWidget>
#include <QTextBrowser>
#include <QToolBar>
#include <QUrl>
#include <QWheelEvent>

#include "WindowFixture.h"
#include "app/figures/FigureFitting.h"
#include "app/gui/FingertipView.h"
#include "app/gui/HelpBrowser.h"
#include "support/BoxText.h"

/// Records the file URLs the window asks the desktop to open, instead of opening them.
class UrlCatcher : public QObject {
    Q_OBJECT
public:
    QList<QUrl> opened;
public slots:
    void open(const QUrl& url) { opened << url; }
};

class TestWindowDesktop : public WindowFixture {
    Q_OBJECT
    UrlCatcher urls_;

    /// Presses `keys` on the window; a modal dialog it opens is recorded and closed. Returns the
    /// dialog's title, or an empty string if none opened.
    QString pressExpectingDialog(const QKeySequence& keys) {
        QString title;
        QTimer poll;
        poll.setInterval(20);
        connect(&poll, &QTimer::timeout, this, [&] {
            if (QWidget* modal = QApplication::activeModalWidget()) {
                title = modal->windowTitle();
                if (auto* d = qobject_cast<QDialog*>(modal))
                    d->reject();
                else
                    modal->close();
            }
        });
        poll.start();
        press(keys);
        QTest::qWait(50);
        return title;
    }
    void press(const QKeySequence& keys) {
        window_->activateWindow();
        QVERIFY(QTest::qWaitForWindowActive(window_.get()));
        QTest::keySequence(window_.get(), keys);
    }
    QAction* action(const char* name) { return window_->findChild<QAction*>(name); }
    QString writeRig(const QString& name, const QByteArray& text) {
        QFile f(dir_.filePath(name));
        if (f.open(QIODevice::WriteOnly)) f.write(text);
        return f.fileName();
    }

private slots:
    void initTestCase() {
        QDesktopServices::setUrlHandler("file", &urls_, "open");
        openWindow();
    }
    void cleanupTestCase() {
        closeWindow();
        QDesktopServices::unsetUrlHandler("file");
    }

    void helpInsideTheWindow() {
        // F1 on a tab opens docs/window.md at that tab's section, rendered from its Markdown.
        auto* tabs = window_->findChild<QTabWidget*>();
        QVERIFY(tabs);
        int validation = -1;
        for (int i = 0; i < tabs->count(); ++i)
            if (tabs->tabText(i).startsWith("Training")) validation = i;
        QVERIFY(validation >= 0);
        tabs->setCurrentIndex(validation);
        press(QKeySequence::HelpContents);
        auto* help = window_->findChild<HelpBrowser*>("helpBrowser");
        QVERIFY(help && help->isVisible());
        QTextBrowser* text = help->browser();
        QVERIFY(text->source().toLocalFile().endsWith("docs/window.md"));
        QVERIFY(!text->toPlainText().contains("**"));  // rendered, not shown as source
        QCOMPARE(text->textCursor().selectedText(), QString("Training & validation:"));
        // A link followed in place: the keyboard selects the first link and opens it.
        text->setFocus();
        QTextCursor start(text->document());
        text->setTextCursor(start);
        QTest::keyClick(text, Qt::Key_Tab);
        const QString link = text->textCursor().charFormat().anchorHref();
        QVERIFY2(link.endsWith(".md"), qPrintable(link));
        QTest::keyClick(text, Qt::Key_Return);
        QTRY_VERIFY(text->source().toLocalFile().endsWith(QFileInfo(link).fileName()));
        QVERIFY(text->isBackwardAvailable());
        // A search over every document lists its hits and opens the first, found in place.
        auto* search = help->findChild<QLineEdit*>("helpSearch");
        QVERIFY(search);
        QTest::keyClicks(search, "Kolmogorov");
        QTest::keyClick(search, Qt::Key_Return);
        QVERIFY(help->hits()->count() >= 3);
        QVERIFY(help->hits()->item(0)->text().contains(".md:"));
        QCOMPARE(text->textCursor().selectedText().toLower(), QString("kolmogorov"));
        QCOMPARE(help->search("no such words anywhere at all"), 0);
        help->close();
        window_->activateWindow();
        QVERIFY(QTest::qWaitForWindowActive(window_.get()));
        tabs->setFocus();
    }

    void theWindowFitsA1280x720Screen() {
        for (QDockWidget* dock : window_->findChildren<QDockWidget*>()) {
            dock->show();
            QVERIFY(dock->isVisible());
        }
        // Every dock in its own area too, none tabified: still no larger.
        const QSize least = window_->layout()->minimumSize().expandedTo(window_->minimumSize());
        qInfo("the window's minimum size with every dock shown: %dx%d", least.width(),
              least.height());
        QVERIFY2(least.width() <= 1280 && least.height() <= 720,
                 qPrintable(QString("%1x%2").arg(least.width()).arg(least.height())));
        window_->resize(1280, 720);
        QTRY_COMPARE(window_->size(), QSize(1280, 720));
        QVERIFY(window_->statusBar()->isVisible());
        QVERIFY(window_->statusBar()->geometry().bottom() < 720);
        // Connecting devices does not widen the Devices dock: its long states wrap.
        auto* devices = window_->findChild<QDockWidget*>("devicesDock");
        devices->raise();
        const int before = devices->width();
        QTest::mouseClick(window_->findChild<QPushButton*>("connectDevices"), Qt::LeftButton);
        QTRY_VERIFY(window_->findChild<QLabel*>("stagePosition")->text().startsWith("x "));
        QCoreApplication::processEvents();
        QCOMPARE(devices->width(), before);
        QTest::mouseClick(window_->findChild<QPushButton*>("connectDevices"), Qt::LeftButton);
        QTRY_COMPARE(window_->findChild<QLabel*>("tapperState")->text(), QString("disconnected"));
        window_->resize(1600, 1000);
    }

    void theKeysAreTheOnesTheDocsList() {
        // Each row of docs/window.md's table: a menu, its entries and their keys, in order.
        QFile doc(sourceFile("docs/window.md"));
        QVERIFY(doc.open(QIODevice::ReadOnly | QIODevice::Text));
        auto plain = [](QString text) {
            text.replace("&&", "\x01").remove('&').replace("\x01", "&");
            return text;
        };
        int checked = 0;
        QStringList menusSeen;
        for (const QString& line : QString::fromUtf8(doc.readAll()).split('\n')) {
            const QStringList cells = line.split('|');
            if (cells.size() != 5 || !cells[1].trimmed().front().isUpper()) continue;
            const QString menuName = cells[1].trimmed();
            if (menuName == "menu") continue;
            QMenu* menu = nullptr;
            for (QAction* top : window_->menuBar()->actions())
                if (plain(top->text()) == menuName) menu = top->menu();
            QVERIFY2(menu, qPrintable("no menu " + menuName));
            menusSeen << menuName;
            const QStringList entries = cells[2].split(" / "), keys = cells[3].split(" / ");
            QCOMPARE(entries.size(), keys.size());
            for (int i = 0; i < entries.size(); ++i) {
                // "About ActiveTouch Workbench (the version, ...)": the entry is before " (".
                const QString entry = entries[i].trimmed().section(" (", 0, 0);
                const QAction* found = nullptr;
                for (const QAction* a : menu->actions())
                    if (plain(a->text()) == entry) found = a;
                QVERIFY2(found, qPrintable(menuName + " has no entry " + entry));
                const QString key = keys[i].trimmed();
                const QString want = key == "—" ? QString() : QKeySequence(key).toString();
                QVERIFY2(found->shortcut().toString() == want,
                         qPrintable(QString("%1 > %2: %3, the docs say %4")
                                        .arg(menuName, entry, found->shortcut().toString(), want)));
                ++checked;
            }
        }
        menusSeen.removeDuplicates();
        QCOMPARE(menusSeen, QStringList({"File", "Run", "View", "Help"}));
        QVERIFY2(checked >= 25, qPrintable(QString::number(checked)));
        // Ctrl+1 is the first dock the docs list.
        QCOMPARE(window_->findChild<QDockWidget*>("sceneDock")->toggleViewAction()->shortcut(),
                 QKeySequence("Ctrl+1"));
    }

    void everyMenuActionAnswersItsShortcut() {
        // A copy of the paper experiment, so that Save has a file of its own to write.
        const QString copy = paperVariant("paper_copy.json", R"("name": "paper copy")");
        QVERIFY(window_->openExperiment(copy));
        QStringList pressed;
        auto key = [&](const char* name) {
            QAction* a = action(name);
            if (!a) qFatal("no action %s", name);
            pressed << name;
            return a->shortcut();
        };
        auto dialogOf = [&](const char* name) { return pressExpectingDialog(key(name)); };

        // File
        QCOMPARE(dialogOf("menuOpen"), QString("Open an experiment"));
        QCOMPARE(dialogOf("menuSaveAs"), QString("Save the experiment"));
        QCOMPARE(dialogOf("menuOpenRig"), QString("Open rig file"));
        QCOMPARE(dialogOf("menuPreferences"), QString("Preferences"));
        // Without a run there is nothing to export: the action waits for one.
        QVERIFY(!action("menuExportAll")->isEnabled());
        const QDateTime before = QFileInfo(copy).lastModified();
        QTest::qWait(20);
        QFile::remove(copy);
        press(key("menuSave"));
        QVERIFY(QFileInfo::exists(copy));
        QVERIFY(QFileInfo(copy).lastModified() >= before);
        QCOMPARE(loadExperiment(copy.toStdString()).name, std::string("paper copy"));
        urls_.opened.clear();
        press(key("menuResultsFolder"));
        QCOMPARE(urls_.opened.size(), 1);
        QCOMPARE(QDir(urls_.opened.front().toLocalFile()).absolutePath(),
                 QDir(window_->outputBase()).absolutePath());

        // Run: F5 starts the whole protocol and Esc cancels it; F6 trains; F7 follows with it;
        // F8 runs over the seeds the tab shows; F9 asks for B.
        window_->setPace(Pace::LiveFrames);
        QSignalSpy ended(window_.get(), &MainWindow::runEnded);
        press(key("runAll"));
        QVERIFY(window_->running());
        press(key("cancel"));
        QVERIFY(ended.wait(30000));
        QTRY_VERIFY(!window_->running());
        window_->setPace(Pace::Fastest);
        press(key("runTraining"));
        QVERIFY(window_->running());
        endsSuccessfully(*window_, ended);
        QVERIFY(window_->lastRun() && window_->lastRun()->trials.empty());
        press(key("runFollowing"));
        QVERIFY(window_->running());
        press(Qt::Key_Escape);
        QVERIFY(ended.wait(30000));
        QTRY_VERIFY(!window_->running());
        press(key("menuRunSeeds"));
        QVERIFY(window_->running());
        QCOMPARE(window_->tabs()->currentWidget(), window_->seedsTab());
        press(Qt::Key_Escape);
        QVERIFY(ended.wait(60000));
        QTRY_VERIFY(!window_->running());
        QCOMPARE(dialogOf("menuCompare"), QString("Compare with the experiment (B)"));
        QCOMPARE(dialogOf("analyseRecording"), QString("Analyse recorded training and test taps"));
        QCOMPARE(dialogOf("replayRun"), QString("Replay the run recorded in (a run's folder)"));
        QCOMPARE(dialogOf("calibrate"),
                 QString("Fit the scene to recorded training and test taps"));
        QCOMPARE(dialogOf("menuExportAll"), QString("Export all figures into"));  // a run now

        // View: each dock and the tool bar hide and come back; the live view pauses.
        for (QDockWidget* dock : window_->findChildren<QDockWidget*>()) {
            const QByteArray name = (dock->objectName() + "Toggle").toUtf8();
            const QKeySequence keys = key(name.constData());
            QVERIFY(!dock->isHidden());
            press(keys);
            QVERIFY2(dock->isHidden(), name.constData());
            press(keys);
            QVERIFY2(!dock->isHidden(), name.constData());
        }
        auto* bar = window_->findChild<QToolBar*>("runToolBar");
        press(key("runToolBarToggle"));
        QVERIFY(bar->isHidden());
        press(key("menuPauseLive"));
        QVERIFY(window_->liveView()->paused());
        press(key("menuPauseLive"));
        QVERIFY(!window_->liveView()->paused());
        window_->findChild<QDockWidget*>("logDock")->hide();
        press(key("menuResetLayout"));
        QVERIFY(!bar->isHidden());
        for (QDockWidget* dock : window_->findChildren<QDockWidget*>()) QVERIFY(!dock->isHidden());

        // Help: the documentation inside the window, at the section on the tab in front
        // (helpInsideTheWindow follows its links and searches it).
        urls_.opened.clear();
        press(key("menuDocs"));
        QVERIFY(urls_.opened.isEmpty());
        auto* help = window_->findChild<HelpBrowser*>("helpBrowser");
        QVERIFY(help && help->isVisible());
        QVERIFY(help->browser()->source().toLocalFile().endsWith("docs/window.md"));
        help->close();
        QCOMPARE(dialogOf("menuAbout"), QString("About ActiveTouch Workbench"));
        QCOMPARE(dialogOf("menuAboutQt"), QString("About Qt"));

        // Every action in the menus has a shortcut, and each was pressed above (Quit last).
        QStringList inMenus;
        for (QAction* top : window_->menuBar()->actions())
            for (QAction* a : top->menu()->actions()) {
                if (a->isSeparator() || a->menu()) continue;  // Open recent is a list of files
                QVERIFY2(!a->shortcut().isEmpty(), qPrintable(a->text()));
                inMenus << a->objectName();
            }
        inMenus.removeAll("menuQuit");
        for (const QString& name : inMenus) QVERIFY2(pressed.contains(name), qPrintable(name));
        QVERIFY(window_->recentExperiments().contains(QFileInfo(copy).absoluteFilePath()));
    }

    void anUnsavedEditIsNotLostWithoutAsking() {
        const QString copy = dir_.filePath("paper_copy.json");
        QVERIFY(window_->openExperiment(copy));
        QVERIFY(!window_->hasUnsavedEdits());
        QVERIFY(!window_->isWindowModified());
        auto* follow = protocolField<QDoubleSpinBox>("following_follow_step_mm");
        QVERIFY(follow);
        follow->setValue(follow->value() + 1.0);
        emit follow->editingFinished();
        QVERIFY(window_->hasUnsavedEdits());
        QTRY_VERIFY(window_->isWindowModified());
        // Open asks first; Cancel keeps the edit and the experiment.
        QCOMPARE(pressExpectingDialog(action("menuOpen")->shortcut()), QString("Unsaved changes"));
        QVERIFY(window_->hasUnsavedEdits());
        QCOMPARE(window_->experimentPath(), copy);
        // Dropping an experiment asks too.
        QString asked;
        QTimer poll;
        poll.setInterval(20);
        connect(&poll, &QTimer::timeout, this, [&] {
            if (auto* box = qobject_cast<QMessageBox*>(QApplication::activeModalWidget())) {
                asked = box->windowTitle();
                box->button(QMessageBox::Discard)->click();
            }
        });
        poll.start();
        QVERIFY(window_->openDropped(sourceFile("experiments/paper.json")));
        poll.stop();
        QCOMPARE(asked, QString("Unsaved changes"));
        QCOMPARE(window_->experimentPath(), sourceFile("experiments/paper.json"));
        QVERIFY(!window_->hasUnsavedEdits());
    }

    void filesDroppedOnTheWindowOpenAsWhatTheyAre() {
        // A rig file sets the device pickers; a recording is analysed; an unknown file is refused.
        const QString rig = dir_.filePath("dropped_rig.json");
        QFile f(rig);
        QVERIFY(f.open(QIODevice::WriteOnly));
        f.write(R"({"stage": {"device": "yamaha", "port": "/dev/ttyUSB7"}})");
        f.close();
        QMimeData mime;
        mime.setUrls({QUrl::fromLocalFile(rig)});
        QDragEnterEvent enter(QPoint(20, 20), Qt::CopyAction, &mime, Qt::LeftButton,
                              Qt::NoModifier);
        QCoreApplication::sendEvent(window_.get(), &enter);
        QVERIFY(enter.isAccepted());
        QDropEvent drop(QPointF(20, 20), Qt::CopyAction, &mime, Qt::LeftButton, Qt::NoModifier);
        QCoreApplication::sendEvent(window_.get(), &drop);
        auto* devices = window_->findChild<DevicesPanel*>();
        QTRY_COMPARE(devices->choice().config.yamaha.serial.portName, std::string("/dev/ttyUSB7"));
        QVERIFY(devices->openRigFile(
            writeRig("sim_again.json", R"({"stage": {"device": "simulated"}})")));
        const QString other = dir_.filePath("notes.txt");
        QFile t(other);
        QVERIFY(t.open(QIODevice::WriteOnly));
        t.close();
        QMimeData text;
        text.setUrls({QUrl::fromLocalFile(other)});
        QDragEnterEvent refused(QPoint(20, 20), Qt::CopyAction, &text, Qt::LeftButton,
                                Qt::NoModifier);
        refused.setAccepted(false);
        QCoreApplication::sendEvent(window_.get(), &refused);
        QVERIFY(!refused.isAccepted());
    }

    void plotsZoomPanResetAndTraceTheValueUnderTheCursor() {
        PlotPanel panel("test_plot");
        QCustomPlot& plot = panel.plot();
        QCPGraph* g = plot.addGraph();
        g->setName("taxel 3");
        QVector<double> x, y;
        for (int i = 0; i <= 50; ++i) {
            x << i * 0.02;
            y << 100.0 + i;
        }
        g->setData(x, y);
        plot.xAxis->setLabel("time in the tap (s)");
        plot.yAxis->setLabel("pressure (counts)");
        plot.xAxis->setRange(0, 1);
        plot.yAxis->setRange(0, 255);
        panel.resize(800, 500);
        panel.show();
        QVERIFY(QTest::qWaitForWindowExposed(&panel));
        plot.replot(QCustomPlot::rpImmediateRefresh);
        const QCPRange homeX = plot.xAxis->range(), homeY = plot.yAxis->range();
        const QPointF centre = plot.axisRect()->rect().center();

        // The wheel zooms in about the cursor.
        QWheelEvent wheel(centre, plot.mapToGlobal(centre), QPoint(), QPoint(0, 240), Qt::NoButton,
                          Qt::NoModifier, Qt::NoScrollPhase, false);
        QCoreApplication::sendEvent(&plot, &wheel);
        QVERIFY(plot.xAxis->range().size() < homeX.size());
        QVERIFY(plot.yAxis->range().size() < homeY.size());
        QVERIFY(panel.isZoomed());
        // A drag pans: the axes move with the mouse.
        const QCPRange zoomedX = plot.xAxis->range();
        QMouseEvent press(QEvent::MouseButtonPress, centre, plot.mapToGlobal(centre),
                          Qt::LeftButton, Qt::LeftButton, Qt::NoModifier);
        QCoreApplication::sendEvent(&plot, &press);
        const QPointF to = centre + QPointF(100, 0);
        QMouseEvent move(QEvent::MouseMove, to, plot.mapToGlobal(to), Qt::NoButton, Qt::LeftButton,
                         Qt::NoModifier);
        QCoreApplication::sendEvent(&plot, &move);
        QMouseEvent release(QEvent::MouseButtonRelease, to, plot.mapToGlobal(to), Qt::LeftButton,
                            Qt::NoButton, Qt::NoModifier);
        QCoreApplication::sendEvent(&plot, &release);
        QVERIFY2(plot.xAxis->range().lower < zoomedX.lower - 1e-6,
                 qPrintable(QString("%1 -> %2").arg(zoomedX.lower).arg(plot.xAxis->range().lower)));
        QCOMPARE(plot.xAxis->range().size(), zoomedX.size());
        // A double-click goes back to the plot's own ranges.
        QTest::mouseDClick(&plot, Qt::LeftButton, Qt::NoModifier, centre.toPoint());
        QCOMPARE(plot.xAxis->range().lower, homeX.lower);
        QCOMPARE(plot.xAxis->range().upper, homeX.upper);
        QCOMPARE(plot.yAxis->range().lower, homeY.lower);
        QCOMPARE(plot.yAxis->range().upper, homeY.upper);
        QVERIFY(!panel.isZoomed());

        // The value under the cursor: the graph's point nearest it, named with its units.
        plot.replot(QCustomPlot::rpImmediateRefresh);
        const QPointF at(plot.xAxis->coordToPixel(0.5), plot.yAxis->coordToPixel(125.0));
        QTest::mouseMove(&plot, at.toPoint());
        QTRY_VERIFY(!panel.cursorText().isEmpty());
        const QString text = panel.cursorText();
        QVERIFY2(text.contains("taxel 3") && text.contains("time in the tap 0.5 s") &&
                     text.contains("pressure 125 counts"),
                 qPrintable(text));
        // Away from the data, the axes' values there.
        const QPointF empty(plot.xAxis->coordToPixel(0.25), plot.yAxis->coordToPixel(20.0));
        QVERIFY(panel.traceAt(empty).contains("pressure 2"));
        // The CSV names each column's quantity and unit.
        const QString csv = dir_.filePath("test_plot.csv");
        panel.exportCsv(csv);
        QFile file(csv);
        QVERIFY(file.open(QIODevice::ReadOnly));
        QCOMPARE(file.readLine().trimmed(),
                 QByteArray("panel,series,x_quantity,x_unit,x,y_quantity,y_unit,y,value_quantity,"
                            "value_unit,value"));
        QCOMPARE(file.readLine().trimmed(),
                 QByteArray(",taxel 3,time in the tap,s,0,pressure,counts,100,,,"));
    }

    void readOutsNameCategoriesAndStayInsideThePlot() {
        PlotPanel panel("readout_plot");
        QCustomPlot& plot = panel.plot();
        QCPGraph* g = plot.addGraph();
        g->setName("error");
        g->setData({0, 1, 2, 3}, {3.14159265, 2718.2818, 0.000123456, 1.0 / 3.0});
        plot.xAxis->setLabel("orientation");
        QSharedPointer<QCPAxisTickerText> names(new QCPAxisTickerText);
        names->addTick(0, "left");
        names->addTick(1, "right\n(12 trials)");  // a name's first line
        names->addTick(2, "up");
        names->addTick(3, "down");
        plot.xAxis->setTicker(names);
        plot.yAxis->setLabel("position error (mm)");
        plot.xAxis->setRange(-0.5, 3.5);
        plot.yAxis->setRange(-100, 3000);
        panel.resize(640, 400);
        panel.show();
        QVERIFY(QTest::qWaitForWindowExposed(&panel));
        plot.replot(QCustomPlot::rpImmediateRefresh);
        auto pixel = [&](double x, double y) {
            return QPointF(plot.xAxis->coordToPixel(x), plot.yAxis->coordToPixel(y));
        };
        // Names, not numbers; four significant figures with the unit.
        QString text = panel.traceAt(pixel(0, 3.14159265));
        QVERIFY2(text.contains("orientation left") && text.contains("position error 3.142 mm"),
                 qPrintable(text));
        text = panel.traceAt(pixel(1, 2718.2818));
        QVERIFY2(text.contains("orientation right\n") && text.contains("error 2718 mm"),
                 qPrintable(text));
        QVERIFY(panel.traceAt(pixel(2, 0.000123456)).contains("error 0.0001235 mm"));
        // An axis naming its categories in a property reads them where no tick label does.
        plot.xAxis->setProperty(kCategoryNames, QStringList{"E", "NE", "N", "NW"});
        QVERIFY(panel.traceAt(pixel(3, 1.0 / 3.0)).contains("orientation NW"));
        // Hovered at each corner, the label lies whole inside the plot.
        const QRect r = plot.axisRect()->rect();
        auto* label = plot.findChild<QCPItemText*>("valueLabel");
        QVERIFY(label);
        for (const QPointF corner :
             {QPointF(r.right() - 2, r.bottom() - 2), QPointF(r.right() - 2, r.top() + 2),
              QPointF(r.left() + 2, r.top() + 2), QPointF(r.center())}) {
            panel.traceAt(corner);
            plot.replot(QCustomPlot::rpImmediateRefresh);
            const QRectF box(label->topLeft->pixelPosition(), label->bottomRight->pixelPosition());
            QVERIFY2(QRectF(plot.rect()).contains(box), qPrintable(QString("%1 hovered at (%2, %3)")
                                                                       .arg(boxText(box))
                                                                       .arg(corner.x())
                                                                       .arg(corner.y())));
        }
    }

    void plotsFollowADarkThemeAndExportOnWhite() {
        PlotPanel panel("dark_plot");
        QCustomPlot& plot = panel.plot();
        QCPGraph* g = plot.addGraph();
        g->setName("active");
        const QColor blue(31, 119, 180);
        g->setPen(QPen(blue, 2));
        g->setScatterStyle(QCPScatterStyle(QCPScatterStyle::ssCircle, Qt::black, Qt::white, 6));
        g->setData({0, 1, 2}, {1, 3, 2});
        plot.xAxis->setLabel("time (s)");
        plot.legend->setVisible(true);
        auto* note = new QCPItemText(&plot);
        note->setText("valid range");
        note->position->setCoords(1, 2.5);
        plot.rescaleAxes();
        panel.resize(500, 360);
        QPalette dark;
        dark.setColor(QPalette::Window, QColor(40, 40, 40));
        dark.setColor(QPalette::WindowText, QColor(230, 230, 230));
        dark.setColor(QPalette::Base, QColor(30, 30, 30));
        dark.setColor(QPalette::Text, QColor(230, 230, 230));
        panel.setPalette(dark);
        panel.show();
        QVERIFY(QTest::qWaitForWindowExposed(&panel));
        plot.replot(QCustomPlot::rpImmediateRefresh);
        auto lightness = [](const QColor& c) { return c.lightnessF(); };
        const QImage screen = plot.grab().toImage();
        // Dark ink: the page, the texts, the legend and the outlines turned; the series kept.
        QVERIFY2(lightness(screen.pixelColor(3, 3)) < 0.25,
                 qPrintable(screen.pixelColor(3, 3).name()));
        QVERIFY(lightness(plot.xAxis->labelColor()) > 0.8);
        QVERIFY(lightness(plot.xAxis->basePen().color()) > 0.8);
        QVERIFY(lightness(plot.legend->brush().color()) < 0.25);
        QVERIFY2(lightness(plot.legend->item(0)->textColor()) > 0.8,
                 qPrintable(plot.legend->item(0)->textColor().name()));
        QVERIFY(lightness(note->color()) > 0.8);
        QVERIFY(lightness(g->scatterStyle().pen().color()) > 0.8);
        QCOMPARE(g->pen().color(), blue);
        // A figure drawn anew (its page set white, a part added) is drawn dark too.
        plot.setBackground(Qt::white);
        auto* added = new QCPItemText(&plot);
        added->setText("added");
        added->position->setCoords(0.5, 1.5);
        plot.replot(QCustomPlot::rpImmediateRefresh);
        QVERIFY(lightness(plot.grab().toImage().pixelColor(3, 3)) < 0.25);
        QVERIFY(lightness(added->color()) > 0.8);
        plot.removeItem(added);
        plot.replot(QCustomPlot::rpImmediateRefresh);
        QCOMPARE(plot.grab().toImage(), screen);
        // An export is a white page in light ink, and leaves the screen as it was.
        const QString base = dir_.filePath("dark_plot");
        panel.exportTo(base, {"png"}, FigureSize::physical(89, 60, 150));
        const QImage page(base + ".png");
        QVERIFY(!page.isNull());
        QCOMPARE(page.pixelColor(2, 2), QColor(Qt::white));
        QCOMPARE(plot.grab().toImage(), screen);
        // A light palette again: every colour back exactly as the figure's code set it.
        panel.setPalette(QApplication::palette());
        QTRY_COMPARE(plot.xAxis->labelColor(), QColor(Qt::black));
        QCOMPARE(g->scatterStyle().pen().color(), QColor(Qt::black));
        QCOMPARE(g->scatterStyle().brush().color(), QColor(Qt::white));
        QCOMPARE(note->color(), QColor(Qt::black));
        QCOMPARE(plot.legend->brush().color(), QColor(Qt::white));
        QCOMPARE(plot.legend->item(0)->textColor(), QColor(Qt::black));
    }

    void theLiveViewPausesAndDrawsTheFingertip() {
        // The window's live view knows the scene's fingertip and its reflex threshold.
        const SceneSpec scene =
            loadExperiment(sourceFile("experiments/paper.json").toStdString()).scene;
        QCOMPARE(window_->liveView()->fingertipView()->contactThreshold(),
                 scene.tap.contactThreshold);

        LiveFeed feed;
        LiveView live(feed);
        live.setFingertip(scene.fingertip, scene.tap.contactThreshold);
        live.resize(1000, 700);
        live.show();
        QVERIFY(QTest::qWaitForWindowExposed(&live));
        auto shown = [&] {
            std::vector<double> v;
            for (int k = 0; k < kFingertipTaxels; ++k) {
                auto* bars = qobject_cast<QCPBars*>(live.barsPanel()->plot().plottable(k));
                v.push_back(bars->data()->constBegin()->value);
            }
            return v;
        };
        std::vector<double> frame(kFingertipTaxels, 0.0);
        frame[3] = 250.0;
        frame[7] = 120.0;
        feed.publishFrame(frame.data(), kFingertipTaxels);
        QTRY_COMPARE(shown(), frame);

        // The fingertip view: each taxel filled by its pressure on the fixed scale.
        FingertipView* tip = live.fingertipView();
        QCOMPARE(tip->fillOf(3), FingertipView::pressureColour(250.0));
        QCOMPARE(tip->fillOf(7), FingertipView::pressureColour(120.0));
        QCOMPARE(tip->fillOf(0), FingertipView::pressureColour(0.0));
        QVERIFY(tip->fillOf(3) != tip->fillOf(0));
        QCOMPARE(tip->total(), 370.0);
        // As drawn: beside the taxel's number, the disc has its fill colour.
        const QImage image = tip->grab().toImage();
        const QPointF c = tip->centreOf(3) + QPointF(0.6 * tip->discRadius(), 0);
        QCOMPARE(image.pixelColor(c.toPoint()), FingertipView::pressureColour(250.0));
        // Taxels sit where the fingertip has them: the tip taxel (11) nearest the top.
        for (int k = 0; k < 11; ++k) QVERIFY(tip->centreOf(11).y() < tip->centreOf(k).y());

        // Pause holds what is shown; Resume shows the newest frame.
        live.setPaused(true);
        std::vector<double> next(kFingertipTaxels, 40.0);
        feed.publishFrame(next.data(), kFingertipTaxels);
        QTest::qWait(100);
        QCOMPARE(shown(), frame);
        QCOMPARE(tip->fillOf(3), FingertipView::pressureColour(250.0));
        live.setPaused(false);
        QTRY_COMPARE(shown(), next);
        QTRY_COMPARE(tip->fillOf(3), FingertipView::pressureColour(40.0));

        // A training tap says the class it was taken on; only a following tap has a percept.
        TapRecord record;
        record.tap = Tap(50, kFingertipTaxels);
        feed.publishTap(record, "training set 1: 90° edge, position 3", false);
        QTRY_VERIFY(live.tapText().contains("training set 1"));
        QVERIFY(live.perceptText().isEmpty());
        feed.publishTap(record, "active rectangle trial 1: 90° edge, position 9 -> follow", true);
        QTRY_VERIFY(live.perceptText().contains("90° edge, position 9"));
    }

    void aDeviceFailureShowsOnItsPanel() {
        auto* devices = window_->findChild<QDockWidget*>("devicesDock");
        devices->raise();
        auto* jog = window_->findChild<QPushButton*>("jog+x");
        auto* testTap = window_->findChild<QPushButton*>("testTap");
        QVERIFY(!jog->isEnabled());  // nothing to jog while disconnected
        QVERIFY(!testTap->isEnabled());
        auto* stageKind = window_->findChild<QComboBox*>("stageKind");
        stageKind->setCurrentIndex(1);  // the Yamaha, on a port that is not there
        auto* port = window_->findChild<QComboBox*>("serialPort");
        port->setCurrentText(dir_.filePath("no-such-port"));
        QTest::mouseClick(window_->findChild<QPushButton*>("connectDevices"), Qt::LeftButton);
        auto* status = window_->findChild<QLabel*>("deviceStatus");
        QTRY_VERIFY_WITH_TIMEOUT(status->isVisible() && status->text().contains("no-such-port"),
                                 10000);
        QVERIFY2(status->styleSheet().contains("#b00020"), qPrintable(status->styleSheet()));
        QVERIFY(!jog->isEnabled());
        QCOMPARE(window_->findChild<QPushButton*>("connectDevices")->text(), QString("Connect"));
        // The pickers are kept for the next start.
        {
            DevicesPanel next(window_->findChild<DevicesPanel*>()->session());
            QCOMPARE(next.choice().config.stage, RigConfig::StageKind::Yamaha);
            QCOMPARE(QString::fromStdString(next.choice().config.yamaha.serial.portName),
                     dir_.filePath("no-such-port"));
        }
        stageKind->setCurrentIndex(0);
    }

    void theResultsFolderIsAPreference() {
        const QString folder = dir_.filePath("my results");
        window_->setResultsFolder(folder);
        QCOMPARE(QSettings().value("resultsFolder").toString(), QDir(folder).absolutePath());
        auto* label = window_->findChild<QLabel*>("resultsFolderLabel");
        QVERIFY2(label->text().contains(QDir(folder).absolutePath().toHtmlEscaped()),
                 qPrintable(label->text()));
        // Runs go there.
        QSignalSpy ended(window_.get(), &MainWindow::runEnded);
        QVERIFY(window_->startRun(RunController::What::TrainingOnly));
        endsSuccessfully(*window_, ended);
        QVERIFY2(window_->lastRunDirectory().startsWith(QDir(folder).absolutePath()),
                 qPrintable(window_->lastRunDirectory()));
        // Figure 6 exported for a single journal column from the window: drawn for that shape,
        // written at 89 mm and 300 dpi, and drawn for the screen again after.
        PlotPanel* errors = nullptr;
        for (PlotPanel* p : window_->plotPanels())
            if (p->name() == "figure6_errors") errors = p;
        QVERIFY(errors && errors->plot().plottableCount() > 0);
        auto sideBySide = [&] {
            QCustomPlot& plot = errors->plot();
            plot.replot(QCustomPlot::rpImmediateRefresh);
            const QList<QCPAxisRect*> rects = plot.axisRects();
            return rects.size() >= 2 && rects[0]->top() == rects[1]->top();
        };
        window_->tabs()->setCurrentIndex(1);
        QVERIFY(sideBySide());  // on a wide screen, A and B side by side
        const QStringList files =
            errors->exportTo(dir_.filePath("figure6_column"), {"png", "pdf"},
                             FigureSize::physical(kSingleColumn_mm, 140, 300));
        QCOMPARE(files.size(), 2);
        QCOMPARE(QImage(files.front()).width(), 1051);
        QVERIFY(sideBySide());
        // A session's own output folder (the screenshot tour's) is not kept as the preference.
        window_->setOutputBase(dir_.filePath("runs"));
        QCOMPARE(QSettings().value("resultsFolder").toString(), QDir(folder).absolutePath());
        // The next window starts with it.
        MainWindow next;
        QCOMPARE(next.resultsFolder(), QDir(folder).absolutePath());
        QCOMPARE(next.outputBase(), QDir(folder).absolutePath());
        // And without one, under the documents folder.
        QVERIFY(MainWindow::defaultResultsFolder().startsWith(
            QStandardPaths::writableLocation(QStandardPaths::DocumentsLocation)));
        window_->setOutputBase(dir_.filePath("runs"));
    }

    void theScenePanelSpeaksInWordsAndUnits() {
        auto* noise = window_->scenePanel()->findChild<QGroupBox*>("effect_taxel_noise");
        QVERIFY(noise);
        QCOMPARE(noise->title(), QString("Taxel noise"));
        auto* form = qobject_cast<QFormLayout*>(noise->layout());
        QVERIFY(form);
        QStringList labels;
        for (int r = 0; r < form->rowCount(); ++r)
            if (auto* item = form->itemAt(r, QFormLayout::LabelRole))
                if (auto* l = qobject_cast<QLabel*>(item->widget())) labels << l->text();
        QVERIFY2(labels.contains("σ (counts)"), qPrintable(labels.join(" | ")));
    }

    void quitClosesTheWindow() {
        QVERIFY(window_->isVisible());
        press(action("menuQuit")->shortcut());
        QTRY_VERIFY(!window_->isVisible());
    }
};

QTEST_MAIN(TestWindowDesktop)
#include "test_window_desktop.moc"
