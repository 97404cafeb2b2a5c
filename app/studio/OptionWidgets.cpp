#include "OptionWidgets.h"

#include <QDoubleSpinBox>
#include <QSpinBox>
#include <QString>

#include <climits>
#include <cmath>

namespace octrace::studio {

void configure(QWidget* widget, const model::Option& o) {
    widget->setProperty(kOptionProperty, QString::fromLatin1(o.key));
    QString tip = QString::fromStdString(model::sayForStudio(o.helpLine()));
    if (!tip.isEmpty()) tip[0] = tip[0].toUpper();
    if (*o.flag) tip += QStringLiteral(" (the CLI's --%1)").arg(QLatin1String(o.flag));
    widget->setToolTip(tip);
}

void configure(QSpinBox* box, const model::Option& o) {
    configure(static_cast<QWidget*>(box), o);
    // Open ends of an integer option are the next whole number inside.
    const double lo = o.minOpen ? std::floor(o.min) + 1 : std::ceil(o.min);
    const double hi = o.maxOpen ? std::ceil(o.max) - 1 : std::floor(o.max);
    box->setRange(std::isfinite(lo) ? int(lo) : INT_MIN, std::isfinite(hi) ? int(hi) : INT_MAX);
}

void configure(QDoubleSpinBox* box, const model::Option& o, int decimals) {
    configure(static_cast<QWidget*>(box), o);
    box->setDecimals(decimals);
    const double step = std::pow(10.0, -decimals);
    const double big = 1e12;
    const double lo = std::isfinite(o.min) ? o.min + (o.minOpen ? step : 0.0) : -big;
    const double hi = std::isfinite(o.max) ? o.max - (o.maxOpen ? step : 0.0) : big;
    box->setRange(lo, hi);
}

}  // namespace octrace::studio
