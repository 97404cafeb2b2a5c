#pragma once
// Steps through an input's time axis: a NetCDF variable's time steps (`time`) or the volumes of
// a 4-D DICOM series or NIfTI image (`volume`). A slider, the step's index, its name (date or
// what tells the volume apart) and Play, which shows the steps one after the other (cine),
// looping: the next step is asked for only once the window has shown the last one
// (stepShown), at most the table's `fps` a second, so that slow builds never pile up.
#include <QStringList>
#include <QTimer>
#include <QWidget>

class QLabel;
class QSlider;
class QSpinBox;
class QToolButton;

namespace octrace::studio {

class StepSlider : public QWidget {
    Q_OBJECT
public:
    explicit StepSlider(QWidget* parent = nullptr);

    /// The steps by name and the one on screen; fewer than two: disabled (and Play stops).
    void setSteps(const QStringList& names, int current);
    /// Moves the slider to `index` without asking for it.
    void showStep(int index);
    int step() const;
    int count() const { return int(names_.size()); }
    bool playing() const;
    void setPlaying(bool on);
    /// The window shows the step last asked for: while playing, the next follows after the
    /// frame interval.
    void stepShown();

signals:
    /// The user (or Play) asks for step `index`.
    void stepChosen(int index);

private:
    void choose(int index);
    void showName(int index);

    QStringList names_;
    QSlider* slider_ = nullptr;
    QSpinBox* index_ = nullptr;
    QToolButton* play_ = nullptr;
    QLabel* name_ = nullptr;
    QTimer next_;
    bool updating_ = false;
};

}  // namespace octrace::studio
