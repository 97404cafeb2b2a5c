#pragma once
// The dock's scrolling side panel (input, surface, cut-away and rendering controls). Two things
// a panel of many small controls needs:
// - it is never narrower than its controls: its minimum width follows the content's minimum
//   width (plus the vertical scroll bar), so that it scrolls vertically only and nothing is cut
//   off at the side;
// - the mouse wheel scrolls it: a spin box, combo box or slider takes the wheel only when it has
//   the keyboard focus (click or Tab into it first), so that scrolling past a control does not
//   change its value unseen (the usual Qt remedy: Qt::StrongFocus and an event filter).
#include <QScrollArea>

namespace octrace::studio {

class SidePanel : public QScrollArea {
    Q_OBJECT
public:
    /// Takes `content` (its controls made already) and guards the wheel of every spin box,
    /// combo box and slider in it.
    explicit SidePanel(QWidget* content, QWidget* parent = nullptr);

    QSize minimumSizeHint() const override;
    QSize sizeHint() const override;

    /// Whether `w` is a control whose value the wheel changes (spin box, combo box, slider).
    static bool isWheelControl(const QObject* w);

protected:
    bool eventFilter(QObject* watched, QEvent* event) override;

private:
    void guard(QWidget* control);
    int widthFor(int contentWidth) const;
};

}  // namespace octrace::studio
