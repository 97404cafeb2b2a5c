#include "dicom/DicomSeries.h"

#include "input/InputFile.h"
#include "octrace/util/Error.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <numbers>

namespace octrace::io::detail {
namespace {

constexpr double kDirectionTolerance = 1e-4;  // cosines: the same orientation, perpendicular
constexpr double kSpacingTolerance = 0.01;    // relative: uniform slice distances, same pixel spacing
constexpr double kShearTolerance = 0.01;      // in pixels: a shift below this is no tilt

std::string imageName(const DicomHeader& h, int frame) {
    return h.frames.size() > 1 ? h.file + " (frame " + std::to_string(frame + 1) + ")" : h.file;
}

std::string vecText(dvec3 v) { return num(v.x) + "\\" + num(v.y) + "\\" + num(v.z); }

bool sameDirection(dvec3 a, dvec3 b) { return glm::length(a - b) <= kDirectionTolerance; }

// The series' orientation as unit row and column directions, checked.
void orientation(const DicomHeader& h, const DicomFrame& f, const std::string& what, dvec3& row, dvec3& col) {
    const double lr = glm::length(f.rowDir), lc = glm::length(f.colDir);
    if (!(lr > 0.5 && lr < 2.0 && lc > 0.5 && lc < 2.0) || !std::isfinite(lr) || !std::isfinite(lc))
        throw FileError(what + ": ImageOrientationPatient '" + vecText(f.rowDir) + "\\" + vecText(f.colDir) + "' of " +
                        h.file + " is not two unit vectors");
    row = f.rowDir / lr;
    col = f.colDir / lc;
    if (std::abs(glm::dot(row, col)) > 1e-3)
        throw FileError(what + ": ImageOrientationPatient of " + h.file + " has row and column directions at " +
                        num(std::acos(std::clamp(glm::dot(row, col), -1.0, 1.0)) * 180.0 / std::numbers::pi) +
                        " degrees, not perpendicular");
}

void checkSameGeometry(const std::vector<DicomHeader>& headers, const std::string& what) {
    const DicomHeader& h0 = headers.front();
    const DicomFrame& f0 = h0.frames.front();
    for (const DicomHeader& h : headers) {
        if (h.rows != h0.rows || h.columns != h0.columns)
            throw FileError(what + ": mixed image sizes in one series: " + h0.file + " is " + std::to_string(h0.columns) +
                            "x" + std::to_string(h0.rows) + ", " + h.file + " is " + std::to_string(h.columns) + "x" +
                            std::to_string(h.rows));
        for (std::size_t n = 0; n < h.frames.size(); ++n) {
            const DicomFrame& f = h.frames[n];
            if (f.hasOrientation != f0.hasOrientation ||
                (f.hasOrientation && (!sameDirection(f.rowDir, f0.rowDir) || !sameDirection(f.colDir, f0.colDir))))
                throw FileError(what + ": images of one series have different orientations: " + imageName(h, int(n)) +
                                " differs from " + h0.file + " (several stacks in one series are not supported)");
            if (f.hasPixelSpacing != f0.hasPixelSpacing ||
                glm::length(f.pixelSpacing - f0.pixelSpacing) > kSpacingTolerance * std::min(f0.pixelSpacing.x, f0.pixelSpacing.y))
                throw FileError(what + ": images of one series have different pixel spacings: " + imageName(h, int(n)) +
                                " has " + num(f.pixelSpacing.x) + "\\" + num(f.pixelSpacing.y) + ", " + h0.file + " " +
                                num(f0.pixelSpacing.x) + "\\" + num(f0.pixelSpacing.y));
        }
    }
}

// Slice distances: uniform, or the warning that says how they are not.
void checkDistances(SeriesLayout& L) {
    double lo = HUGE_VAL, hi = 0.0;
    for (std::size_t k = 1; k < L.z.size(); ++k) {
        lo = std::min(lo, L.z[k] - L.z[k - 1]);
        hi = std::max(hi, L.z[k] - L.z[k - 1]);
    }
    const double mean = L.z.back() / double(L.z.size() - 1);
    L.uniform = hi - lo <= kSpacingTolerance * mean;
    if (!L.uniform)
        L.warnings.push_back("slice distances are not uniform (" + num(lo) + " to " + num(hi) + " mm" +
                             (hi >= 1.5 * lo ? ": a missing slice?" : "") +
                             "); the true positions are kept as a rectilinear z axis");
}

constexpr double kSamePosition = 1e-3;  // mm along the normal: two images at one position

const DicomFrame& frameOf(const std::vector<DicomHeader>& headers, const SliceRef& s) {
    return headers[s.header].frames[std::size_t(s.frame)];
}

// The slice normal of the series (row x column of the first image; z without an orientation).
dvec3 seriesNormal(const std::vector<DicomHeader>& headers) {
    const DicomFrame& f0 = headers.front().frames.front();
    if (!f0.hasOrientation) return dvec3(0.0, 0.0, 1.0);
    const dvec3 n = glm::cross(f0.rowDir, f0.colDir);
    const double l = glm::length(n);
    return l > 0.0 && std::isfinite(l) ? n / l : dvec3(0.0, 0.0, 1.0);
}

// Each image's position along the normal as the index of a cluster of positions less than
// kSamePosition apart, clusters numbered from the lowest position; `where` gets each
// cluster's position. Images without a position are each a cluster of their own.
std::vector<std::size_t> positionClusters(const std::vector<DicomHeader>& headers, const std::vector<SliceRef>& images,
                                          std::vector<double>& where) {
    const dvec3 normal = seriesNormal(headers);
    std::vector<std::size_t> order(images.size());
    std::vector<double> z(images.size());
    for (std::size_t i = 0; i < images.size(); ++i) {
        const DicomFrame& f = frameOf(headers, images[i]);
        z[i] = f.hasPosition ? glm::dot(f.position, normal) : 1e12 + double(i);  // apart from any position and each other
        order[i] = i;
    }
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return z[a] < z[b]; });
    std::vector<std::size_t> cluster(images.size());
    where.clear();
    for (std::size_t k = 0; k < order.size(); ++k) {
        if (k == 0 || !(z[order[k]] - z[order[k - 1]] <= kSamePosition)) where.push_back(z[order[k]]);
        cluster[order[k]] = where.size() - 1;
    }
    return cluster;
}

// Orders two attribute values: as numbers when both are (every backslash-separated part),
// else as text.
bool valueLess(const std::string& a, const std::string& b) {
    const auto x = a.empty() ? std::nullopt : dicomNumbers(a), y = b.empty() ? std::nullopt : dicomNumbers(b);
    if (x && y) return *x < *y;
    return a < b;
}

struct KeyLess {
    bool operator()(const std::vector<std::string>& a, const std::vector<std::string>& b) const {
        for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) {
            if (valueLess(a[i], b[i])) return true;
            if (valueLess(b[i], a[i])) return false;
        }
        return a.size() < b.size();
    }
};

// The images grouped by the values of `attributes`, in KeyLess order of the values.
std::map<std::vector<std::string>, std::vector<SliceRef>, KeyLess> groupBy(const std::vector<DicomHeader>& headers,
                                                                          const std::vector<SliceRef>& images,
                                                                          const std::vector<int>& attributes) {
    std::map<std::vector<std::string>, std::vector<SliceRef>, KeyLess> groups;
    for (const SliceRef& s : images) {
        std::vector<std::string> key;
        for (int a : attributes) key.push_back(frameOf(headers, s).volumeKey[std::size_t(a)]);
        groups[key].push_back(s);
    }
    return groups;
}

std::string sliceCount(std::size_t n) { return std::to_string(n) + (n == 1 ? " slice" : " slices"); }

std::string volumeName(const std::vector<SeriesVolume>& volumes, std::size_t v) {
    return "volume " + std::to_string(v) + (volumes[v].label.empty() ? "" : " (" + volumes[v].label + ")");
}

}  // namespace

std::optional<std::vector<double>> dicomNumbers(const std::string& text) {
    std::vector<double> v;
    std::size_t start = 0;
    while (start <= text.size()) {
        std::size_t end = text.find('\\', start);
        if (end == std::string::npos) end = text.size();
        const std::string item = trim(text.substr(start, end - start));
        char* stop = nullptr;
        const double x = std::strtod(item.c_str(), &stop);
        if (item.empty() || *stop != '\0' || !std::isfinite(x)) return std::nullopt;
        v.push_back(x);
        start = end + 1;
    }
    return v;
}

const char* volumeAttributeName(int attribute) {
    static const char* const names[kVolumeAttributeCount] = {
        "temporal position", "trigger time", "stack", "echo", "echo time", "b-value", "gradient direction",
        "image type", "complex component", "dimension index"};
    return attribute >= 0 && attribute < kVolumeAttributeCount ? names[attribute] : "?";
}

std::vector<SeriesVolume> splitVolumes(const std::vector<DicomHeader>& headers) {
    std::vector<SliceRef> all;
    for (std::size_t h = 0; h < headers.size(); ++h)
        for (std::size_t n = 0; n < headers[h].frames.size(); ++n) all.push_back({h, int(n), dvec2(0.0)});
    std::vector<double> where;
    const std::vector<std::size_t> cluster = positionClusters(headers, all, where);
    std::vector<std::size_t> perPosition(where.size(), 0);
    for (std::size_t c : cluster) ++perPosition[c];
    const std::size_t repeats = perPosition.empty() ? 1 : *std::max_element(perPosition.begin(), perPosition.end());
    if (repeats <= 1) return {SeriesVolume{"", all}};

    // The attributes that split the images into at most `repeats` groups, each only if it splits further.
    std::vector<int> used;
    std::size_t groups = 1;
    for (int a = 0; a < kVolumeAttributeCount; ++a) {
        std::vector<int> trial = used;
        trial.push_back(a);
        const std::size_t n = groupBy(headers, all, trial).size();
        if (n > groups && n <= repeats) {
            used = trial;
            groups = n;
        }
    }
    std::vector<SeriesVolume> volumes;
    for (auto& group : groupBy(headers, all, used)) {
        // Named, not a structured binding: clang before 16 cannot capture one in the lambda below.
        const std::vector<std::string>& key = group.first;
        const std::vector<SliceRef>& images = group.second;
        std::string label;
        const std::string& dimensions = headers[images.front().header].dimensionNames;
        for (std::size_t i = 0; i < used.size(); ++i)
            label += (i ? ", " : "") + std::string(volumeAttributeName(used[i])) + " " + (key[i].empty() ? "(none)" : key[i]) +
                     (used[i] == kDimensionIndex && !dimensions.empty() ? " (" + dimensions + ")" : "");
        // Images still sharing a position: the first acquired at each position is in the first repeat.
        std::vector<std::size_t> at = positionClusters(headers, images, where);
        std::vector<std::vector<std::size_t>> byPosition(where.size());
        for (std::size_t i = 0; i < images.size(); ++i) byPosition[at[i]].push_back(i);
        std::size_t deepest = 0;
        for (auto& list : byPosition) {
            std::stable_sort(list.begin(), list.end(), [&](std::size_t a, std::size_t b) {
                return valueLess(frameOf(headers, images[a]).acquired, frameOf(headers, images[b]).acquired);
            });
            deepest = std::max(deepest, list.size());
        }
        if (deepest <= 1) {
            volumes.push_back({label, images});
            continue;
        }
        for (std::size_t r = 0; r < deepest; ++r) {
            SeriesVolume v;
            for (const auto& list : byPosition)
                if (r < list.size()) v.images.push_back(images[list[r]]);
            const std::string when = frameOf(headers, v.images.front()).acquired;
            v.label = label + (label.empty() ? "" : ", ") + "repeat " + std::to_string(r + 1) +
                      (when.empty() ? " (in file order)" : " (acquired " + when + ")");
            volumes.push_back(std::move(v));
        }
    }
    return volumes;
}

void checkVolumesAlike(const std::vector<DicomHeader>& headers, const std::vector<SeriesVolume>& volumes, const std::string& what) {
    if (volumes.size() < 2) return;
    std::vector<SliceRef> all;
    std::vector<std::size_t> owner;
    for (std::size_t v = 0; v < volumes.size(); ++v)
        for (const SliceRef& s : volumes[v].images) {
            all.push_back(s);
            owner.push_back(v);
        }
    std::vector<double> where;
    const std::vector<std::size_t> cluster = positionClusters(headers, all, where);
    std::vector<std::vector<bool>> has(volumes.size(), std::vector<bool>(where.size(), false));
    for (std::size_t i = 0; i < all.size(); ++i) has[owner[i]][cluster[i]] = true;
    // A hole inside a volume's own first..last slice is a missing slice.
    for (std::size_t v = 0; v < volumes.size(); ++v) {
        const auto lo = std::find(has[v].begin(), has[v].end(), true) - has[v].begin();
        const auto hi = has[v].rend() - std::find(has[v].rbegin(), has[v].rend(), true) - 1;
        for (auto c = lo; c <= hi; ++c)
            if (!has[v][std::size_t(c)]) {
                std::size_t other = 0;
                while (other < volumes.size() && !has[other][std::size_t(c)]) ++other;
                throw FileError(what + ": " + volumeName(volumes, v) + " is missing a slice: it has none at " +
                                num(where[std::size_t(c)]) + " mm along the slice normal, where " + volumeName(volumes, other) +
                                " has one (slice " + std::to_string(c + 1) + " of the series' " + std::to_string(where.size()) +
                                " positions); every volume of a series needs the same slices");
            }
    }
    for (std::size_t v = 1; v < volumes.size(); ++v)
        if (has[v] != has[0])
            throw FileError(what + ": " + volumeName(volumes, v) + " has " + sliceCount(volumes[v].images.size()) + ", " +
                            volumeName(volumes, 0) + " has " + sliceCount(volumes[0].images.size()) +
                            " at other positions: every volume of a series needs the same slices");
    for (std::size_t v = 0; v < volumes.size(); ++v)
        if (volumes[v].images.size() != where.size())
            throw FileError(what + ": " + volumeName(volumes, v) + " has " + sliceCount(volumes[v].images.size()) + " at " +
                            std::to_string(where.size()) + " positions: several images of it lie at one position");
}

SeriesLayout layoutSeries(const std::vector<DicomHeader>& headers, const std::string& what, const std::vector<SliceRef>& images) {
    if (headers.empty()) throw FileError(what + ": no DICOM image");
    checkSameGeometry(headers, what);
    const DicomHeader& h0 = headers.front();
    const DicomFrame& f0 = h0.frames.front();

    SeriesLayout L;
    std::size_t count = 0, positioned = 0;
    for (std::size_t h = 0; h < headers.size(); ++h)
        for (std::size_t n = 0; n < headers[h].frames.size(); ++n) L.slices.push_back({h, int(n), dvec2(0.0)});
    if (!images.empty()) L.slices = images;  // one volume of several (DicomVolumes)
    for (const SliceRef& s : L.slices) {
        ++count;
        positioned += frameOf(headers, s).hasPosition ? 1 : 0;
    }
    L.sliceDims = ivec3(h0.columns, h0.rows, int(count));
    L.single = count == 1;

    dvec3 row(1.0, 0.0, 0.0), col(0.0, 1.0, 0.0);
    if (f0.hasOrientation) orientation(h0, f0, what, row, col);
    else L.warnings.push_back("no ImageOrientationPatient: the images are taken as axis-aligned");
    const dvec3 normal = glm::cross(row, col);
    L.direction = dmat3(row, col, normal);
    // PixelSpacing is (between rows, between columns): x (along a row) is the second.
    if (f0.hasPixelSpacing) L.spacing = dvec2(f0.pixelSpacing.y, f0.pixelSpacing.x);
    else L.warnings.push_back("no PixelSpacing: 1 mm assumed");

    const auto framePos = [&](const SliceRef& s) { return headers[s.header].frames[std::size_t(s.frame)].position; };
    if (L.single) {
        // One image: its plane, and no distance to a neighbour it does not have (none is
        // invented from SliceThickness or SpacingBetweenSlices).
        L.z = {0.0};
        if (positioned) L.origin = f0.position;
        else L.warnings.push_back("no ImagePositionPatient: the image is placed at the origin");
        return L;
    }
    if (positioned == count) {
        std::stable_sort(L.slices.begin(), L.slices.end(), [&](const SliceRef& a, const SliceRef& b) {
            return glm::dot(framePos(a), normal) < glm::dot(framePos(b), normal);
        });
        const dvec3 p0 = framePos(L.slices.front());
        L.origin = p0;
        for (std::size_t k = 0; k < L.slices.size(); ++k) {
            const dvec3 d = framePos(L.slices[k]) - p0;
            L.z.push_back(glm::dot(d, normal));
            L.slices[k].shift = dvec2(glm::dot(d, row), glm::dot(d, col));
            if (k > 0 && !(L.z[k] - L.z[k - 1] > 1e-3)) {
                const SliceRef& a = L.slices[k - 1];
                const SliceRef& b = L.slices[k];
                throw FileError(what + ": " + imageName(headers[a.header], a.frame) + " and " +
                                imageName(headers[b.header], b.frame) + " lie at the same position along the slice normal (" +
                                vecText(framePos(b)) + ") and nothing in their headers tells their volumes apart");
            }
        }
    } else if (positioned == 0 && headers.size() == 1) {
        const double dz = h0.sliceSpacing > 0.0 ? h0.sliceSpacing : 1.0;
        for (std::size_t k = 0; k < count; ++k) L.z.push_back(double(k) * dz);
        L.warnings.push_back("no ImagePositionPatient for the frames: stacked in frame order " + num(dz) + " mm apart (" +
                             (h0.sliceSpacing > 0.0 ? "SpacingBetweenSlices or SliceThickness" : "assumed") + ")");
    } else {
        for (const DicomHeader& h : headers)
            for (std::size_t n = 0; n < h.frames.size(); ++n)
                if (!h.frames[n].hasPosition)
                    throw FileError(what + ": " + imageName(h, int(n)) +
                                    " has no ImagePositionPatient: its slice cannot be placed (octrace never orders slices by "
                                    "file name or InstanceNumber)");
    }
    checkDistances(L);

    double largest = 0.0;
    for (const SliceRef& s : L.slices)
        largest = std::max({largest, std::abs(s.shift.x) / L.spacing.x, std::abs(s.shift.y) / L.spacing.y});
    if (largest > kShearTolerance) {
        const dvec2 last = L.slices.back().shift;
        L.tilted = true;
        L.tiltDegrees = std::atan2(glm::length(last), L.z.back()) * 180.0 / std::numbers::pi;
        if (L.tiltDegrees > 45.0 || largest > 4.0 * std::max(L.sliceDims.x, L.sliceDims.y))
            throw FileError(what + ": slice positions are sheared by " + num(L.tiltDegrees) +
                            " degrees against their orientation: not a gantry tilt, refused");
        L.warnings.push_back("slices are sheared by a gantry tilt of " + num(L.tiltDegrees) +
                             " degrees: resampled onto an orthogonal grid (bilinear in each slice; points outside a slice are masked)");
    }
    return L;
}

void shearedGrid(const SeriesLayout& L, ivec3& outDims, dvec2& outOffset) {
    dvec2 lo(0.0), hi(0.0);
    for (const SliceRef& s : L.slices) {
        lo = glm::min(lo, s.shift);
        hi = glm::max(hi, s.shift);
    }
    outOffset = lo;
    outDims = L.sliceDims;
    for (int a = 0; a < 2; ++a) {
        const double extent = double(L.sliceDims[a] - 1) * L.spacing[a] + hi[a] - lo[a];
        outDims[a] = int(std::ceil(extent / L.spacing[a] - 1e-6)) + 1;
    }
}

std::vector<float> resampleSheared(const std::vector<float>& stored, const SeriesLayout& L, ivec3 outDims,
                                   dvec2 outOffset, std::vector<std::uint8_t>& valid) {
    const int nx = L.sliceDims.x, ny = L.sliceDims.y;
    const std::size_t plane = std::size_t(nx) * std::size_t(ny);
    const std::size_t outPlane = std::size_t(outDims.x) * std::size_t(outDims.y);
    std::vector<float> out(outPlane * std::size_t(outDims.z), 0.0f);
    valid.assign(out.size(), 0);
    constexpr double eps = 1e-6;
    for (int k = 0; k < outDims.z; ++k) {
        const float* slice = stored.data() + plane * std::size_t(k);
        const dvec2 shift = L.slices[std::size_t(k)].shift;
        for (int j = 0; j < outDims.y; ++j) {
            const double v = (outOffset.y + j * L.spacing.y - shift.y) / L.spacing.y;  // row index in slice k
            if (v < -eps || v > ny - 1 + eps) continue;
            const int j0 = std::clamp(int(std::floor(v)), 0, std::max(0, ny - 2));
            const double fy = std::clamp(v - j0, 0.0, 1.0);
            for (int i = 0; i < outDims.x; ++i) {
                const double u = (outOffset.x + i * L.spacing.x - shift.x) / L.spacing.x;  // column index
                if (u < -eps || u > nx - 1 + eps) continue;
                const int i0 = std::clamp(int(std::floor(u)), 0, std::max(0, nx - 2));
                const double fx = std::clamp(u - i0, 0.0, 1.0);
                const float* p = slice + std::size_t(j0) * std::size_t(nx) + std::size_t(i0);
                const double top = p[0] * (1.0 - fx) + p[1] * fx;
                const double bottom = p[nx] * (1.0 - fx) + p[nx + 1] * fx;
                const std::size_t at = outPlane * std::size_t(k) + std::size_t(j) * std::size_t(outDims.x) + std::size_t(i);
                out[at] = float(top * (1.0 - fy) + bottom * fy);
                valid[at] = 1;
            }
        }
    }
    return out;
}

}  // namespace octrace::io::detail
