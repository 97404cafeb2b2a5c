#pragma once
// Mouse and keyboard camera control shared by the studio's views (the CPU panes' RenderView and
// the OpenGL SurfelView), with ParaView / 3D Slicer conventions:
//   left drag: orbit; middle drag or Shift+left drag: pan; right drag or wheel: zoom;
//   arrow keys: orbit 5 degrees (with Shift: pan); + / -: zoom; a left click (press and
//   release without moving): clicked (the window picks the surface point under it).
// It filters the input events of its view; the window turns the signals into camera moves
// (Navigation.h), so that every view moves the one camera the same way.
#include <QObject>
#include <QPoint>
#include <QPointF>

class QEvent;
class QKeyEvent;
class QMouseEvent;
class QWheelEvent;
class QWidget;

namespace octrace::studio {

class ViewInput : public QObject {
    Q_OBJECT
public:
    /// Filters the mouse, wheel and key events of `view` (its parent; its height scales a pan).
    explicit ViewInput(QWidget* view);
    bool eventFilter(QObject* watched, QEvent* event) override;

signals:
    void orbitBy(double yawDeg, double pitchDeg);
    /// (dx, dy) pixels of a view `viewHeight` pixels high.
    void panBy(double dx, double dy, int viewHeight);
    void dollyBy(double factor);
    /// The camera stopped moving (button released, or a key or wheel step done).
    void interactionFinished();
    /// A left click that did not move the camera, at `pos` (the view's logical pixels).
    void clicked(QPointF pos);

private:
    void mousePress(QMouseEvent* e);
    void mouseMove(QMouseEvent* e);
    void mouseRelease(QMouseEvent* e);
    void wheel(QWheelEvent* e);
    /// False for a key that is not a camera key (the view gets it).
    bool key(QKeyEvent* e);

    enum class Drag { None, Orbit, Pan, Zoom };
    QWidget* view_;
    Drag drag_ = Drag::None;
    QPoint last_;
    bool moved_ = false;  // the camera moved since the button went down
};

}  // namespace octrace::studio
