#pragma once
// Curvilinear horizontal grids (internal, no GDAL types): a variable whose longitude and
// latitude are 2-D auxiliary coordinates (CF 5.2; NEMO nav_lat/nav_lon, POP TLAT/TLONG, MOM6
// geolat/geolon, ROMS lat_rho/lon_rho, rotated-pole models with 2-D lat/lon) is resampled onto a
// regular longitude/latitude lattice, which then maps to world km as a regular grid does.
//
// How: every source cell (the quad between four neighbouring grid points, plus the quads across
// a periodic x seam and across a tripolar north fold) is rasterised onto the lattice in
// longitude/latitude, unwrapped around its first corner so that a cell across the dateline is
// one small quad; a lattice point inside it gets the cell's four corners and their bilinear
// weights by inverse bilinear mapping. Degenerate, folded or pole-enclosing cells are skipped.
// Per level, a lattice point takes the weighted mean of the ocean corners only; it is land when
// less than half of its weight is ocean (so the coastline stays where the source's is, and no
// value is ever interpolated across land). Why this and not a nearest-cell search:
// docs/dev/ocean.md, "Curvilinear grids".
#include "netcdf/CfSource.h"
#include "octrace/io/FieldRequest.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace octrace::io::detail {

class CurvilinearGrid {
public:
    /// Reads and checks the 2-D coordinates `coords` (from curvilinearCoordinates) of `var`.
    /// @throws InputError naming `path`, the variable and the coordinates when there is not
    ///         exactly one 2-D longitude and one latitude; FileError (a broken file) for a
    ///         coordinate whose dimensions are not two of the variable's (or differ between the
    ///         two), fewer than 2 x 2 points, a missing or non-finite coordinate, a latitude
    ///         outside -90..90, a longitude beyond +-10^4; FileError as CfSource::read.
    static CurvilinearGrid read(const std::string& path, const CfSource& file, const VariableInfo& var,
                                const std::vector<const VariableInfo*>& coords);

    /// A grid from its coordinates (ny x nx, x fastest), checked as `read` checks them; for
    /// tests and the fuzz target. @throws FileError naming `what`.
    static CurvilinearGrid fromCoordinates(const std::string& what, std::size_t ny, std::size_t nx,
                                           std::vector<double> lon, std::vector<double> lat);

    /// A regular grid's 1-D axes as a curvilinear grid (the polar mapping resamples both the
    /// same way): `lon` over the variable's dimension `lonDim`, `lat` over `latDim`, rows along
    /// the slower of the two. Never a tripolar fold. @throws FileError as fromCoordinates.
    static CurvilinearGrid fromAxes(const std::string& what, const std::vector<double>& lon, const std::vector<double>& lat,
                                    std::size_t lonDim, std::size_t latDim, const std::string& lonName,
                                    const std::string& latName);

    std::size_t yDim = 0, xDim = 0;  ///< the variable's dimensions the coordinates lie over (y slower)
    std::size_t ny = 0, nx = 0;      ///< source size
    std::string lonName, latName;    ///< coordinate signatures, for notes
    bool periodicX = false;          ///< the last column neighbours the first (a global grid)
    bool northFold = false;          ///< the top row neighbours itself mirrored (a tripolar grid)

    /// The lattice for `req`: its region, else the source's extent (the whole circle when the
    /// source goes round it). `samples` points along the larger extent (in km on the contract's
    /// mapping); 0 chooses about the source's own spacing. Longitudes increase from the
    /// region's west edge (unwrapped, may pass 180), latitudes increase.
    struct Lattice {
        std::vector<double> lon, lat;
        double lonStep = 0.0, latStep = 0.0;
        std::string how;  ///< how the step was chosen, for notes
    };
    Lattice lattice(const std::string& path, const FieldRequest& req, int samples) const;

    /// A lattice regular in the polar stereographic plane (PolarStereographic.h) of `pole`
    /// (+1 north, -1 south): over the bounding box of the region (else of the source's
    /// latitudes poleward of its equatorward edge, the whole circle), centred, `samples` points
    /// along the larger side as `lattice` chooses them; `inside` marks the points whose
    /// longitude and latitude lie in the region (the others stay empty).
    struct PlaneLattice {
        int pole = 0;
        double lon0 = 0.0;            ///< central meridian, degrees
        double x0 = 0.0, y0 = 0.0;    ///< plane position of the world origin (km)
        std::vector<double> x, y;     ///< world km (plane minus x0, y0), increasing, uniform
        std::vector<std::uint8_t> inside;  ///< x fastest
        double stepKm = 0.0;
        std::string how;
    };
    PlaneLattice planeLattice(const std::string& path, const FieldRequest& req, int pole, int samples) const;

    /// Builds the lookup onto a plane lattice: every source cell rasterised in the projected
    /// plane (no seam there: a cell across the dateline or around the pole is an ordinary quad),
    /// plus, on a periodic grid without a fold whose first or last row rings the pole within
    /// 10 degrees, the strips across that ring (row points i, i+1, i+n/2, i+n/2+1), so the pole
    /// is filled with the mean of opposite ring points. Points outside `lattice.inside` stay
    /// empty.
    void buildPlaneLookup(const PlaneLattice& lattice);
    /// For `info`, after buildPlaneLookup.
    std::string planeDescription(const PlaneLattice& lattice) const;

    /// Builds the lookup onto the lattice points lonOut x latOut (both increasing and uniform,
    /// longitudes unwrapped), x fastest. Not thread-safe with resample on the same object.
    void buildLookup(const std::vector<double>& lonOut, const std::vector<double>& latOut);

    /// One horizontal plane: `raw` holds ny x nx stored samples (x fastest); writes the
    /// resampled values and validity of the lattice (as built) into `values` and `valid`, each
    /// lonOut.size() * latOut.size() long.
    void resample(const std::vector<double>& raw, const SampleRules& rules, float* values, std::uint8_t* valid) const;

    /// The same weighting for samples already decoded: `values` and `valid` (1 = ocean) hold
    /// ny x nx source points; `out` gets the weighted mean of a lattice point's valid corners
    /// (NaN and outValid 0 where less than half the weight is valid). For what follows the
    /// field's cells, e.g. a parametric vertical coordinate's per-column depths.
    void resample(const double* values, const std::uint8_t* valid, double* out, std::uint8_t* outValid) const;

    /// The source coordinates, ny x nx (x fastest), degrees; the median cell size, degrees.
    const std::vector<double>& lon() const { return lon_; }
    const std::vector<double>& lat() const { return lat_; }
    double medianStepDeg() const;
    /// The smallest and largest latitude of the source, degrees.
    std::pair<double, double> latitudeRange() const;

    /// Lattice points inside some source cell, of all.
    std::size_t coveredPoints() const;
    std::size_t skippedCells() const { return skipped_; }

    /// For `info`: "curvilinear grid: 2-D coordinates ...; source ...; resampled onto ...".
    std::string description(const Lattice& lattice, std::size_t nxOut, std::size_t nyOut) const;

private:
    std::vector<double> lon_, lat_;  ///< ny x nx, degrees
    struct Weights {
        std::uint32_t corner[4];  ///< flat source indices; corner[0] == kNone: outside every cell
        float w[4];
    };
    static constexpr std::uint32_t kNone = 0xffffffffu;
    std::vector<Weights> lookup_;
    std::size_t skipped_ = 0;
    void check(const std::string& what);  // latitudes within +-90, sane longitudes; periodic and fold
    bool detectPeriodic() const;
    bool detectFold() const;
    void rasterise(const std::uint32_t corner[4], const std::vector<double>& lonOut, const std::vector<double>& latOut);
    // Rasterises the quad (qx, qy) of source corners `corner` onto the uniform axes xOut x yOut,
    // the quad shifted by each of `shifts` along x. Skips (and counts) a folded or collapsed quad;
    // `cosY` scales x for the convexity test (cos(lat) in longitude/latitude, 1 in a plane).
    void rasteriseQuad(const std::uint32_t corner[4], const double qx[4], const double qy[4], double cosY,
                       const std::vector<double>& shifts, const std::vector<double>& xOut, const std::vector<double>& yOut);
    bool poleCap_ = false;  // the last buildPlaneLookup added cells across a ring round the pole
};

}  // namespace octrace::io::detail
