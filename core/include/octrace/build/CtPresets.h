#pragma once
/// @file CtPresets.h
/// Named iso values and display windows for CT volumes, in Hounsfield units (HU: water 0,
/// air -1000). They mean something only for values in HU (a field whose units are "HU": a
/// DICOM CT series, after RescaleSlope/Intercept); callers refuse them for other fields.
/// docs/dev/medical.md says where each value comes from.
#include "octrace/build/ScalarField.h"

#include <optional>
#include <string>
#include <vector>

namespace octrace {

struct CtIsoPreset {
    const char* name;
    double hu;
    const char* what;
    vec3 colour;  ///< the tissue's colour, sRGB display values: the surface's unless a window greys it
};

/// --iso presets: skin -500 HU (halfway between air, -1000, and soft tissue, about 0: the air /
/// skin boundary); bone 300 HU (above contrast-free soft tissue and blood, below which
/// cancellous bone starts to fall apart into noise). Their colours are those of 3D Slicer's
/// generic anatomy colour table: skin 177,122,101, bone 241,214,145 (8-bit sRGB).
inline const std::vector<CtIsoPreset>& ctIsoPresets() {
    static const std::vector<CtIsoPreset> p = {
        {"skin", -500.0, "the air / skin boundary", vec3(177.0f, 122.0f, 101.0f) / 255.0f},
        {"bone", 300.0, "cortical and dense cancellous bone", vec3(241.0f, 214.0f, 145.0f) / 255.0f},
    };
    return p;
}

inline const CtIsoPreset* findCtIsoPreset(const std::string& name) {
    for (const auto& p : ctIsoPresets())
        if (name == p.name) return &p;
    return nullptr;
}

struct CtWindowPreset {
    const char* name;
    ValueWindow window;
};

/// --window presets (centre, width in HU), the usual radiology windows: brain 40/80,
/// soft-tissue 40/400, lung -600/1500, bone 400/1800.
inline const std::vector<CtWindowPreset>& ctWindowPresets() {
    static const std::vector<CtWindowPreset> p = {
        {"brain", {40.0, 80.0}},
        {"soft-tissue", {40.0, 400.0}},
        {"lung", {-600.0, 1500.0}},
        {"bone", {400.0, 1800.0}},
    };
    return p;
}

inline std::optional<double> ctIsoPreset(const std::string& name) {
    for (const auto& p : ctIsoPresets())
        if (name == p.name) return p.hu;
    return std::nullopt;
}

inline std::optional<ValueWindow> ctWindowPreset(const std::string& name) {
    for (const auto& p : ctWindowPresets())
        if (name == p.name) return p.window;
    return std::nullopt;
}

}  // namespace octrace
