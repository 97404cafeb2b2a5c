#pragma once
/// @file TimeAxis.h
/// The time axis of an input's field, read without its samples: what an animation needs to
/// choose its frames (app/model/Animation.h) and to caption them. Plain data, no GDAL types.
#include "octrace/io/FieldRequest.h"

#include <cstddef>
#include <string>
#include <vector>

namespace octrace::io {

struct TimeAxis {
    std::string path;      ///< the input, for messages
    std::string name;      ///< the time dimension's name; empty: the field has no time axis
    std::size_t size = 0;  ///< steps along it (0 without a time axis)
    std::string units;     ///< the coordinate's units as the file gives them ("days since 2000-01-01")
    std::string calendar;  ///< the CF calendar's name when `units` are CF time units, else ""
    std::vector<double> values;  ///< coordinate values; empty when the dimension has no coordinate variable
    /// Per step, the date as `octrace info` and `time`'s notes say it ("1990-01-15", or with
    /// the time of day when it is not midnight); "" when the axis has no CF time units.
    std::vector<std::string> dates;
    /// The steps are the volumes of a multi-volume DICOM series or of a 4-D NIfTI image (name
    /// "volume"): a step is chosen by FieldRequest::volume, not `time`.
    bool volumes = false;
    /// With `volumes`, per step what tells it apart ("temporal position 2"; "" for NIfTI).
    std::vector<std::string> labels;

    bool empty() const { return size == 0; }
    /// Whether the steps have dates (CF "UNIT since DATE" units that decode).
    bool dated() const { return !dates.empty() && !dates.front().empty(); }
    /// The coordinate value of `isoDate` (YYYY-MM-DD[THH:MM[:SS]]) in the axis's calendar.
    /// @throws UsageError (malformed date), InputError (the axis has no dates, or the date does
    ///         not exist in its calendar, e.g. 2001-02-29, or 2000-02-30 outside 360_day).
    double valueOf(const std::string& isoDate) const;
};

/// The dates of CF time coordinate `values` in `units` ("UNIT since DATE") and `calendar` (""
/// = standard), as TimeAxis::dates says them; every one "" when `units` are not CF time units.
/// For coordinates that come from elsewhere than a file (Python's DataArrays). @throws FileError
/// naming `what` (units or calendar that do not parse, a value that does not decode).
std::vector<std::string> timeDates(const std::vector<double>& values, const std::string& units, const std::string& calendar,
                                   const std::string& what);

/// The time axis of the field `req` asks for (its variable, or the file's only 3-D variable),
/// without reading samples. NetCDF: the variable's time dimension (by CF rules, as read() picks
/// it), of size 1 too; none (empty) when it has no time dimension. Other formats have none
/// but the volumes of a multi-volume DICOM series or of a 4-D NIfTI image (`volumes`; none for
/// a single volume).
/// @throws as readField() when the input cannot be opened or the variable is not found.
TimeAxis readTimeAxis(const std::string& path, const FieldRequest& req = {});

}  // namespace octrace::io
