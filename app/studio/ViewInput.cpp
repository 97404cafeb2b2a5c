#include "ViewInput.h"

#include <QKeyEvent>
#include <QMouseEvent>
#include <QWheelEvent>
#include <QWidget>

#include <cmath>

namespace octrace::studio {
namespace {
constexpr double kDegreesPerPixel = 0.4;
constexpr double kKeyDegrees = 5.0;
constexpr double kKeyPanPixels = 20.0;
constexpr double kZoomStep = 0.9;  // distance factor per wheel notch or key press
}  // namespace

ViewInput::ViewInput(QWidget* view) : QObject(view), view_(view) { view->installEventFilter(this); }

bool ViewInput::eventFilter(QObject* watched, QEvent* event) {
    if (watched != view_) return false;
    switch (event->type()) {
        case QEvent::MouseButtonPress: mousePress(static_cast<QMouseEvent*>(event)); return true;
        case QEvent::MouseMove: mouseMove(static_cast<QMouseEvent*>(event)); return true;
        case QEvent::MouseButtonRelease: mouseRelease(static_cast<QMouseEvent*>(event)); return true;
        case QEvent::Wheel: wheel(static_cast<QWheelEvent*>(event)); return true;
        case QEvent::KeyPress: return key(static_cast<QKeyEvent*>(event));
        default: return false;
    }
}

void ViewInput::mousePress(QMouseEvent* e) {
    view_->setFocus();
    last_ = e->position().toPoint();
    moved_ = false;
    if (e->button() == Qt::LeftButton) drag_ = (e->modifiers() & Qt::ShiftModifier) ? Drag::Pan : Drag::Orbit;
    else if (e->button() == Qt::MiddleButton) drag_ = Drag::Pan;
    else if (e->button() == Qt::RightButton) drag_ = Drag::Zoom;
}

void ViewInput::mouseMove(QMouseEvent* e) {
    const QPoint pos = e->position().toPoint();
    const QPoint d = pos - last_;
    last_ = pos;
    if (d.isNull()) return;
    moved_ = moved_ || drag_ != Drag::None;
    switch (drag_) {
        case Drag::Orbit: emit orbitBy(d.x() * kDegreesPerPixel, d.y() * kDegreesPerPixel); break;
        case Drag::Pan: emit panBy(d.x(), d.y(), view_->height()); break;
        case Drag::Zoom: emit dollyBy(std::pow(1.01, d.y())); break;  // drag down: away (ParaView)
        case Drag::None: break;
    }
}

void ViewInput::mouseRelease(QMouseEvent* e) {
    if (drag_ == Drag::Orbit && !moved_ && e->button() == Qt::LeftButton) emit clicked(e->position());
    if (drag_ != Drag::None) emit interactionFinished();
    drag_ = Drag::None;
}

void ViewInput::wheel(QWheelEvent* e) {
    const double notches = e->angleDelta().y() / 120.0;
    if (notches == 0.0) return;
    emit dollyBy(std::pow(kZoomStep, notches));
    emit interactionFinished();
}

bool ViewInput::key(QKeyEvent* e) {
    const bool shift = e->modifiers() & Qt::ShiftModifier;
    const int h = view_->height();
    switch (e->key()) {
        case Qt::Key_Left: shift ? emit panBy(-kKeyPanPixels, 0, h) : emit orbitBy(-kKeyDegrees, 0); break;
        case Qt::Key_Right: shift ? emit panBy(kKeyPanPixels, 0, h) : emit orbitBy(kKeyDegrees, 0); break;
        case Qt::Key_Up: shift ? emit panBy(0, -kKeyPanPixels, h) : emit orbitBy(0, -kKeyDegrees); break;
        case Qt::Key_Down: shift ? emit panBy(0, kKeyPanPixels, h) : emit orbitBy(0, kKeyDegrees); break;
        case Qt::Key_Plus:
        case Qt::Key_Equal: emit dollyBy(kZoomStep); break;
        case Qt::Key_Minus: emit dollyBy(1.0 / kZoomStep); break;
        default: return false;
    }
    emit interactionFinished();
    return true;
}

}  // namespace octrace::studio
