#include "RenderView.h"

#include <QPainter>

namespace octrace::studio {

RenderView::RenderView(QWidget* parent) : QWidget(parent), input_(new ViewInput(this)) {
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

void RenderView::resizeEvent(QResizeEvent*) { emit resized(); }

}  // namespace octrace::studio
