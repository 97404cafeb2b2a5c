#pragma once
/// @file SliceView.h
/// Planar slices through a ScalarField, sampled from its samples (not from an octree) and
/// seen as a radiology workstation or a map shows them.
///
/// Screen conventions (world axes; for patient volumes world is LPS: x to the patient's left,
/// y posterior, z superior):
///  - Axial: seen from the feet, screen right = +x (patient's left), up = -y (anterior).
///  - Coronal (and Y): seen from the front, right = +x (left), up = +z (superior).
///  - Sagittal (and X): seen from the patient's left, right = +y (posterior), up = +z.
///  - Z: seen from above, right = +x (east on a geographic grid), up = +y (north).
/// These are 3D Slicer's default views. Nothing is mirrored: a pixel's world position is
/// `topLeft + px * right + py * down`.
#include "octrace/build/ScalarField.h"
#include "octrace/render/Frame.h"

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace octrace {

enum class SlicePlane { Axial, Coronal, Sagittal, X, Y, Z };

/// "axial", "coronal", "sagittal", "x", "y", "z".
const char* slicePlaneName(SlicePlane p);

/// The world axis (0 x, 1 y, 2 z) a plane is normal to.
int sliceNormalAxis(SlicePlane p);

/// Where a slice lies and how its pixels map to the world.
struct SliceView {
    SlicePlane plane = SlicePlane::Z;
    double position = 0.0;      ///< world coordinate along sliceNormalAxis(plane)
    dvec3 topLeft{0.0};         ///< world position of the centre of pixel (0, 0)
    dvec3 right{1.0, 0.0, 0.0};  ///< world step from a pixel to the next one to the right
    dvec3 down{0.0, -1.0, 0.0};  ///< world step from a pixel to the one below it
    double pixelSize = 1.0;     ///< |right| = |down|: pixels are square in world units
    int width = 0, height = 0;
    /// The grid axis closest to the plane's normal and the fractional sample index of the
    /// plane along it (an integer when the plane passes through samples of an aligned grid).
    int gridAxis = 2;
    double gridIndex = 0.0;
    /// The grid's extent in the image, in pixels (pixel centres at integers): the first and
    /// last sample positions along the screen's right (x) and down (y).
    dvec2 gridMin{0.0}, gridMax{0.0};
    /// How far the image's content reaches beyond the first and last samples, in pixels (half
    /// a sample of the finer in-plane spacing).
    double margin = 0.5;

    dvec3 world(double px, double py) const { return topLeft + px * right + py * down; }
    /// Unit directions of the screen's right and up in world space.
    dvec3 screenRight() const;
    dvec3 screenUp() const;
};

/// Unit screen right and up of a plane (the conventions above).
dvec3 sliceScreenRight(SlicePlane p);
dvec3 sliceScreenUp(SlicePlane p);

/// The view of `plane` at world coordinate `position` along its normal axis. The pixel size
/// is the finer of the spacings of the grid axes closest to the screen's right and up (the
/// mean step of a rectilinear axis), so anisotropic voxels keep their aspect; the image
/// covers the grid's extent in the plane plus half a pixel around. `width` x `height` > 0:
/// that image size instead, the slice scaled to fit and centred. @throws InputError when
/// `position` lies outside slicePositionRange.
SliceView makeSliceView(const ScalarField& f, SlicePlane plane, double position, int width = 0, int height = 0);

/// The grid axis closest to the plane's normal (the axis --index counts along).
int sliceGridAxis(const ScalarField& f, SlicePlane plane);

/// Where along the plane's normal (world) a plane of `plane` meets the grid: from its first to
/// its last sample, and half a step beyond each (the end step of that side on an uneven axis;
/// nothing beyond the one level of a planar field). makeSliceView refuses positions outside.
std::pair<double, double> slicePositionRange(const ScalarField& f, SlicePlane plane);

/// World coordinate along the plane's normal of grid sample `index` along the grid axis
/// closest to that normal (the middle sample: index = n / 2). @throws UsageError when `index`
/// is outside 0..n-1.
double slicePositionOfIndex(const ScalarField& f, SlicePlane plane, int index);

/// The continuous sample indices (i, j, k) of world point `p`: integers at the samples; beyond
/// the grid's ends by its first or last step (the studio's crosshair and probe).
dvec3 sliceGridPosition(const ScalarField& f, const dvec3& p);

/// What one pixel of a slice holds.
enum class SliceSample : std::uint8_t { Valid, Masked, Outside };

/// The field's values at the pixel centres (row-major, row 0 at the top): trilinear between
/// the 8 surrounding samples, or the nearest sample's value when one of them is masked (so a
/// mask's edge stays sharp); positions within half a sample of the grid are clamped onto it.
/// Pixels beyond the grid's extent in the image by more than SliceView::margin are Outside.
struct SliceValues {
    int width = 0, height = 0;
    std::vector<float> values;          ///< NaN where not Valid
    std::vector<SliceSample> state;
    /// Minimum and maximum of the valid values (NaN, NaN when none).
    std::pair<float, float> range() const;
};
SliceValues sampleSlice(const ScalarField& f, const SliceView& v, int threads = 0);

/// How values become colours.
struct SliceColouring {
    /// A display window (valid: grey = window.grey(v, invertedGrey), an sRGB display value
    /// quantized to 8 bits so that the PNG holds round(255 grey)); else the colour map.
    ValueWindow window;
    bool invertedGrey = false;
    std::string colormap = "viridis";  ///< Shading.h's maps, over [low, high], clamped
    double low = 0.0, high = 1.0;
    vec4 masked{0.6f, 0.6f, 0.6f, 1.0f};  ///< linear RGBA of Masked pixels
    vec4 outside{0.0f, 0.0f, 0.0f, 1.0f}; ///< linear RGBA of Outside pixels
};

/// The slice as an image (linear RGBA). @throws UsageError for an unknown colour map.
Frame colourSlice(const SliceValues& s, const SliceColouring& c);

}  // namespace octrace
