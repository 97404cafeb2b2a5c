#pragma once
// Which samples of a NetCDF variable make a ScalarField (internal, no GDAL types): the roles of
// its dimensions by CF rules, the time step, the region and depth range, the geographic mapping,
// and the reading of those samples with CF masking and unpacking. NetcdfReader reads one
// variable through it; SoundSpeedField reads two on the same layout.
#include "netcdf/GeoGrid.h"
#include "netcdf/CfSource.h"
#include "netcdf/CurvilinearGrid.h"
#include "netcdf/VerticalFormula.h"

#include "octrace/build/ScalarField.h"
#include "octrace/io/FieldRequest.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace octrace::io::detail {

/// Layout::dim of a map's z, which no dimension of the variable makes.
constexpr std::size_t kNoDimension = std::size_t(-1);

struct Layout {
    std::array<std::size_t, 3> dim{};  ///< the variable's dimensions that make x, y, z (a map's z: kNoDimension)
    bool planar = false;  ///< a 2-D field read as a map: one sample along z (FieldRequest::acceptPlanar)
    std::array<AxisSelection, 3> axes;
    std::vector<std::uint64_t> fixedIndex;  ///< per dimension: the index read along a non-spatial one
    std::vector<std::string> notes;
    std::string timeLabel;  ///< the time step read (ScalarField::timeLabel); empty without time
    std::string warning;  ///< said by shapeField once the grid is known to be sound (e.g. index axes)
    bool geographic = false;
    // Geographic grids only, per output sample along y and z:
    std::vector<double> latitudeDeg;  ///< latitude of each y
    std::vector<double> depthM;       ///< depth of each z, metres, positive down
    std::vector<double> levelDbar;    ///< pressure of each z when the vertical axis is pressure, else empty
    std::string latitudeAxis, verticalAxis;  ///< dimension names, for messages
    double lon0 = 0.0, lat0 = 0.0, verticalScale = 1.0;  ///< the mapping (ScalarField::Geographic)
    int pole = 0;                ///< polar stereographic mapping (ScalarField::Geographic::pole), 0: lon/lat
    double x0 = 0.0, y0 = 0.0;   ///< its plane position of the world origin (km)
    /// Curvilinear grids, and every grid in the polar mapping (a regular grid then as
    /// CurvilinearGrid::fromAxes): x and y are a regular lattice resampled from the 2-D grid over
    /// dimensions dim[0] (x) and dim[1] (y) of the variable; readSamples goes through it.
    std::shared_ptr<const CurvilinearGrid> curvilinear;
    /// A parametric vertical coordinate (VerticalFormula.h): each selected column's native
    /// depths; axes[2].stored then indexes `latticeM`, the depths (m) every column is
    /// resampled onto, and readSamples reads all native levels. Null on z-level grids.
    std::shared_ptr<const ColumnDepths> columns;
    std::vector<double> latticeM;
};

/// The layout of `var` for `req`: spatial axes by CF rules (1-D coordinate variables, the
/// `coordinates` attribute, units, standard_name, axis, positive), the time step `req.time`
/// (index or date in the axis's calendar; default the first, with a warning), the first index
/// of any other extra dimension (with a warning), region and depth range on geographic grids.
/// A variable with two dimensions longer than 1 besides time is a map (Layout::planar) when
/// `req.acceptPlanar`, at its vertical dimension of length 1 if it has one, else at depth 0.
/// A curvilinear grid (2-D longitude/latitude) is resampled onto a regular lattice
/// (CurvilinearGrid) of `req.horizontalSamples` points along its larger extent.
/// @throws InputError (unusable 2-D coordinates, a 2-D field without acceptPlanar, fewer than 2 spatial axes, --time without a time axis or out
///         of range, a region or depth range on a non-geographic grid), FileError, UsageError,
///         EmptyResultError as NetcdfReader::read.
Layout layoutFor(const std::string& path, const CfSource& file, const VariableInfo& var, const FieldRequest& req);

/// A field shaped by `L` (dims, origin, spacing or rectilinear coordinates), without samples,
/// named after `var`; checks the sample count and that `bytesPerSample` of reading fit
/// `req.memoryBudget` (LimitError).
ScalarField shapeField(const std::string& path, const VariableInfo& var, const Layout& L, const FieldRequest& req,
                       std::uint64_t bytesPerSample);

/// Reads the samples of `var` selected by `L` into `f` (shaped by shapeField). A raw sample
/// equal to a missing value, outside the valid range or not finite is invalid (masked before
/// unpacking, CF 2.5.1); the others become raw * scale + offset.
void readSamples(const CfSource& file, const VariableInfo& var, const Layout& L, const SampleRules& rules,
                 ScalarField& f);

/// Bytes per sample that reading one variable needs: its float, its mask byte and the double
/// GDAL reads it into.
constexpr std::uint64_t kReadBytesPerSample = sizeof(float) + 1 + sizeof(double);

/// Variables with the 2-D longitude/latitude coordinates of `var` (a curvilinear grid), by its
/// `coordinates` attribute or, without one, by 2-D variables over its dimensions whose units or
/// standard_name say longitude or latitude. Empty for a grid with 1-D axes.
std::vector<const VariableInfo*> curvilinearCoordinates(const CfSource& file, const VariableInfo& var);

}  // namespace octrace::io::detail
