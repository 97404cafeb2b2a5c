#pragma once
/// @file FieldRequest.h
/// What a caller asks a field reader for: which variable, which geographic region, which
/// vertical exaggeration, which DICOM series. Plain data, no GDAL or VTK types.
#include <array>
#include <cstdint>
#include <functional>
#include <string>

namespace octrace::io {

/// What an interactive caller gives a read (model::BuildHooks fills it): `progress` of the
/// read, 0..1, non-decreasing, 1 once the samples are in (DICOM: per file scanned and per file
/// decoded; NIfTI: per slice of the volume read; the other formats do not report), and
/// `cancelled`, asked between files or slices: true stops the read with CancelledError.
/// Either may be empty. Both are called on the reading thread.
struct ReadHooks {
    std::function<void(double)> progress;
    std::function<bool()> cancelled;

    void report(double fraction) const {
        if (progress) progress(fraction);
    }
    /// @throws CancelledError "`what`: read cancelled" when cancelled() says so.
    void checkCancelled(const std::string& what) const;
};

struct FieldRequest {
    /// Variable to read. Empty: the file's only 3-D variable (an error if it has several);
    /// with `acceptPlanar` and no 3-D variable, its only 2-D one.
    std::string variable;
    /// Accept a 2-D field (NetCDF: two spatial dimensions longer than 1, e.g. `sst(lat, lon)` or
    /// OISST's `sst(time, zlev = 1, lat, lon)`) and read it as a map, a ScalarField with
    /// `planar` set and one sample along z. Slices set it; a surface needs a 3-D field, so
    /// without it a 2-D field is refused with a message that says to draw it with slice.
    bool acceptPlanar = false;
    /// When true, only grid points inside `region` are read (geographic grids only).
    bool hasRegion = false;
    /// LON0, LON1, LAT0, LAT1 in degrees. LON1 < LON0 crosses the dateline (170,-170 is
    /// the same region as 170,190). LAT0 < LAT1.
    double region[4] = {0.0, 0.0, 0.0, 0.0};
    /// World z = -depth_km * verticalScale. 0 chooses the default (depth extent = a quarter of
    /// the larger horizontal extent); negative values are refused.
    double verticalScale = 0.0;
    /// Time step of a variable with a time axis (NetCDF only): a 0-based index ("3") or an ISO
    /// date ("1990-07-15", "1990-07-15T12:00"), decoded in the axis's CF calendar; a date
    /// selects the nearest step. Empty: the first step.
    std::string time;
    /// When true, only depth levels in depthRange[0]..depthRange[1] (metres, positive down,
    /// inclusive) are read (geographic grids only).
    bool hasDepthRange = false;
    double depthRange[2] = {0.0, 0.0};
    /// DICOM series to read: SeriesInstanceUID, 1-based index in `octrace info`'s list, or
    /// SeriesDescription. Empty: the largest series. Refused for other formats.
    std::string series;
    /// Volume of a multi-volume DICOM series (time points, echoes, ...) or of a 4-D NIfTI
    /// image, 0-based. -1: volume 0, said with log::info when there are several. Refused for
    /// the other formats.
    int volume = -1;
    /// Memory budget in bytes (see octrace/util/Memory.h); 0 = no limit. A read whose samples
    /// (with the reader's own buffers) would need more is refused with LimitError before
    /// anything that size is allocated.
    std::uint64_t memoryBudget = 0;
    /// Curvilinear grids (2-D longitude/latitude): lattice points along the larger horizontal
    /// extent of the regular lattice they are resampled onto; the octree's 2^depth + 1 when
    /// reading for an octree. 0: about the source grid's own spacing.
    int horizontalSamples = 0;
    /// Horizontal mapping of a geographic grid (`map_projection`): Auto is polar stereographic when
    /// the region (else the grid) lies in one hemisphere and reaches 75 degrees or more towards
    /// its pole, else the contract's lon x cos(lat0) mapping; LonLat and Polar force one.
    enum class Projection { Auto, LonLat, Polar };
    Projection projection = Projection::Auto;
    /// Progress and cancellation of the read (not a setting: no option names it).
    ReadHooks hooks;
};

/// The `horizontalSamples` that match an octree of `depth`: 2^depth + 1 (depth clamped to 1..12).
inline int latticeSamplesForDepth(int depth) { return (1 << (depth < 1 ? 1 : depth > 12 ? 12 : depth)) + 1; }

/// Parses "LON0,LON1,LAT0,LAT1" (degrees) and checks the values (see checkRegion).
/// @throws UsageError naming the text and the problem.
std::array<double, 4> parseRegion(const std::string& text);

/// Parses "Z0,Z1" (metres, positive down, Z0 < Z1). @throws UsageError.
std::array<double, 2> parseDepthRange(const std::string& text);

/// Checks that `text` is a time index (digits) or an ISO date YYYY-MM-DD[THH:MM[:SS]].
/// @throws UsageError.
void checkTimeText(const std::string& text);

/// Checks LON0..LON1 spans more than 0 and at most 360 degrees once unwrapped, and
/// -90 <= LAT0 < LAT1 <= 90. `what` prefixes the message (e.g. the input path).
/// @throws UsageError.
void checkRegion(const double region[4], const std::string& what);

}  // namespace octrace::io
