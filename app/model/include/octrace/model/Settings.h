#pragma once
/// @file Settings.h
/// How a setting's value, given as text, lands in the pipeline's specs: one function per
/// option of the table, shared by every front end. The CLI hands it the text after a flag, a
/// session file its stored text, Python the text of a keyword's value (a tuple joined by the
/// separator the table's argument shows: "1,2,3", "800x600"). Each parses with the option's
/// own rules and the table's limits and throws UsageError naming the option's key ("`fov`: 180
/// is outside (0, 180) degrees"), which each front end words as its own (sayForCli, ...).
#include "octrace/model/Figure.h"
#include "octrace/model/OptionTable.h"
#include "octrace/model/Render.h"
#include "octrace/model/Surface.h"

#include "octrace/util/Math.h"

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace octrace::model {

struct SliceSpec;  // Slice.h

/// Where a job's settings land. A front end points at the parts its command has; a setting
/// whose part is missing is not the command's (applySetting returns false).
struct SettingTargets {
    SurfaceSpec* surface = nullptr;
    RenderSpec* render = nullptr;
    FigureSettings* figure = nullptr;
    /// Where the settings of what to read land (`var`, `region`, `time`, ...): null for the
    /// surface's request. For a command without a surface (info), `max_memory` lands here too
    /// (FieldRequest::memoryBudget); with a surface in SurfaceSpec::maxMemory.
    io::FieldRequest* request = nullptr;
    /// A slice (Slice.h): its own settings (`plane`, `at`, `index`) and those it shares with
    /// the surface and the view under the same names (`window`, `colormap`, `size`,
    /// `background`, ...) land here; what to read and the figure land in its request and
    /// figure unless `request` or `figure` is given.
    SliceSpec* slice = nullptr;
};

/// Which part of a job a setting belongs to: what to read (FieldRequest), the surface
/// (SurfaceSpec), how it is drawn (RenderSpec), its figure (FigureSettings); None for the
/// settings a front end keeps (`verify`, `repeat`, a command's own such as `format`); Slice for
/// those only a slice has (`plane`, `at`, `index`).
enum class SettingPart { None, Request, Surface, Render, Figure, Slice };
SettingPart settingPart(const Option& o);
/// Whether a slice takes the setting (applySetting with SettingTargets::slice): its own, those
/// it shares with the surface and the view, what to read, and the figure's that `octrace slice`
/// takes.
bool sliceSetting(const Option& o);
/// Whether a surface setting is read only when a frame is shaded (applyColour, applyLighting:
/// colours, colour map and range, lighting), so that changing it needs no rebuild.
bool shadingSetting(const Option& o);

/// Sets option `o` from `text` in `targets` (a Flag ignores `text`): parsed by the option's
/// rules, checked against the table. Repeatable options (`cut`, `bake_light`) add one value per
/// call. @returns false when no target holds the option (the front end's own settings, such as
/// `verify` or `repeat`, and the options of a part the command lacks). @throws UsageError
/// naming `o.key`.
bool applySetting(const Option& o, const std::string& text, const SettingTargets& targets);

/// The separator of a value with several parts, from the option's argument ("R,G,B" -> ',',
/// "WxH" -> 'x'), or 0 for a value of one part.
char valueSeparator(const Option& o);

// The value parsers behind applySetting, for the settings a front end keeps to itself; each
// throws UsageError naming `o.key` and the text.
/// "X,Y,Z", each a finite number.
dvec3 parseVec3(const Option& o, const std::string& text);
/// A colour: "R,G,B" or (allowAlpha) "R,G,B,A", each in [0,1] (sRGB display values, as a user
/// picks a colour); "#RRGGBB" or "#RGB" (and with allowAlpha "#RRGGBBAA"); or a CSS colour name
/// ("steelblue", any case, spaces ignored). Alpha is 1 unless given.
vec4 parseColour(const Option& o, const std::string& text, bool allowAlpha);
/// The CSS Color Level 4 colour `name` (any case; spaces, '_' and '-' ignored) in sRGB [0,1].
std::optional<vec3> namedColour(std::string_view name);
/// Every accepted colour name, sorted.
std::vector<std::string> colourNames();
/// "WxH", each within `width`'s and `height`'s ranges.
void parseSize(const Option& o, const std::string& text, int& w, int& h);
/// "WxH" with a unit mm, cm or in ("180x120mm", "7x5in"), in inches, each side at most 100 in.
dvec2 parsePrintSize(const Option& o, const std::string& text);
/// "MIN,MAX", finite, MIN < MAX, within float range.
dvec2 parseRange(const Option& o, const std::string& text);
/// "MIN,MAX", each a number with an optional unit (parseQuantity: "5degC,20degC"); finite,
/// within float range, MIN < MAX when both are in the same units (else checked once converted).
std::pair<Quantity, Quantity> parseQuantityRange(const Option& o, const std::string& text);
/// A memory size: a positive number of bytes with an optional suffix K, M, G, T or KiB, MiB,
/// GiB, TiB (powers of 1024, any case; "1.5G" is allowed), or N% of the physical memory.
std::uint64_t parseByteSize(const Option& o, const std::string& text);

}  // namespace octrace::model
