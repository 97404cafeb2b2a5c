#include "RenderView.h"

#include <QKeyEvent>
#include <QMouseEvent>
#include <QPainter>
#include <QWheelEvent>

#include <cmath>

namespace octrace::studio {
namespace {
constexpr double kDegreesPerPixel = 0.4;
constexpr double kKeyDegrees = 5.0;
constexpr double kKeyPanPixels = 20.0;
constexpr double kZoomStep = 0.9;  // distance factor per wheel notch or key press
}  // namespace

RenderView::RenderView(QWidget* parent) : QWidget(parent) {
    setFocusPolicy(Qt::StrongFocus);
    setMinimumSize(64, 64);
    setAttribute(Qt::WA_OpaquePaintEvent);
}

void RenderView::setImage(const QImage& image) {
    image_ = image;
    update();
}

void RenderView::setOverlay(const QString& text) {
    overlay_ = text;
    update();
}

void RenderView::paintEvent(QPaintEvent*) {
    QPainter p(this);
    p.fillRect(rect(), palette().color(QPalette::Base));
    if (!image_.isNull()) {
        // A preview is smaller than the pane: scaled up to fill it.
        p.setRenderHint(QPainter::SmoothPixmapTransform, image_.size() != size());
        p.drawImage(rect(), image_);
    }
    if (!overlay_.isEmpty()) {
        QFont f = font();
        f.setStyleHint(QFont::Monospace);
        f.setFamily(QStringLiteral("monospace"));
        p.setFont(f);
        const QRect box = p.boundingRect(rect().adjusted(6, 6, -6, -6), Qt::AlignLeft | Qt::AlignTop, overlay_);
        p.fillRect(box.adjusted(-4, -2, 4, 2), QColor(0, 0, 0, 150));
        p.setPen(Qt::white);
        p.drawText(box, Qt::AlignLeft | Qt::AlignTop, overlay_);
    }
    if (hasFocus()) {
        p.setPen(QPen(palette().color(QPalette::Highlight), 2));
        p.drawRect(rect().adjusted(1, 1, -1, -1));
    }
}

void RenderView::mousePressEvent(QMouseEvent* e) {
    setFocus();
    last_ = e->position().toPoint();
    if (e->button() == Qt::LeftButton) drag_ = (e->modifiers() & Qt::ShiftModifier) ? Drag::Pan : Drag::Orbit;
    else if (e->button() == Qt::MiddleButton) drag_ = Drag::Pan;
    else if (e->button() == Qt::RightButton) drag_ = Drag::Zoom;
}

void RenderView::mouseMoveEvent(QMouseEvent* e) {
    const QPoint pos = e->position().toPoint();
    const QPoint d = pos - last_;
    last_ = pos;
    if (d.isNull()) return;
    switch (drag_) {
        case Drag::Orbit: emit orbitBy(d.x() * kDegreesPerPixel, d.y() * kDegreesPerPixel); break;
        case Drag::Pan: emit panBy(d.x(), d.y()); break;
        case Drag::Zoom: emit dollyBy(std::pow(1.01, d.y())); break;  // drag down: away (ParaView)
        case Drag::None: break;
    }
}

void RenderView::mouseReleaseEvent(QMouseEvent*) {
    if (drag_ != Drag::None) emit interactionFinished();
    drag_ = Drag::None;
}

void RenderView::wheelEvent(QWheelEvent* e) {
    const double notches = e->angleDelta().y() / 120.0;
    if (notches == 0.0) return;
    emit dollyBy(std::pow(kZoomStep, notches));
    emit interactionFinished();
}

void RenderView::keyPressEvent(QKeyEvent* e) {
    const bool shift = e->modifiers() & Qt::ShiftModifier;
    switch (e->key()) {
        case Qt::Key_Left: shift ? emit panBy(-kKeyPanPixels, 0) : emit orbitBy(-kKeyDegrees, 0); break;
        case Qt::Key_Right: shift ? emit panBy(kKeyPanPixels, 0) : emit orbitBy(kKeyDegrees, 0); break;
        case Qt::Key_Up: shift ? emit panBy(0, -kKeyPanPixels) : emit orbitBy(0, -kKeyDegrees); break;
        case Qt::Key_Down: shift ? emit panBy(0, kKeyPanPixels) : emit orbitBy(0, kKeyDegrees); break;
        case Qt::Key_Plus:
        case Qt::Key_Equal: emit dollyBy(kZoomStep); break;
        case Qt::Key_Minus: emit dollyBy(1.0 / kZoomStep); break;
        default: QWidget::keyPressEvent(e); return;
    }
    emit interactionFinished();
}

void RenderView::resizeEvent(QResizeEvent*) { emit resized(); }

}  // namespace octrace::studio
