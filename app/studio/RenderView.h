#pragma once
// One pane of the studio: shows the latest frame (scaled up while it is a coarse preview) with
// its statistics over it; its mouse and keyboard input moves the camera (ViewInput.h).
#include "ViewInput.h"

#include <QImage>
#include <QPointF>
#include <QString>
#include <QWidget>

#include <cstdint>
#include <optional>

namespace octrace::studio {

class RenderView : public QWidget {
    Q_OBJECT
public:
    explicit RenderView(QWidget* parent = nullptr);
    /// Shows `image`; a non-zero `inputSerial` (LatencyMeter.h) is handed to painted() once the
    /// image is painted.
    void setImage(const QImage& image, std::uint64_t inputSerial = 0);
    void setOverlay(const QString& text);
    /// A crosshair mark at `pos` (logical pixels; none: hidden): the slice panes' crosshair.
    void setMarker(std::optional<QPointF> pos);
    std::optional<QPointF> marker() const { return marker_; }
    const QImage& image() const { return image_; }
    /// The camera moves asked for in this view.
    ViewInput* input() const { return input_; }
    QSize sizeHint() const override { return {640, 480}; }

signals:
    void resized();
    /// An image given with `inputSerial` has been painted (the end of paintEvent).
    void painted(std::uint64_t inputSerial);

protected:
    void paintEvent(QPaintEvent*) override;
    void resizeEvent(QResizeEvent*) override;

private:
    QImage image_;
    QString overlay_;
    std::optional<QPointF> marker_;
    std::uint64_t unpaintedSerial_ = 0;
    ViewInput* input_;
};

}  // namespace octrace::studio
