#pragma once
/// @file ScalarField.h
/// A scalar field sampled on a structured grid: the input of the octree builder.
///
/// Coordinates (the project's contract): sample (i,j,k) sits at
///   world = origin + direction * (axisX(i), axisY(j), axisZ(k))
/// where axisA(n) = n * spacing[A] for a uniform axis, or coords[A][n] for a rectilinear
/// axis (e.g. uneven ocean depth levels). Rectilinear coordinates are strictly increasing.
/// Samples are stored x fastest: index = i + dims.x * (j + dims.y * k).
#include "octrace/build/SampleBuffer.h"
#include "octrace/util/Math.h"

#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace octrace {

/// A display window (radiology's window level / width): values centre - width/2 .. centre +
/// width/2 map linearly to black .. white, values beyond are clamped. width <= 0: no window.
struct ValueWindow {
    double centre = 0.0, width = 0.0;
    bool valid() const { return width > 0.0; }
    /// Grey in [0,1] (display value) of `v`; `inverted`: low values bright (DICOM MONOCHROME1).
    float grey(float v, bool inverted) const { return float(greyValue(v, inverted)); }
    /// The same in double precision (no rounding before an 8-bit code is taken from it).
    double greyValue(double v, bool inverted) const;
};

class ScalarField {
public:
    ScalarField() = default;
    ScalarField(ScalarField&&) noexcept = default;
    ScalarField& operator=(ScalarField&&) noexcept = default;
    ScalarField(const ScalarField&) = delete;             // big buffers: move-only
    ScalarField& operator=(const ScalarField&) = delete;
    /// The one deep copy (samples, mask, geometry, provenance), for a caller that keeps a
    /// field and builds from copies of it (e.g. Python's Volume, shared by its surfaces).
    /// Borrowed samples are shared, not copied (SampleBuffer.h).
    ScalarField copy() const;

    std::string name;    ///< variable name ("TEMP", "density", ...)
    std::string units;   ///< units of the values ("deg C", "HU", ...); may be empty
    std::string standardName;  ///< CF standard_name ("sea_water_temperature"); may be empty
    std::string source;  ///< where it was read from (for messages)

    ivec3 dims{0};                      ///< samples per axis
    dvec3 origin{0.0};                  ///< world position of sample (0,0,0) before axis offsets
    dvec3 spacing{1.0};                 ///< uniform spacing per axis (ignored where coords[a] is set)
    dmat3 direction{1.0};               ///< columns: world direction of the grid axes (orthonormal)
    std::array<std::vector<double>, 3> coords;  ///< rectilinear axis positions (empty: uniform)

    /// dims.x*dims.y*dims.z samples, owned or read in place from another owner's memory (a
    /// NumPy array): SampleBuffer.h. Read a field through a const reference, so that reading
    /// never copies borrowed samples.
    SampleBuffer values;
    std::vector<std::uint8_t> valid;    ///< 1 = valid sample; empty means every sample is valid

    /// The window the file recommends for display (DICOM WindowCenter/WindowWidth, the first
    /// pair); invalid when it gives none.
    ValueWindow window;
    /// The file displays low values bright (DICOM PhotometricInterpretation MONOCHROME1): a
    /// window's grey is inverted. The values themselves are never inverted.
    bool invertedGrey = false;
    /// World coordinates are patient LPS in mm (x towards the patient's left, y posterior, z
    /// superior): DICOM series, NIfTI with a qform/sform (turned from RAS), NRRD whose space is
    /// left-posterior-superior. Slices are then named axial, coronal, sagittal and labelled
    /// with the patient's directions (SliceView.h).
    bool patientLps = false;
    /// A 2-D field read as a map (an SST or bathymetry grid, or a 3-D variable with a single
    /// vertical level): one sample along z (dims.z == 1, which validateGeometry allows only
    /// then). Slices draw it; a surface needs a 3-D field, and buildOctree refuses it.
    bool planar = false;

    /// Geographic grids (NetCDF longitude, latitude, depth): the contract's mapping to world
    /// kilometres, x = R (lon - lon0) cos(lat0), y = R (lat - lat0), z = -depth_km *
    /// verticalScale (R = kEarthRadiusKm, angles in radians), so that world points can be told
    /// in degrees and metres (figure ticks). `valid` is false on other grids.
    /// A region near a pole is mapped polar stereographic instead (`pole` +1 north, -1 south;
    /// 0 is the lon/lat mapping above): on the sphere of radius R, true scale at latitude
    /// `pole` x kPolarStandardParallel, rho = R (1 + sin 71 deg) tan(45 deg - |lat| / 2),
    /// x = rho sin(lon - lon0) - x0, y = -pole rho cos(lon - lon0) - y0, so lon0 is the
    /// central meridian (pointing to -y in the north, +y in the south) and (x0, y0) the
    /// projected centre of the region. docs/dev/ocean.md, "Polar regions".
    struct Geographic {
        static constexpr double kEarthRadiusKm = 6371.0;
        static constexpr double kPolarStandardParallel = 71.0;
        bool valid = false;
        double lon0 = 0.0, lat0 = 0.0, verticalScale = 1.0;
        int pole = 0;
        double x0 = 0.0, y0 = 0.0;
        bool polar() const { return pole != 0; }
    };
    Geographic geographic;

    /// The time step read, as a figure's subtitle tells it: its date ("1982-01-16 00:00:00")
    /// when the time axis has one, else "time step N of M"; empty when the input has no time
    /// (set by the NetCDF/Zarr reader where it selects the step).
    std::string timeLabel;

    /// Notes for `info` and stats (e.g. "geographic: lon0=150 lat0=35, vertical scale 30").
    std::vector<std::string> notes;

    std::size_t sampleCount() const {
        return std::size_t(dims.x) * std::size_t(dims.y) * std::size_t(dims.z);
    }
    std::size_t index(int i, int j, int k) const {
        return std::size_t(i) + std::size_t(dims.x) * (std::size_t(j) + std::size_t(dims.y) * std::size_t(k));
    }
    bool isValid(std::size_t idx) const { return valid.empty() || valid[idx] != 0; }
    bool isRectilinear(int axis) const { return !coords[axis].empty(); }

    /// Position of grid line n along axis a in the grid's local frame (before direction).
    double axisPosition(int a, int n) const {
        return coords[a].empty() ? n * spacing[a] : coords[a][std::size_t(n)];
    }
    /// World position of sample (i,j,k).
    dvec3 worldFromGrid(int i, int j, int k) const;
    /// Axis-aligned world bounding box of the grid (the 8 corners transformed).
    Box3 worldBounds() const;
    /// Minimum and maximum of the valid samples. Throws EmptyResultError if none is valid.
    std::pair<float, float> validRange() const;
    std::size_t validCount() const;

    /// Checks internal consistency (at least 2 samples per axis, 1 along z when `planar`; sizes, finite geometry, increasing coordinates,
    /// orthonormal direction, world coordinates within +-kMaxWorldCoordinate, a largest
    /// extent of at least kMinWorldExtent and of a billionth of the largest coordinate).
    /// Throws FileError naming `source` and the problem.
    void validate() const;
    /// The same checks but those of the samples and the mask: readers call it before they
    /// allocate the samples, so that an absurd header costs no memory.
    void validateGeometry() const;

    static constexpr double kMaxWorldCoordinate = 1e30;
    static constexpr double kMinWorldExtent = 1e-30;
};

}  // namespace octrace
