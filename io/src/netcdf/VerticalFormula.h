#pragma once
// Vertical coordinates whose depths differ from column to column (internal, no GDAL types):
// CF parametric coordinates (CF 4.3.3 and Appendix D: the vertical coordinate variable's
// `standard_name` names the formula, its `formula_terms` attribute the variables of each term)
// and depths the file gives outright (a 3-D or 4-D depth variable named in the field's
// `coordinates` attribute, e.g. z* or time-varying layers). Each column's depths are
// computed, then every column is resampled onto one vertical lattice, so that the rest of the
// reader sees a z-level grid. NetcdfLayout hooks it in (layoutFor, readSamples); the rules are
// in docs/dev/ocean.md, "Parametric vertical coordinates".
#include "netcdf/CfSource.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace octrace::io::detail {

/// One "term: variable" pair of a `formula_terms` attribute.
struct FormulaTerm {
    std::string term, variable;
};

/// Parses a CF `formula_terms` attribute, "s: s_rho C: Cs_r eta: zeta depth: h depth_c: hc"
/// (white space around the colon tolerated, as in "s : s_rho"). @throws InputError prefixed
/// by `what` when a term has no variable, a variable no term, or a term comes twice.
std::vector<FormulaTerm> parseFormulaTerms(const std::string& text, const std::string& what);

/// The variables `formula_terms` attributes of `file` name (malformed attributes skipped): the
/// terms of a vertical coordinate, never offered as the field to draw.
std::vector<std::string> formulaTermVariables(const CfSource& file);

/// Which formula turns a column's terms into depths.
enum class VerticalKind {
    SigmaG1,      ///< ocean_s_coordinate_g1 (ROMS Vtransform = 1)
    SigmaG2,      ///< ocean_s_coordinate_g2 (ROMS Vtransform = 2)
    Sigma,        ///< ocean_sigma_coordinate
    DoubleSigma,  ///< ocean_double_sigma_coordinate
    SCoordinate,  ///< ocean_s_coordinate (Song and Haidvogel 1994)
    GivenDepth,   ///< depths given by a variable named in `coordinates`
};

/// A vertical coordinate with its own depths per column, as found for one field variable.
struct ParametricVertical {
    VerticalKind kind = VerticalKind::Sigma;
    std::string formula;                 ///< the standard_name, or "depths given by 'depth'"
    std::string coordinateVariable;      ///< the vertical coordinate variable (or the depth variable)
    std::vector<FormulaTerm> terms;      ///< empty for GivenDepth
    double givenToM = 1.0;               ///< GivenDepth: metres per unit, times -1 for a height
    /// "ocean_s_coordinate_g2 (s: s_rho, C: Cs_r, eta: zeta, depth: h, depth_c: hc)".
    std::string text() const;
};

/// The parametric vertical coordinate of `var` along its dimension `verticalDim`, if any:
/// the dimension's coordinate variable with a known formula `standard_name` and a
/// `formula_terms` attribute, else a variable of 3 or more dimensions, named in `var`'s
/// `coordinates` attribute, over `verticalDim`, whose units, standard_name or `positive` say
/// depth or height. nullopt for a plain z-level axis.
/// @throws InputError naming `path`, the coordinate variable and the problem: a known formula
///         without `formula_terms`, a malformed one, a term the formula needs missing from it.
std::optional<ParametricVertical> findParametricVertical(const std::string& path, const CfSource& file,
                                                         const VariableInfo& var, std::size_t verticalDim);

/// The depths of the columns of a field: metres, positive down, per native level k (in the
/// file's order) of each selected column (j, i).
struct ColumnDepths {
    std::size_t nk = 0, ny = 0, nx = 0;
    std::vector<double> depth;    ///< nk*ny*nx, index (k*ny + j)*nx + i; NaN where undefined
    std::vector<double> top;      ///< ny*nx: the sea surface's depth (-eta); NaN: no column
    std::vector<double> bottom;   ///< ny*nx: the sea floor's depth (the `depth` term); NaN: no column
    std::size_t badColumns = 0;   ///< columns left out: depths not finite or not monotonic
};

/// Which samples of the field variable a column of the output grid comes from.
struct ColumnSelection {
    std::array<std::size_t, 3> dim{};       ///< the field's dimensions that make x, y, z
    std::vector<std::uint64_t> fixedIndex;  ///< per field dimension: the index read along a non-spatial one (time)
    std::vector<std::size_t> x, y;          ///< stored indices per output column
};

/// Evaluates `p` for the columns `sel` of `var`: reads each term (at the field's time step
/// where the term has a time dimension), checks that its dimensions are the field's with the
/// same sizes, and computes z by the formula of CF Appendix D (depth = -z).
/// @throws InputError naming `path`, the term and its variable: a variable the file lacks,
///         dimensions that do not match the field's; FileError when reading fails;
///         LimitError when the terms do not fit `memoryBudget` (bytes, 0 = no limit).
ColumnDepths evaluateColumns(const std::string& path, const CfSource& file, const VariableInfo& var,
                             const ParametricVertical& p, const ColumnSelection& sel, std::uint64_t memoryBudget);

/// The lattice every column is resampled onto: depths in metres, increasing, from the
/// shallowest surface to the deepest floor; at each depth the step is the median over the
/// columns that reach it of their own level spacing there (at most kMaxLatticeLevels levels).
/// @throws EmptyResultError when no column has two levels.
std::vector<double> chooseLattice(const std::string& path, const ColumnDepths& c);

constexpr std::size_t kMaxLatticeLevels = 1024;

/// Resamples the native samples of column (j, i) (values[k * stride], valid[k * stride] in the
/// file's level order) to each of `depthM`, into out[n] and outValid[n] (1 = valid): linear
/// between the two native levels around a depth when both are valid, the nearest level's value
/// between the surface and the shallowest level or between the deepest level and the floor,
/// invalid above the surface, below the floor, next to an invalid level or in a column left
/// out. O(nk log nk + depths log nk).
void resampleColumn(const ColumnDepths& c, std::size_t j, std::size_t i, const double* values,
                    const std::uint8_t* valid, std::size_t stride, const std::vector<double>& depthM, double* out,
                    std::uint8_t* outValid);

}  // namespace octrace::io::detail
