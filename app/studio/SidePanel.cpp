#include "SidePanel.h"

#include <QAbstractSlider>
#include <QAbstractSpinBox>
#include <QComboBox>
#include <QEvent>
#include <QScrollBar>

#include <algorithm>

namespace octrace::studio {

SidePanel::SidePanel(QWidget* content, QWidget* parent) : QScrollArea(parent) {
    setWidget(content);
    setWidgetResizable(true);
    setHorizontalScrollBarPolicy(Qt::ScrollBarAsNeeded);  // never needed: see minimumSizeHint
    content->installEventFilter(this);  // its layout changes: the panel's width follows
    for (QWidget* w : content->findChildren<QWidget*>())
        if (isWheelControl(w)) guard(w);
}

bool SidePanel::isWheelControl(const QObject* w) {
    // A scroll bar (of a combo box's list, say) is a slider too, but scrolling is its purpose.
    if (qobject_cast<const QScrollBar*>(w)) return false;
    return qobject_cast<const QAbstractSpinBox*>(w) || qobject_cast<const QComboBox*>(w) || qobject_cast<const QAbstractSlider*>(w);
}

void SidePanel::guard(QWidget* control) {
    // Focus by click or Tab, never by the wheel (spin and combo boxes default to Qt::WheelFocus).
    control->setFocusPolicy(Qt::StrongFocus);
    control->installEventFilter(this);
}

int SidePanel::widthFor(int contentWidth) const {
    return contentWidth + verticalScrollBar()->sizeHint().width() + 2 * frameWidth();
}

QSize SidePanel::minimumSizeHint() const {
    const QSize base = QScrollArea::minimumSizeHint();
    return widget() ? QSize(std::max(base.width(), widthFor(widget()->minimumSizeHint().width())), base.height()) : base;
}

QSize SidePanel::sizeHint() const {
    const QSize base = QScrollArea::sizeHint();
    return QSize(std::max(base.width(), minimumSizeHint().width()), base.height());
}

bool SidePanel::eventFilter(QObject* watched, QEvent* event) {
    if (watched == widget()) {
        if (event->type() == QEvent::LayoutRequest) updateGeometry();  // the content's minimum may have changed
        return QScrollArea::eventFilter(watched, event);
    }
    if (event->type() == QEvent::Wheel && isWheelControl(watched) && !static_cast<QWidget*>(watched)->hasFocus()) {
        // Not the control's: ignored, the event goes on to the parents, up to this panel, which
        // scrolls.
        event->ignore();
        return true;
    }
    return QScrollArea::eventFilter(watched, event);
}

}  // namespace octrace::studio
