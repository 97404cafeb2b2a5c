#include "RenderView.h"

#include <QPainter>

#include <utility>

namespace octrace::studio {

RenderView::RenderView(QWidget* parent) : QWidget(parent), input_(new ViewInput(this)) {
    setFocusPolicy(Qt::StrongFocus);
    setMinimumSize(64, 64);
    setAttribute(Qt::WA_OpaquePaintEvent);
}

void RenderView::setImage(const QImage& image, std::uint64_t inputSerial) {
    image_ = image;
    if (inputSerial) unpaintedSerial_ = inputSerial;
    update();
}

void RenderView::setOverlay(const QString& text) {
    overlay_ = text;
    update();
}

void RenderView::setMarker(std::optional<QPointF> pos) {
    if (pos == marker_) return;
    marker_ = pos;
    update();
}

void RenderView::paintEvent(QPaintEvent*) {
    QPainter p(this);
    // The frame covers the whole view: the base colour shows only where it is transparent.
    if (image_.isNull() || image_.hasAlphaChannel()) p.fillRect(rect(), palette().color(QPalette::Base));
    if (!image_.isNull()) {
        // A preview is smaller than the pane: scaled up to fill it.
        p.setRenderHint(QPainter::SmoothPixmapTransform, image_.size() != size());
        p.drawImage(rect(), image_);
    }
    if (marker_) {
        const QPointF c = *marker_;
        for (const auto& [colour, width] : {std::pair{QColor(0, 0, 0, 160), 3}, std::pair{QColor(255, 220, 0), 1}}) {
            p.setPen(QPen(colour, width));
            p.drawLine(c + QPointF(-12, 0), c + QPointF(-3, 0));
            p.drawLine(c + QPointF(3, 0), c + QPointF(12, 0));
            p.drawLine(c + QPointF(0, -12), c + QPointF(0, -3));
            p.drawLine(c + QPointF(0, 3), c + QPointF(0, 12));
        }
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
    p.end();
    if (const std::uint64_t s = std::exchange(unpaintedSerial_, 0)) emit painted(s);
}

void RenderView::resizeEvent(QResizeEvent*) { emit resized(); }

}  // namespace octrace::studio
