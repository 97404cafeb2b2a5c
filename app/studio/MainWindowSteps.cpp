// MainWindow's ocean controls and step slider: the window's glue to OceanPanel and StepSlider
// (kept apart from MainWindow.cpp, whose panes and controls other work extends).
#include "MainWindow.h"

#include "OceanPanel.h"
#include "StepSlider.h"

#include "octrace/model/OptionTable.h"
#include "octrace/util/Error.h"

#include <QFormLayout>
#include <QLabel>
#include <QLineEdit>

#include <algorithm>

namespace octrace::studio {

void MainWindow::buildStepAndOceanControls(QFormLayout* inputForm, QLayout* panel) {
    stepSlider_ = new StepSlider(inputForm->parentWidget());
    stepSlider_->setObjectName(QStringLiteral("stepSlider"));
    stepLabel_ = new QLabel(tr("Step"), inputForm->parentWidget());
    inputForm->addRow(stepLabel_, stepSlider_);
    connect(stepSlider_, &StepSlider::stepChosen, this, &MainWindow::stepChosen);
    oceanPanel_ = new OceanPanel(inputForm->parentWidget());
    oceanPanel_->hide();
    panel->addWidget(oceanPanel_);
    connect(oceanPanel_, &OceanPanel::settingEdited, this, &MainWindow::settingEdited);
}

int MainWindow::currentStep() const {
    const InputInfo& in = engine_.info();
    if (in.volumeSteps) {
        const auto it = state_.settings.find(model::opt::volume.key);
        return it == state_.settings.end() ? 0 : std::stoi(it->second);
    }
    const std::string& t = state_.time;
    if (!t.empty() && t.find_first_not_of("0123456789") == std::string::npos) return std::stoi(t);
    // A date: the step named with it, else the first.
    for (int i = 0; i < in.steps.size() && !t.empty(); ++i)
        if (in.steps[i].contains(QString::fromStdString(t))) return i;
    return 0;
}

void MainWindow::stepAbandoned() {
    if (!stepPending_) return;
    stepPending_ = false;
    stepSlider_->setPlaying(false);
    stepSlider_->showStep(currentStep());
    timeEdit_->setText(QString::fromStdString(state_.time));
}

void MainWindow::showStepsAndOcean() {
    const InputInfo& in = engine_.info();
    stepLabel_->setText(in.volumeSteps ? tr("Volume") : tr("Time step"));
    stepSlider_->setToolTip(in.volumeSteps ? QString::fromStdString(model::sayForStudio(model::opt::volume.helpLine()))
                                           : tr("The time steps of the variable (the CLI's --time INDEX)"));
    stepSlider_->setSteps(in.steps, currentStep());
    stepLabel_->setVisible(in.steps.size() > 1);
    stepSlider_->setVisible(in.steps.size() > 1);
    oceanPanel_->setVisible(in.geographic);
    if (in.geographic) oceanPanel_->showState(state_, in);
}

void MainWindow::settingEdited(const QString& key, const QString& text) {
    const model::Option* o = model::findOption(key.toStdString());
    if (!o) return;
    StudioState s = state_;
    if (text.isEmpty()) s.settings.erase(o->key);
    else s.settings[o->key] = text.toStdString();
    try {
        if (!text.isEmpty()) checkSetting(*o, text.toStdString());
    } catch (const std::exception& e) {
        showMessage(QString::fromStdString(model::sayForStudio(e.what())), true);
        oceanPanel_->showState(state_, engine_.info());  // back to what is on screen
        return;
    }
    switch (settingEffect(*o)) {
    case SettingEffect::Reload:
        // Another part of the grid, or another scale: another world, framed anew.
        s.cameraSet = false;
        load(s);
        break;
    case SettingEffect::Rebuild:
        state_ = s;
        scheduleBuild();
        break;
    case SettingEffect::Render:
        state_ = s;
        requestRender(false);
        break;
    }
}

void MainWindow::stepChosen(int index) {
    StudioState s = state_;
    if (engine_.info().volumeSteps) s.settings[model::opt::volume.key] = std::to_string(index);
    else s.time = std::to_string(index);
    timeEdit_->setText(QString::fromStdString(s.time));
    stepPending_ = true;
    load(s);  // the same iso value and camera: the steps compare
}

}  // namespace octrace::studio
