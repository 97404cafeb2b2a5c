#pragma once
// One pane of the studio: shows the latest frame (scaled up while it is a coarse preview) with
// its statistics over it, and turns mouse and keyboard input into camera moves.
//   left drag: orbit; middle drag or Shift+left drag: pan; right drag or wheel: zoom;
//   arrow keys: orbit 5 degrees (with Shift: pan); + / -: zoom.
#include <QImage>
#include <QPoint>
#include <QString>
#include <QWidget>

namespace octrace::studio {

class RenderView : public QWidget {
    Q_OBJECT
public:
    explicit RenderView(QWidget* parent = nullptr);
    void setImage(const QImage& image);
    void setOverlay(const QString& text);
    const QImage& image() const { return image_; }
    QSize sizeHint() const override { return {640, 480}; }

signals:
    void orbitBy(double yawDeg, double pitchDeg);
    void panBy(double dx, double dy);
    void dollyBy(double factor);
    /// The camera stopped moving (button released, or a key or wheel step done).
    void interactionFinished();
    void resized();

protected:
    void paintEvent(QPaintEvent*) override;
    void mousePressEvent(QMouseEvent*) override;
    void mouseMoveEvent(QMouseEvent*) override;
    void mouseReleaseEvent(QMouseEvent*) override;
    void wheelEvent(QWheelEvent*) override;
    void keyPressEvent(QKeyEvent*) override;
    void resizeEvent(QResizeEvent*) override;

private:
    enum class Drag { None, Orbit, Pan, Zoom };
    QImage image_;
    QString overlay_;
    Drag drag_ = Drag::None;
    QPoint last_;
};

}  // namespace octrace::studio
