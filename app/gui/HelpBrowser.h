#pragma once
// The documentation inside the window (docs/window.md, Help): the installed Markdown documents
// rendered by Qt's own Markdown support in a text browser, links between them followed in place,
// a list of the documents and a search over all of them.
#include <QDialog>
#include <QString>

class QLineEdit;
class QListWidget;
class QTextBrowser;

namespace activetouch {

class HelpBrowser : public QDialog {
    Q_OBJECT
public:
    /// Shows the documents of `folder` (its *.md files).
    explicit HelpBrowser(const QString& folder, QWidget* parent = nullptr);

    /// Opens `document` (a file name in the folder) at the first place its text reads `topic`
    /// (the whole document if empty or not found).
    void showTopic(const QString& document, const QString& topic = {});
    /// Searches every document for `text`: lists each hit (document and line), opens the first.
    /// Returns the number of hits.
    int search(const QString& text);

    QTextBrowser* browser() const { return browser_; }
    QListWidget* hits() const { return hits_; }

private:
    void openHit(int row);
    QString folder_;
    QTextBrowser* browser_;
    QListWidget* documents_;
    QListWidget* hits_;
    QLineEdit* query_;
    QString lastQuery_;
};

}  // namespace activetouch
