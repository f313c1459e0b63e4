#pragma once
// The dock panels' common frame: a column of groups that scrolls when the dock is shorter than it.
#include <QScrollArea>
#include <QVBoxLayout>
#include <QWidget>

namespace activetouch {

/// Fills `panel` with a scroll area and returns the column inside it to add the groups to.
inline QVBoxLayout* scrolledColumn(QWidget* panel) {
    auto* outer = new QVBoxLayout(panel);
    auto* scroll = new QScrollArea;
    scroll->setWidgetResizable(true);
    outer->addWidget(scroll);
    auto* content = new QWidget;
    scroll->setWidget(content);
    return new QVBoxLayout(content);
}

}  // namespace activetouch
