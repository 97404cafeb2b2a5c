#pragma once
// The studio's controls of settings in the options table (model/OptionTable.h): their ranges,
// tooltips and defaults come from the table, and each control carries the option's key in the
// property kOptionProperty, so that tests find the control of an option and read its range back.
#include "octrace/model/OptionTable.h"

class QDoubleSpinBox;
class QSpinBox;
class QWidget;

namespace octrace::studio {

inline constexpr const char* kOptionProperty = "octraceOption";

/// An integer option: range [min, max] of the table, its tooltip, its key.
void configure(QSpinBox* box, const model::Option& o);
/// A number option shown with `decimals` decimals: range from the table, an open end moved
/// inside by one step of the last decimal (fov (0, 180) -> 0.1 .. 179.9 at one decimal).
void configure(QDoubleSpinBox* box, const model::Option& o, int decimals);
/// Any other control of an option (a check box, a combo box): its tooltip and its key.
void configure(QWidget* widget, const model::Option& o);

}  // namespace octrace::studio
