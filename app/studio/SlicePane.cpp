#include "SlicePane.h"

#include <QKeyEvent>
#include <QMouseEvent>
#include <QPainter>
#include <QWheelEvent>

#include <cmath>

namespace octrace::studio {

SlicePane::SlicePane(SlicePlane plane, QWidget* parent) : QWidget(parent), plane_(plane) {
    setFocusPolicy(Qt::StrongFocus);
    setMouseTracking(true);
    setMinimumSize(96, 96);
    setAttribute(Qt::WA_OpaquePaintEvent);
}

void SlicePane::setContent(Content content) {
    content_ = std::move(content);
    hasSlice_ = true;
    message_.clear();
    update();
}

void SlicePane::setMessage(const QString& text) {
    content_ = {};
    hasSlice_ = false;
    message_ = text;
    update();
}

QSize SlicePane::imageSize() const {
    const qreal dpr = devicePixelRatioF();
    return {std::max(16, int(std::lround(width() * dpr))), std::max(16, int(std::lround(height() * dpr)))};
}

QPointF SlicePane::imagePixel(QPointF p) const { return p * devicePixelRatioF(); }
QPointF SlicePane::widgetPoint(QPointF px) const { return px / devicePixelRatioF(); }

void SlicePane::paintEvent(QPaintEvent*) {
    QPainter p(this);
    p.fillRect(rect(), Qt::black);
    p.setPen(Qt::white);
    if (!hasSlice_) {
        p.drawText(rect().adjusted(8, 8, -8, -8), Qt::AlignCenter | Qt::TextWordWrap, message_);
        return;
    }
    // The image at one image pixel per device pixel: the pane asked for its own size.
    p.drawImage(QRectF(QPointF(0, 0), QSizeF(content_.image.size()) / devicePixelRatioF()), content_.image);
    if (content_.crosshair) {
        const QPointF c = widgetPoint(*content_.crosshair);
        p.setPen(QPen(QColor(255, 220, 0, 170), 1));
        p.drawLine(QPointF(c.x(), 0), QPointF(c.x(), c.y() - 6));
        p.drawLine(QPointF(c.x(), c.y() + 6), QPointF(c.x(), height()));
        p.drawLine(QPointF(0, c.y()), QPointF(c.x() - 6, c.y()));
        p.drawLine(QPointF(c.x() + 6, c.y()), QPointF(width(), c.y()));
    }
    // Orientation letters in the middle of each edge, as `slice --figure` puts them beside the grid.
    QFont f = font();
    f.setBold(true);
    p.setFont(f);
    p.setPen(QColor(255, 255, 160));
    const QRect r = rect().adjusted(4, 2, -4, -2);
    p.drawText(r, Qt::AlignRight | Qt::AlignVCenter, content_.letters[0]);
    p.drawText(r, Qt::AlignLeft | Qt::AlignVCenter, content_.letters[1]);
    p.drawText(r, Qt::AlignHCenter | Qt::AlignTop, content_.letters[2]);
    p.drawText(r, Qt::AlignHCenter | Qt::AlignBottom, content_.letters[3]);
    p.setFont(font());
    p.setPen(Qt::white);
    p.drawText(rect().adjusted(6, 4, -6, -4), Qt::AlignLeft | Qt::AlignTop, content_.caption);
    // The scale bar in the lower left corner, its length in millimetres under it.
    if (content_.scaleBar.length > 0.0) {
        const double len = content_.scaleBar.pixels / devicePixelRatioF();
        const QFontMetrics fm(font());
        const double y = height() - fm.height() - 8;
        p.setPen(QPen(Qt::white, 2));
        p.drawLine(QPointF(10, y), QPointF(10 + len, y));
        p.drawLine(QPointF(10, y - 4), QPointF(10, y + 4));
        p.drawLine(QPointF(10 + len, y - 4), QPointF(10 + len, y + 4));
        p.drawText(QPointF(10, y + fm.ascent() + 3), QString::fromStdString(content_.scaleBar.label));
    }
    if (hasFocus()) {
        p.setPen(QPen(palette().color(QPalette::Highlight), 2));
        p.setBrush(Qt::NoBrush);
        p.drawRect(rect().adjusted(1, 1, -1, -1));
    }
}

void SlicePane::resizeEvent(QResizeEvent*) { emit resized(); }

void SlicePane::wheelEvent(QWheelEvent* e) {
    // One slice per notch (120 eighths of a degree); a fine-grained wheel adds up to a notch.
    wheelAngle_ += e->angleDelta().y();
    const int steps = wheelAngle_ / 120;
    wheelAngle_ -= steps * 120;
    if (steps) emit stepBy(steps);
    e->accept();
}

void SlicePane::keyPressEvent(QKeyEvent* e) {
    switch (e->key()) {
        case Qt::Key_Up:
        case Qt::Key_Right:
        case Qt::Key_PageUp: emit stepBy(1); break;
        case Qt::Key_Down:
        case Qt::Key_Left:
        case Qt::Key_PageDown: emit stepBy(-1); break;
        default: QWidget::keyPressEvent(e); return;
    }
    e->accept();
}

void SlicePane::mousePressEvent(QMouseEvent* e) {
    setFocus();
    last_ = e->position().toPoint();
    if (e->button() == Qt::RightButton || (e->button() == Qt::LeftButton && windowLevelMode_)) drag_ = Drag::Window;
    else if (e->button() == Qt::LeftButton) {
        drag_ = Drag::Crosshair;
        emit pressedAt(imagePixel(e->position()));
    }
}

void SlicePane::mouseMoveEvent(QMouseEvent* e) {
    const QPoint pos = e->position().toPoint();
    if (drag_ == Drag::Window && pos != last_) emit windowDrag(pos.x() - last_.x(), pos.y() - last_.y());
    if (drag_ == Drag::Crosshair) emit pressedAt(imagePixel(e->position()));
    last_ = pos;
    emit pointerAt(imagePixel(e->position()));
}

void SlicePane::mouseReleaseEvent(QMouseEvent*) { drag_ = Drag::None; }

void SlicePane::leaveEvent(QEvent*) { emit pointerLeft(); }

}  // namespace octrace::studio
