#include "OceanPanel.h"

#include "Engine.h"
#include "OptionWidgets.h"
#include "StudioState.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QGridLayout>
#include <QHBoxLayout>
#include <QLabel>

#include <algorithm>
#include <cstdio>
#include <string>

namespace octrace::studio {
namespace {

QString number(double v) { return QString::number(v, 'g', 10); }

/// A box of degrees or metres: its range is what the quantity can be (longitudes are unwrapped
/// up to a turn past the grid's start); the option's text is checked when it is applied.
QDoubleSpinBox* coordinateBox(QWidget* parent, const char* name, double lo, double hi, const QString& suffix) {
    auto* box = new QDoubleSpinBox(parent);
    box->setObjectName(QLatin1String(name));
    box->setRange(lo, hi);
    box->setDecimals(2);
    box->setSuffix(suffix);
    box->setKeyboardTracking(false);
    return box;
}

void settingText(const StudioState& s, const model::Option& o, std::string& out) {
    const auto it = s.settings.find(o.key);
    out = it == s.settings.end() ? std::string() : it->second;
}

}  // namespace

OceanPanel::OceanPanel(QWidget* parent) : QGroupBox(tr("Ocean"), parent) {
    setObjectName(QStringLiteral("oceanPanel"));
    auto* form = new QFormLayout(this);

    // Region: west, east, south, north, as --region LON0,LON1,LAT0,LAT1.
    regionCheck_ = new QCheckBox(tr("subregion (else the whole grid)"), this);
    regionCheck_->setObjectName(QStringLiteral("regionCheck"));
    configure(regionCheck_, model::opt::region);
    auto* grid = new QGridLayout;
    const char* names[4] = {"regionWest", "regionEast", "regionSouth", "regionNorth"};
    const QString labels[4] = {tr("W"), tr("E"), tr("S"), tr("N")};
    for (int i = 0; i < 4; ++i) {
        region_[i] = i < 2 ? coordinateBox(this, names[i], -360.0, 720.0, QStringLiteral(" °E"))
                           : coordinateBox(this, names[i], -90.0, 90.0, QStringLiteral(" °N"));
        region_[i]->setToolTip(regionCheck_->toolTip());
        grid->addWidget(new QLabel(labels[i], this), i / 2, 2 * (i % 2));
        grid->addWidget(region_[i], i / 2, 2 * (i % 2) + 1);
        connect(region_[i], &QDoubleSpinBox::valueChanged, this, [this] { regionEdited(); });
    }
    connect(regionCheck_, &QCheckBox::toggled, this, [this] { regionEdited(); });
    form->addRow(tr(model::opt::region.label), regionCheck_);
    form->addRow(grid);

    depthCheck_ = new QCheckBox(tr("levels from .. to (else all)"), this);
    depthCheck_->setObjectName(QStringLiteral("depthRangeCheck"));
    configure(depthCheck_, model::opt::depthRange);
    auto* depthRow = new QHBoxLayout;
    for (int i = 0; i < 2; ++i) {
        depths_[i] = coordinateBox(this, i ? "depthTo" : "depthFrom", 0.0, 12000.0, QStringLiteral(" m"));
        depths_[i]->setDecimals(0);
        depths_[i]->setSingleStep(50.0);
        depths_[i]->setToolTip(depthCheck_->toolTip());
        depthRow->addWidget(depths_[i]);
        connect(depths_[i], &QDoubleSpinBox::valueChanged, this, [this] { depthRangeEdited(); });
    }
    connect(depthCheck_, &QCheckBox::toggled, this, [this] { depthRangeEdited(); });
    form->addRow(tr(model::opt::depthRange.label), depthCheck_);
    form->addRow(depthRow);

    auto* scaleRow = new QHBoxLayout;
    scale_ = new QDoubleSpinBox(this);
    scale_->setObjectName(QLatin1String(model::opt::verticalScale.key));
    configure(scale_, model::opt::verticalScale, 1);
    scale_->setKeyboardTracking(false);
    scale_->setSuffix(QStringLiteral(" x"));
    scaleAuto_ = new QCheckBox(tr("auto"), this);
    scaleAuto_->setObjectName(QStringLiteral("verticalScaleAuto"));
    scaleAuto_->setToolTip(tr("The default vertical scale: %1").arg(QString::fromLatin1(model::opt::verticalScale.defaultText)));
    scaleRow->addWidget(scale_, 1);
    scaleRow->addWidget(scaleAuto_);
    connect(scale_, &QDoubleSpinBox::valueChanged, this, [this] { scaleEdited(); });
    connect(scaleAuto_, &QCheckBox::toggled, this, [this] { scaleEdited(); });
    form->addRow(tr(model::opt::verticalScale.label), scaleRow);

    projection_ = new QComboBox(this);
    projection_->setObjectName(QLatin1String(model::opt::mapProjection.key));
    configure(projection_, model::opt::mapProjection);
    for (const std::string& c : model::opt::mapProjection.choiceList()) projection_->addItem(QString::fromStdString(c));
    connect(projection_, &QComboBox::activated, this, [this] {
        const QString c = projection_->currentText();
        emit settingEdited(QLatin1String(model::opt::mapProjection.key),
                           c.toStdString() == model::opt::mapProjection.defaultChoice() ? QString() : c);
    });
    form->addRow(tr(model::opt::mapProjection.label), projection_);

    colourBy_ = new QComboBox(this);
    colourBy_->setObjectName(QLatin1String(model::opt::colourBy.key));
    configure(colourBy_, model::opt::colourBy);
    connect(colourBy_, &QComboBox::activated, this, [this](int i) {
        emit settingEdited(QLatin1String(model::opt::colourBy.key), i == 0 ? QString() : colourBy_->currentText());
    });
    form->addRow(tr(model::opt::colourBy.label), colourBy_);

    floorCheck_ = new QCheckBox(tr("draw where the variable is masked"), this);
    floorCheck_->setObjectName(QLatin1String(model::opt::floor.key));
    configure(floorCheck_, model::opt::floor);
    connect(floorCheck_, &QCheckBox::toggled, this, [this](bool on) {
        if (!updating_) emit settingEdited(QLatin1String(model::opt::floor.key), on ? QStringLiteral("on") : QString());
    });
    form->addRow(tr(model::opt::floor.label), floorCheck_);
}

void OceanPanel::showState(const StudioState& state, const InputInfo& info) {
    updating_ = true;
    std::string text;
    settingText(state, model::opt::region, text);
    regionCheck_->setChecked(!text.empty());
    double r[4] = {info.lonLat[0], info.lonLat[1], info.lonLat[2], info.lonLat[3]};
    if (!text.empty()) std::sscanf(text.c_str(), "%lf,%lf,%lf,%lf", &r[0], &r[1], &r[2], &r[3]);
    for (int i = 0; i < 4; ++i) {
        region_[i]->setValue(r[i]);
        region_[i]->setEnabled(!text.empty());
    }
    regionCheck_->setEnabled(!info.polar || !text.empty());

    settingText(state, model::opt::depthRange, text);
    depthCheck_->setChecked(!text.empty());
    double d[2] = {info.depths[0], info.depths[1]};
    if (!text.empty()) std::sscanf(text.c_str(), "%lf,%lf", &d[0], &d[1]);
    for (int i = 0; i < 2; ++i) {
        depths_[i]->setValue(d[i]);
        depths_[i]->setEnabled(!text.empty());
    }

    settingText(state, model::opt::verticalScale, text);
    scaleAuto_->setChecked(text.empty());
    scale_->setValue(text.empty() ? info.verticalScale : std::stod(text));
    scale_->setEnabled(!text.empty());

    settingText(state, model::opt::mapProjection, text);
    projection_->setCurrentText(QString::fromStdString(text.empty() ? model::opt::mapProjection.defaultChoice() : text));

    settingText(state, model::opt::colourBy, text);
    colourBy_->clear();
    colourBy_->addItem(tr("(height: the colour map)"));
    for (const QString& v : info.variables)
        if (v != info.variable) colourBy_->addItem(v);
    colourBy_->setCurrentIndex(text.empty() ? 0 : std::max(0, colourBy_->findText(QString::fromStdString(text))));

    settingText(state, model::opt::floor, text);
    floorCheck_->setChecked(!text.empty());
    updating_ = false;
}

void OceanPanel::regionEdited() {
    if (updating_) return;
    const bool on = regionCheck_->isChecked();
    for (QDoubleSpinBox* b : region_) b->setEnabled(on);
    emit settingEdited(QLatin1String(model::opt::region.key),
                       on ? QStringLiteral("%1,%2,%3,%4").arg(number(region_[0]->value()), number(region_[1]->value()),
                                                              number(region_[2]->value()), number(region_[3]->value()))
                          : QString());
}

void OceanPanel::depthRangeEdited() {
    if (updating_) return;
    const bool on = depthCheck_->isChecked();
    for (QDoubleSpinBox* b : depths_) b->setEnabled(on);
    emit settingEdited(QLatin1String(model::opt::depthRange.key),
                       on ? QStringLiteral("%1,%2").arg(number(depths_[0]->value()), number(depths_[1]->value())) : QString());
}

void OceanPanel::scaleEdited() {
    if (updating_) return;
    scale_->setEnabled(!scaleAuto_->isChecked());
    emit settingEdited(QLatin1String(model::opt::verticalScale.key), scaleAuto_->isChecked() ? QString() : number(scale_->value()));
}

}  // namespace octrace::studio
