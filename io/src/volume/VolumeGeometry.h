#pragma once
// Grid geometry shared by the volume readers (internal to octrace_io).
#include "octrace/build/ScalarField.h"

#include <cstdint>
#include <string>
#include <vector>

namespace octrace::io::detail {

/// Sets f.spacing and f.direction from three axis vectors (world step per sample along each
/// grid axis): their lengths and unit directions. A zero or non-finite vector, or two that
/// are not perpendicular (a sheared grid is not a ScalarField), is refused:
/// FileError "`what` of axes A and B are not perpendicular (D degrees): sheared grids are not supported".
void setAxes(const dmat3& axes, ScalarField& f, const std::string& what);

/// Marks NaN and inf samples invalid (f.valid filled only when there are some) with a note.
void markNonFinite(ScalarField& f);

/// Shortest text that reads back as the same double ("%.17g").
std::string exactNumber(double v);

/// The origin and spacing of `field` as a uniform grid, for a writer of `format`: an evenly
/// spaced rectilinear axis is folded into them, an uneven one refused. Also checks that the
/// field holds its samples. @throws OutputError "PATH: ...".
void uniformGrid(const ScalarField& field, const std::string& path, const std::string& format, dvec3& origin, dvec3& spacing);

/// Appends the samples as little-endian float32, invalid ones as NaN.
void appendFloatsLE(const ScalarField& field, std::vector<std::uint8_t>& out);

}  // namespace octrace::io::detail
