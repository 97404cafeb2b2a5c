#include "StepSlider.h"

#include "octrace/model/OptionTable.h"

#include <QHBoxLayout>
#include <QLabel>
#include <QSlider>
#include <QSpinBox>
#include <QStyle>
#include <QToolButton>
#include <QVBoxLayout>

#include <algorithm>

namespace octrace::studio {

StepSlider::StepSlider(QWidget* parent) : QWidget(parent) {
    auto* column = new QVBoxLayout(this);
    column->setContentsMargins(0, 0, 0, 0);
    auto* row = new QHBoxLayout;
    play_ = new QToolButton(this);
    play_->setObjectName(QStringLiteral("stepPlay"));
    play_->setCheckable(true);
    play_->setIcon(style()->standardIcon(QStyle::SP_MediaPlay));
    play_->setToolTip(tr("Play: show the steps one after the other, looping (cine)"));
    slider_ = new QSlider(Qt::Horizontal, this);
    slider_->setObjectName(QStringLiteral("stepSlider"));
    slider_->setTracking(false);  // a step is read when the slider is let go, not at each pixel
    slider_->setPageStep(1);
    index_ = new QSpinBox(this);
    index_->setObjectName(QStringLiteral("stepIndex"));
    index_->setKeyboardTracking(false);
    row->addWidget(play_);
    row->addWidget(slider_, 1);
    row->addWidget(index_);
    column->addLayout(row);
    name_ = new QLabel(this);
    name_->setObjectName(QStringLiteral("stepName"));
    column->addWidget(name_);

    // The frame interval of the table's default frame rate (`fps`, as `octrace animate`).
    next_.setSingleShot(true);
    next_.setInterval(int(1000.0 / model::opt::fps.defaultValue));
    connect(&next_, &QTimer::timeout, this, [this] {
        if (playing() && count() > 1) choose((step() + 1) % count());
    });
    connect(play_, &QToolButton::toggled, this, [this](bool on) {
        play_->setIcon(style()->standardIcon(on ? QStyle::SP_MediaPause : QStyle::SP_MediaPlay));
        if (on) next_.start();
        else next_.stop();
    });
    connect(slider_, &QSlider::valueChanged, this, [this](int v) {
        if (!updating_) choose(v);
    });
    connect(slider_, &QSlider::sliderMoved, this, [this](int v) { showName(v); });  // while dragging
    connect(index_, &QSpinBox::valueChanged, this, [this](int v) {
        if (!updating_) choose(v);
    });
    setSteps({}, 0);
}

void StepSlider::setSteps(const QStringList& names, int current) {
    names_ = names;
    const bool steps = names.size() > 1;
    updating_ = true;
    slider_->setRange(0, std::max(0, int(names.size()) - 1));
    index_->setRange(0, std::max(0, int(names.size()) - 1));
    updating_ = false;
    setEnabled(steps);
    if (!steps) setPlaying(false);
    showStep(current);
}

void StepSlider::showStep(int index) {
    updating_ = true;
    slider_->setValue(index);
    index_->setValue(index);
    updating_ = false;
    showName(index);
}

void StepSlider::showName(int index) {
    name_->setText(index >= 0 && index < names_.size() ? names_[index] : QString());
}

int StepSlider::step() const { return slider_->value(); }

bool StepSlider::playing() const { return play_->isChecked(); }

void StepSlider::setPlaying(bool on) { play_->setChecked(on); }

void StepSlider::stepShown() {
    if (playing()) next_.start();
}

void StepSlider::choose(int index) {
    showStep(index);
    emit stepChosen(index);
}

}  // namespace octrace::studio
