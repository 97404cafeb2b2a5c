#pragma once
// The ocean controls of the side panel, shown for a geographic field (NetCDF longitude,
// latitude, depth): the CLI's `region` as lon/lat boxes, `depth_range`, `vertical_scale`,
// `map_projection`, `colour_by` and `floor`. Each control is made from its option in the table
// (label, tooltip, range; OptionWidgets.h) and says a change as the CLI's text of the option
// (settingEdited), which the window keeps in StudioState::settings; "" is the default.
#include <QGroupBox>
#include <QString>

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;

namespace octrace::studio {

struct InputInfo;
struct StudioState;

class OceanPanel : public QGroupBox {
    Q_OBJECT
public:
    explicit OceanPanel(QWidget* parent = nullptr);

    /// Shows `state`'s settings; where one is not given, what the field read `info` spans
    /// (its lon/lat box, its depths, its vertical scale). The variables of `info` are the
    /// choices of Colour by.
    void showState(const StudioState& state, const InputInfo& info);

signals:
    /// The option `key` (the table's) set to `text` as the CLI takes it; "" for its default.
    void settingEdited(const QString& key, const QString& text);

private:
    void regionEdited();
    void depthRangeEdited();
    void scaleEdited();

    QCheckBox *regionCheck_ = nullptr, *depthCheck_ = nullptr, *scaleAuto_ = nullptr, *floorCheck_ = nullptr;
    QDoubleSpinBox* region_[4] = {nullptr, nullptr, nullptr, nullptr};  // W, E, S, N
    QDoubleSpinBox* depths_[2] = {nullptr, nullptr};
    QDoubleSpinBox* scale_ = nullptr;
    QComboBox *projection_ = nullptr, *colourBy_ = nullptr;
    bool updating_ = false;
};

}  // namespace octrace::studio
