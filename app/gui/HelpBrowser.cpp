#include "app/gui/HelpBrowser.h"

#include <QDesktopServices>
#include <QDir>
#include <QFile>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QListWidget>
#include <QSplitter>
#include <QTextBrowser>
#include <QTextStream>
#include <QVBoxLayout>

namespace activetouch {

namespace {

/// A document's title: its first "# " line, else its file name.
QString titleOf(const QString& path) {
    QFile f(path);
    if (f.open(QIODevice::ReadOnly | QIODevice::Text)) {
        QTextStream in(&f);
        while (!in.atEnd()) {
            const QString line = in.readLine();
            if (line.startsWith("# ")) return line.mid(2).trimmed();
        }
    }
    return QFileInfo(path).fileName();
}

}  // namespace

HelpBrowser::HelpBrowser(const QString& folder, QWidget* parent)
    : QDialog(parent), folder_(folder) {
    setObjectName("helpBrowser");
    setWindowTitle(tr("ActiveTouch Workbench documentation"));
    browser_ = new QTextBrowser;
    browser_->setObjectName("helpText");
    browser_->setSearchPaths({folder});
    browser_->setOpenLinks(true);
    browser_->setOpenExternalLinks(true);  // web addresses go to the desktop's browser
    documents_ = new QListWidget;
    documents_->setObjectName("helpDocuments");
    for (const QString& name : QDir(folder).entryList({"*.md"}, QDir::Files, QDir::Name)) {
        auto* item = new QListWidgetItem(titleOf(QDir(folder).filePath(name)), documents_);
        item->setData(Qt::UserRole, name);
    }
    query_ = new QLineEdit;
    query_->setObjectName("helpSearch");
    query_->setPlaceholderText(tr("Search the documentation"));
    query_->setClearButtonEnabled(true);
    hits_ = new QListWidget;
    hits_->setObjectName("helpHits");
    auto* side = new QWidget;
    auto* column = new QVBoxLayout(side);
    column->setContentsMargins(0, 0, 0, 0);
    column->addWidget(query_);
    column->addWidget(new QLabel(tr("Documents")));
    column->addWidget(documents_, 2);
    column->addWidget(new QLabel(tr("Found")));
    column->addWidget(hits_, 1);
    auto* split = new QSplitter;
    split->addWidget(side);
    split->addWidget(browser_);
    split->setStretchFactor(1, 3);
    auto* layout = new QHBoxLayout(this);
    layout->addWidget(split);
    resize(1000, 700);
    connect(documents_, &QListWidget::itemActivated, this,
            [this](QListWidgetItem* item) { showTopic(item->data(Qt::UserRole).toString()); });
    connect(documents_, &QListWidget::itemClicked, documents_, &QListWidget::itemActivated);
    connect(query_, &QLineEdit::returnPressed, this, [this] { search(query_->text()); });
    connect(hits_, &QListWidget::currentRowChanged, this, &HelpBrowser::openHit);
}

void HelpBrowser::showTopic(const QString& document, const QString& topic) {
    browser_->setSource(QUrl::fromLocalFile(QDir(folder_).filePath(document)),
                        QTextDocument::MarkdownResource);
    QTextCursor start(browser_->document());
    browser_->setTextCursor(start);
    if (!topic.isEmpty() && browser_->find(topic)) browser_->ensureCursorVisible();
    for (int i = 0; i < documents_->count(); ++i)
        if (documents_->item(i)->data(Qt::UserRole).toString() == document)
            documents_->setCurrentRow(i);
    show();
    raise();
}

int HelpBrowser::search(const QString& text) {
    const QSignalBlocker block(hits_);
    hits_->clear();
    lastQuery_ = text.trimmed();
    if (lastQuery_.isEmpty()) return 0;
    for (const QString& name : QDir(folder_).entryList({"*.md"}, QDir::Files, QDir::Name)) {
        QFile f(QDir(folder_).filePath(name));
        if (!f.open(QIODevice::ReadOnly | QIODevice::Text)) continue;
        QTextStream in(&f);
        for (int line = 1; !in.atEnd(); ++line) {
            const QString l = in.readLine();
            if (!l.contains(lastQuery_, Qt::CaseInsensitive)) continue;
            auto* item = new QListWidgetItem(
                QString("%1:%2  %3").arg(name).arg(line).arg(l.trimmed().left(80)), hits_);
            item->setData(Qt::UserRole, name);
        }
    }
    const int found = hits_->count();
    if (found > 0) {
        hits_->setCurrentRow(0);
        openHit(0);
    }
    return found;
}

void HelpBrowser::openHit(int row) {
    if (row < 0 || row >= hits_->count()) return;
    const QString document = hits_->item(row)->data(Qt::UserRole).toString();
    // The hit's own occurrence: as many finds into the document as hits before it there.
    int before = 0;
    for (int i = 0; i < row; ++i)
        before += hits_->item(i)->data(Qt::UserRole).toString() == document;
    showTopic(document);
    for (int i = 0; i <= before; ++i)
        if (!browser_->find(lastQuery_)) break;
    browser_->ensureCursorVisible();
}

}  // namespace activetouch
