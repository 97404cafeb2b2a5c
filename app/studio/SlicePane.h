#pragma once
// One slice pane of the studio's radiology layout (SliceViews.h): an axial, coronal or sagittal
// slice (x, y or z off patient volumes) drawn by the CLI's slice code (model::renderSlice) at the
// pane's size, with the orientation letters and the scale bar of `slice --figure`, the shared
// crosshair, and the plane's name and sample over it. Its input, as 3D Slicer's slice views:
//   wheel: one slice per notch; Up/Right/Page Up: the next slice, Down/Left/Page Down: the
//   previous one; left click or drag: moves the crosshair there; right drag (or left drag in
//   window/level mode): window (horizontal) and level (vertical); the pointer: the data probe.
#include "octrace/model/Slice.h"

#include <QImage>
#include <QPointF>
#include <QString>
#include <QWidget>

#include <optional>

namespace octrace::studio {

class SlicePane : public QWidget {
    Q_OBJECT
public:
    SlicePane(SlicePlane plane, QWidget* parent = nullptr);
    SlicePlane plane() const { return plane_; }
    void setPlane(SlicePlane plane) { plane_ = plane; }

    /// What the pane shows: a slice (its image is result.image, without a figure), its letters
    /// (right, left, up, down), the scale bar of `slice --figure` (model::sliceScaleBar: its
    /// length in mm, in image pixels and its label; length 0: none), the crosshair's pixel
    /// (image pixels, centres at +0.5) and the caption in the upper left corner.
    struct Content {
        model::SliceResult result;
        QImage image;
        QString letters[4];
        model::SliceScaleBar scaleBar;
        std::optional<QPointF> crosshair;
        QString caption;
    };
    void setContent(Content content);
    /// No slice (no field, or this plane cannot be drawn): `text` says why.
    void setMessage(const QString& text);
    const Content& content() const { return content_; }
    bool hasSlice() const { return hasSlice_; }
    /// The slice's image: pixel for pixel what `octrace slice` writes at the same settings.
    const QImage& image() const { return content_.image; }
    /// The image size the pane asks for: its own size in device pixels.
    QSize imageSize() const;
    /// The image pixel (continuous, pixel centres at +0.5) of a point of the widget, and back.
    QPointF imagePixel(QPointF widgetPos) const;
    QPointF widgetPoint(QPointF imagePixel) const;
    /// Left drag adjusts the window instead of the crosshair.
    void setWindowLevelMode(bool on) { windowLevelMode_ = on; }
    QSize sizeHint() const override { return {320, 320}; }

signals:
    void stepBy(int slices);
    /// Left click or drag at `imagePixel` (move the crosshair there).
    void pressedAt(QPointF imagePixel);
    /// Pointer at `imagePixel` (the probe).
    void pointerAt(QPointF imagePixel);
    void pointerLeft();
    /// A window/level drag of (dx, dy) pixels.
    void windowDrag(int dx, int dy);
    void resized();

protected:
    void paintEvent(QPaintEvent*) override;
    void resizeEvent(QResizeEvent*) override;
    void wheelEvent(QWheelEvent*) override;
    void keyPressEvent(QKeyEvent*) override;
    void mousePressEvent(QMouseEvent*) override;
    void mouseMoveEvent(QMouseEvent*) override;
    void mouseReleaseEvent(QMouseEvent*) override;
    void leaveEvent(QEvent*) override;

private:
    enum class Drag { None, Crosshair, Window };
    SlicePlane plane_;
    Content content_;
    bool hasSlice_ = false;
    QString message_;
    bool windowLevelMode_ = false;
    Drag drag_ = Drag::None;
    QPoint last_;
    int wheelAngle_ = 0;  // eighths of a degree not yet turned into a slice (fine-grained wheels)
};

}  // namespace octrace::studio
