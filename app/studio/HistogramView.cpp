#include "HistogramView.h"

#include <QMouseEvent>
#include <QPainter>

#include <algorithm>
#include <cmath>

namespace octrace::studio {

HistogramView::HistogramView(QWidget* parent) : QWidget(parent) {
    setMinimumHeight(50);
    setToolTip(tr("Histogram of the variable's valid samples (logarithmic counts); click to pick the iso value"));
}

void HistogramView::setHistogram(const std::vector<double>& bins, double minimum, double maximum) {
    bins_ = bins;
    min_ = minimum;
    max_ = maximum;
    update();
}

void HistogramView::setIso(double iso) {
    iso_ = iso;
    update();
}

double HistogramView::valueAt(double x) const {
    const double t = std::clamp(x / std::max(1, width()), 0.0, 1.0);
    return min_ + t * (max_ - min_);
}

void HistogramView::paintEvent(QPaintEvent*) {
    QPainter p(this);
    p.fillRect(rect(), palette().color(QPalette::Base));
    if (bins_.empty()) return;
    double top = 0.0;
    for (double b : bins_) top = std::max(top, std::log1p(b));
    const double w = double(width()) / double(bins_.size());
    p.setPen(Qt::NoPen);
    p.setBrush(palette().color(QPalette::Mid));
    for (std::size_t i = 0; i < bins_.size(); ++i) {
        const double h = top > 0.0 ? std::log1p(bins_[i]) / top * (height() - 2) : 0.0;
        p.drawRect(QRectF(i * w, height() - h, w, h));
    }
    if (max_ > min_) {
        const double x = (iso_ - min_) / (max_ - min_) * width();
        p.setPen(QPen(QColor(220, 40, 40), 2));
        p.drawLine(QPointF(x, 0), QPointF(x, height()));
    }
}

void HistogramView::mousePressEvent(QMouseEvent* e) {
    if (e->button() != Qt::LeftButton || bins_.empty()) return;
    dragging_ = true;
    emit isoPicked(valueAt(e->position().x()));
}

void HistogramView::mouseMoveEvent(QMouseEvent* e) {
    if (dragging_) emit isoPicked(valueAt(e->position().x()));
}

void HistogramView::mouseReleaseEvent(QMouseEvent*) { dragging_ = false; }

}  // namespace octrace::studio
