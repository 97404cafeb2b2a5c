#pragma once
// The histogram of the variable's valid samples (log counts) with the iso value marked; a
// click or drag picks the iso value.
#include <QWidget>

#include <vector>

namespace octrace::studio {

class HistogramView : public QWidget {
    Q_OBJECT
public:
    explicit HistogramView(QWidget* parent = nullptr);
    void setHistogram(const std::vector<double>& bins, double minimum, double maximum);
    void setIso(double iso);
    QSize sizeHint() const override { return {240, 70}; }

signals:
    void isoPicked(double iso);

protected:
    void paintEvent(QPaintEvent*) override;
    void mousePressEvent(QMouseEvent*) override;
    void mouseMoveEvent(QMouseEvent*) override;
    void mouseReleaseEvent(QMouseEvent*) override;

private:
    double valueAt(double x) const;
    std::vector<double> bins_;
    double min_ = 0.0, max_ = 1.0, iso_ = 0.5;
    bool dragging_ = false;
};

}  // namespace octrace::studio
