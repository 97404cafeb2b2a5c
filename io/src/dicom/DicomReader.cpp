#include "octrace/io/DicomReader.h"

#include "dicom/DicomFile.h"
#include "dicom/DicomSeries.h"
#include "input/FieldText.h"
#include "input/InputFile.h"
#include "octrace/util/Error.h"
#include "octrace/util/Log.h"
#include "octrace/util/Memory.h"

#include <algorithm>
#include <filesystem>
#include <limits>
#include <map>
#include <mutex>
#include <optional>
#include <sstream>

namespace fs = std::filesystem;

namespace octrace::io {
namespace {

using detail::DicomHeader;

// The share of a read's progress that scanning the headers takes; decoding the volume's files
// takes the rest.
constexpr double kScanShare = 0.1;

// 8 GiB of float samples: far beyond any real series, refused before decoding anything.
constexpr double kMaxSamples = double(1u << 31);

struct Series {
    DicomSeriesInfo info;
    std::vector<DicomHeader> headers;
    std::vector<detail::SeriesVolume> volumes;  ///< splitVolumes of the headers
};

// Runs `step` on one file of the input; a refusal names the input first when the input is a
// folder, so that every message starts with the path the user gave.
template <typename Step>
auto forFile(const std::string& path, const std::string& file, Step step) {
    try {
        return step();
    } catch (const FileError& e) {
        if (file == path) throw;
        throw FileError(path + ": " + e.what());
    }
}

struct Scan {
    bool folder = false;  ///< a folder or a DICOMDIR was given (several series possible)
    std::vector<Series> series;
};

// The files to look at: the file itself, or every DICOM-looking file under the folder (the
// DICOMDIR's folder), in path order so that messages do not depend on the file system.
std::vector<std::string> candidateFiles(const std::string& path, bool& folder) {
    std::error_code ec;
    auto st = fs::status(path, ec);
    if (ec || !fs::exists(st)) throw InputError(path + ": no such file");
    fs::path root = path;
    folder = fs::is_directory(st);
    if (!folder && detail::isDicomDir(path)) {
        folder = true;
        root = fs::path(path).parent_path();
        if (root.empty()) root = ".";
    }
    if (!folder) {
        detail::requireReadableFile(path);
        return {path};
    }
    std::vector<std::string> files;
    for (fs::recursive_directory_iterator it(root, fs::directory_options::skip_permission_denied, ec), end; !ec && it != end;
         it.increment(ec)) {
        if (!it->is_regular_file(ec)) continue;
        const std::string f = it->path().string();
        if (!detail::isDicomDir(f) && detail::looksLikeDicom(f)) files.push_back(f);
    }
    std::sort(files.begin(), files.end());
    return files;
}

// The last input's scan, kept while none of its files changes: the studio lists a folder's
// series, reads one and lists its volumes, three scans of every header otherwise (a clinical
// folder holds thousands of files). Keyed by the path as given and each candidate file's name,
// size and modification time; one input kept, its headers (a few hundred bytes per file, per
// frame of a multi-frame file). A file rewritten with the same size within the file system's
// time resolution (a second or two on FAT and some network shares), or copied back with its old
// time, would be taken as unchanged.
struct FileStamp {
    std::string file;
    std::uintmax_t size = 0;
    fs::file_time_type modified;
    bool operator==(const FileStamp&) const = default;
};

struct ScanMemo {
    std::string path;
    std::vector<FileStamp> stamps;
    Scan scan;
};

std::mutex scanMemoMutex;
std::optional<ScanMemo> scanMemo;  // guarded by scanMemoMutex

// The stamps of `files`, or nullopt when one cannot be read (then nothing is kept).
std::optional<std::vector<FileStamp>> stampsOf(const std::vector<std::string>& files) {
    std::vector<FileStamp> stamps;
    stamps.reserve(files.size());
    for (const std::string& f : files) {
        std::error_code ec, ec2;
        FileStamp st{f, fs::file_size(f, ec), fs::last_write_time(f, ec2)};
        if (ec || ec2) return std::nullopt;
        stamps.push_back(std::move(st));
    }
    return stamps;
}

Scan scanFiles(const std::string& path, const std::vector<std::string>& files, bool folder, const ReadHooks& hooks);

Scan scan(const std::string& path, const ReadHooks& hooks = {}) {
    bool folder = false;
    const std::vector<std::string> files = candidateFiles(path, folder);
    const std::optional<std::vector<FileStamp>> stamps = stampsOf(files);
    std::optional<Scan> kept;
    if (stamps) {
        const std::lock_guard lock(scanMemoMutex);
        if (scanMemo && scanMemo->path == path && scanMemo->stamps == *stamps) kept = scanMemo->scan;
    }
    if (kept) {
        // Reported and cancellable per file as a scan is (outside the lock: the caller's hooks
        // run there), so that callers see one behaviour.
        for (std::size_t i = 0; i < files.size(); ++i) {
            hooks.checkCancelled(path);
            hooks.report(kScanShare * double(i) / double(files.size()));
        }
        log::debug(path + ": the headers of the last scan (" + std::to_string(files.size()) + " files unchanged)");
        return std::move(*kept);
    }
    Scan s = scanFiles(path, files, folder, hooks);
    if (stamps) {
        const std::lock_guard lock(scanMemoMutex);
        scanMemo = ScanMemo{path, *stamps, s};
    }
    return s;
}

Scan scanFiles(const std::string& path, const std::vector<std::string>& files, bool folder, const ReadHooks& hooks) {
    Scan s;
    s.folder = folder;
    std::map<std::string, Series> byUid;
    std::size_t skipped = 0, scanned = 0;
    for (const std::string& f : files) {
        hooks.checkCancelled(path);
        hooks.report(kScanShare * double(scanned++) / double(files.size()));
        std::string whyNot;
        std::optional<DicomHeader> h = forFile(path, f, [&] { return detail::readDicomHeader(f, whyNot); });
        if (!h) {
            if (!s.folder) {
                if (whyNot.rfind("not a DICOM", 0) == 0) throw FormatNotSupported(path + ": " + whyNot);
                throw FileError(path + ": " + whyNot);
            }
            log::debug(f + ": skipped, " + whyNot);
            ++skipped;
            continue;
        }
        Series& series = byUid[h->seriesUid];
        if (series.headers.empty())
            series.info = {h->seriesUid, h->modality, h->description, h->seriesNumber, h->columns, h->rows, 0, 0};
        series.info.files += 1;
        series.headers.push_back(std::move(*h));
    }
    if (byUid.empty())
        throw FileError(path + ": no DICOM image (" + std::to_string(files.size()) + " DICOM-looking file(s), " +
                        std::to_string(skipped) + " without an image)");
    for (auto& [uid, series] : byUid) {
        series.volumes = detail::splitVolumes(series.headers);
        series.info.volumes = int(series.volumes.size());
        for (const detail::SeriesVolume& v : series.volumes)
            series.info.slices = std::max(series.info.slices, int(v.images.size()));
        s.series.push_back(std::move(series));
    }
    std::stable_sort(s.series.begin(), s.series.end(), [](const Series& a, const Series& b) {
        return a.info.seriesNumber < b.info.seriesNumber;  // then UID: the map's order
    });
    return s;
}

std::string seriesLine(const DicomSeriesInfo& i) {
    std::ostringstream s;
    s << (i.uid.empty() ? std::string("(no SeriesInstanceUID)") : i.uid) << " (" << (i.modality.empty() ? "?" : i.modality)
      << (i.description.empty() ? std::string() : ", '" + i.description + "'") << ", " << i.columns << "x" << i.rows << "x"
      << i.slices << ", " << i.files << " file" << (i.files == 1 ? "" : "s")
      << (i.volumes > 1 ? ", " + std::to_string(i.volumes) + " volumes" : std::string()) << ")";
    return s.str();
}

std::vector<std::string> volumeLabels(const Series& series) {
    std::vector<std::string> labels;
    for (const detail::SeriesVolume& v : series.volumes) labels.push_back(v.label);
    return labels;
}

std::size_t chooseScanned(const Scan& s, const std::string& want, const std::string& path) {
    std::vector<DicomSeriesInfo> list;
    for (const Series& series : s.series) list.push_back(series.info);
    return DicomReader::chooseSeries(list, want, path);
}

// Stored values (rescaled for CT) of every slice, in the layout's z order.
std::vector<float> decodeSlices(const std::vector<DicomHeader>& headers, const detail::SeriesLayout& L, bool rescale,
                                const std::string& path, const ReadHooks& hooks) {
    // Only the files that hold a slice of the volume are decoded.
    const std::size_t plane = std::size_t(L.sliceDims.x) * std::size_t(L.sliceDims.y);
    std::vector<std::vector<std::pair<int, std::size_t>>> wanted(headers.size());  // per file: (frame, slice)
    for (std::size_t k = 0; k < L.slices.size(); ++k) wanted[L.slices[k].header].push_back({L.slices[k].frame, k});
    std::vector<float> stored(plane * L.slices.size());
    std::size_t done = 0;  // slices decoded: progress per file, in proportion to its slices
    for (std::size_t h = 0; h < headers.size(); ++h) {
        if (wanted[h].empty()) continue;
        hooks.checkCancelled(path);
        hooks.report(kScanShare + (1.0 - kScanShare) * double(done) / double(L.slices.size()));
        done += wanted[h].size();
        const std::vector<float> frames = forFile(path, headers[h].file, [&] { return detail::decodeDicomFrames(headers[h]); });
        for (auto [frame, k] : wanted[h]) {
            const detail::DicomFrame& g = headers[h].frames[std::size_t(frame)];
            const float* src = frames.data() + plane * std::size_t(frame);
            float* dst = stored.data() + plane * k;
            for (std::size_t i = 0; i < plane; ++i) dst[i] = rescale ? float(src[i] * g.slope + g.intercept) : src[i];
        }
    }
    hooks.report(1.0);
    return stored;
}

// What reading the series costs at its peak: the stored slices as floats, the resampled grid
// and its mask when tilted, and one file's decoded bytes and floats (files are decoded one by one).
std::uint64_t peakBytes(const Series& series, double stored, double samples, bool tilted) {
    double file = 0.0;
    for (const DicomHeader& h : series.headers)
        file = std::max(file, double(h.rows) * double(h.columns) * double(h.frames.size()) * (h.bitsAllocated / 8.0 + sizeof(float)));
    const double total = stored * sizeof(float) + (tilted ? samples * (sizeof(float) + 1.0) : 0.0) + file;
    return total >= 1.8e19 ? std::numeric_limits<std::uint64_t>::max() : std::uint64_t(total);
}

// The volume `want` (-1: the first, said when there are several) of a series, checked.
std::size_t chooseVolume(const Series& series, int want, const std::string& path) {
    const std::size_t n = series.volumes.size();
    detail::checkVolumesAlike(series.headers, series.volumes, path);
    if (want >= 0 && std::size_t(want) < n) return std::size_t(want);
    std::string list;
    for (std::size_t v = 0; v < n && v < 8; ++v) list += (v ? "; " : "") + std::to_string(v) + ": " + series.volumes[v].label;
    if (n > 8) list += "; ...";
    if (want >= 0)
        throw InputError(path + ": no volume " + std::to_string(want) + ": series " + series.info.uid + " holds " +
                         (n == 1 ? std::string("one volume (`volume` 0)") : std::to_string(n) + " volumes, 0.." + std::to_string(n - 1) + " (" + list + ")"));
    if (n > 1)
        log::info(path + ": the series holds " + std::to_string(n) + " volumes (" + list + "); reading volume 0, choose another with `volume`");
    return 0;
}

// What a single image is, as messages name it: "a single 128x128 CT image (FILE, series UID)".
std::string singleImageText(const Series& series, const std::string& path) {
    const DicomHeader& h = series.headers.front();
    std::string where = h.file == path ? std::string() : h.file + ", ";
    return "a single " + std::to_string(h.columns) + "x" + std::to_string(h.rows) + " " +
           (h.modality.empty() ? std::string() : h.modality + " ") + "image (" + where + "series " +
           (h.seriesUid.empty() ? std::string("without a SeriesInstanceUID") : h.seriesUid) + ")";
}

ScalarField assemble(const Series& series, const std::string& path, std::uint64_t memoryBudget, int volume,
                     bool acceptPlanar, const ReadHooks& hooks) {
    const std::size_t chosen = chooseVolume(series, volume, path);
    const detail::SeriesVolume& vol = series.volumes[chosen];
    detail::SeriesLayout L = detail::layoutSeries(series.headers, path, vol.images);
    if (L.single && !acceptPlanar)
        throw InputError(path + ": " + singleImageText(series, path) +
                         ": a surface needs a volume, a series of slices or a multi-frame image; draw a single image with slice");
    const double stored = double(L.sliceDims.x) * double(L.sliceDims.y) * double(L.sliceDims.z);
    ivec3 dims = L.sliceDims;
    dvec2 offset(0.0);
    if (L.tilted) detail::shearedGrid(L, dims, offset);
    const double samples = double(dims.x) * double(dims.y) * double(dims.z);
    if (std::max(stored, samples) > kMaxSamples)
        throw FileError(path + ": series " + series.info.uid + " is " + std::to_string(dims.x) + "x" + std::to_string(dims.y) +
                        "x" + std::to_string(dims.z) + " samples, more than octrace reads (" + detail::num(kMaxSamples) + ")");

    checkMemoryBudget(path + ": reading DICOM series " + std::to_string(dims.x) + "x" + std::to_string(dims.y) + "x" +
                          std::to_string(dims.z),
                      peakBytes(series, stored, samples, L.tilted), memoryBudget);

    const bool ct = series.info.modality == "CT";
    ScalarField f;
    f.source = path;
    f.name = series.info.modality.empty() ? "DICOM" : series.info.modality;
    f.units = ct ? "HU" : "";
    f.dims = dims;
    f.direction = L.direction;
    // A single image has one sample along its normal and no distance to a neighbour: the
    // field needs a positive spacing there, and nothing reads it (a map's, NetcdfLayout's).
    f.planar = L.single;
    f.spacing = dvec3(L.spacing, L.single ? 1.0 : L.uniform ? L.z.back() / double(L.z.size() - 1) : 1.0);
    if (!L.uniform) f.coords[2] = L.z;
    f.origin = L.origin + L.direction[0] * offset.x + L.direction[1] * offset.y;
    std::vector<float> values = decodeSlices(series.headers, L, ct, path, hooks);
    f.values = L.tilted ? detail::resampleSheared(values, L, dims, offset, f.valid) : std::move(values);
    // The display the file recommends: the window of its first slice, MONOCHROME1's inversion.
    const DicomHeader& first = series.headers[L.slices.front().header];
    const detail::DicomFrame& firstFrame = first.frames[std::size_t(L.slices.front().frame)];
    f.window = {firstFrame.windowCentre, firstFrame.windowWidth};
    f.invertedGrey = first.monochrome1;
    if (f.window.valid())
        f.notes.push_back("display window: centre " + detail::num(f.window.centre) + ", width " + detail::num(f.window.width) +
                          " (WindowCenter/WindowWidth)");
    if (f.invertedGrey) f.notes.push_back("MONOCHROME1: low values displayed bright");

    f.notes.push_back("DICOM series " + seriesLine(series.info));
    if (series.volumes.size() > 1)
        f.notes.push_back("volume " + std::to_string(chosen) + " of " + std::to_string(series.volumes.size()) + ": " + vol.label);
    if (L.single)
        f.notes.push_back(singleImageText(series, path) +
                          ": a 2-D field in its own plane, no spacing between slices; drawn by slice, not as a surface");
    f.notes.push_back(ct ? "values: Hounsfield units (RescaleSlope/Intercept of each image)" : "values: as stored");
    f.notes.push_back("coordinates: patient LPS, mm");
    f.patientLps = true;
    for (const std::string& w : L.warnings) {
        log::warning(path + ": " + w);
        f.notes.push_back(w);
    }
    f.validate();
    return f;
}

ScalarField readScanned(const Scan& s, const std::string& path, const std::string& want, std::uint64_t memoryBudget, int volume,
                        bool acceptPlanar, const ReadHooks& hooks = {}) {
    const std::size_t chosen = chooseScanned(s, want, path);
    const DicomSeriesInfo& info = s.series[chosen].info;
    // Said when there was a choice to make; a folder of one series gets a debugging line.
    const std::string said = path + ": series " + std::to_string(chosen + 1) + " of " + std::to_string(s.series.size()) +
                             ", " + seriesLine(info);
    if (s.series.size() > 1) log::info(said + (want.empty() ? ": the largest; choose another with `series`" : ""));
    else log::debug(said);
    return assemble(s.series[chosen], path, memoryBudget, volume, acceptPlanar, hooks);
}

}  // namespace

std::size_t DicomReader::chooseSeries(const std::vector<DicomSeriesInfo>& list, const std::string& want, const std::string& path) {
    const std::size_t n = list.size();
    if (want.empty()) {
        std::size_t best = 0;
        for (std::size_t i = 1; i < n; ++i)
            if (list[i].samples() > list[best].samples()) best = i;
        return best;
    }
    for (std::size_t i = 0; i < n; ++i)
        if (list[i].uid == want) return i;
    if (want.find_first_not_of("0123456789") == std::string::npos && want.size() < 9) {
        const std::size_t index = std::stoul(want);
        if (index >= 1 && index <= n) return index - 1;
    }
    std::vector<std::size_t> described;
    for (std::size_t i = 0; i < n; ++i)
        if (detail::lower(list[i].description) == detail::lower(want)) described.push_back(i);
    if (described.size() == 1) return described[0];
    std::string known;
    for (std::size_t i = 0; i < n; ++i) known += (i ? "; " : "") + std::to_string(i + 1) + ": " + seriesLine(list[i]);
    throw InputError(path + ": " + (described.size() > 1 ? "several series are described '" : "no series '") + want +
                     "' (give a UID, an index or a description; series: " + known + ")");
}

std::vector<DicomSeriesInfo> DicomReader::listSeries(const std::string& path, const ReadHooks& hooks) {
    std::vector<DicomSeriesInfo> list;
    for (const Series& s : scan(path, hooks).series) list.push_back(s.info);
    return list;
}

ScalarField DicomReader::read(const std::string& path, const std::string& series, std::uint64_t memoryBudget, int volume,
                              bool acceptPlanar, const ReadHooks& hooks) {
    return readScanned(scan(path, hooks), path, series, memoryBudget, volume, acceptPlanar, hooks);
}

std::vector<std::string> DicomReader::listVolumes(const std::string& path, const std::string& series) {
    const Scan s = scan(path);
    const Series& chosen = s.series[chooseScanned(s, series, path)];
    detail::checkVolumesAlike(chosen.headers, chosen.volumes, path);
    return volumeLabels(chosen);
}

std::string DicomReader::describe(const std::string& path, const std::string& series, std::uint64_t memoryBudget, int volume) {
    const Scan s = scan(path);
    std::ostringstream out;
    out << path << "\nformat: DICOM, " << s.series.size() << " image series\n";
    for (std::size_t i = 0; i < s.series.size(); ++i) out << "series " << i + 1 << ": " << seriesLine(s.series[i].info) << "\n";
    const std::size_t chosen = chooseScanned(s, series, path);
    const Series& c = s.series[chosen];
    if (c.volumes.size() > 1) {
        detail::checkVolumesAlike(c.headers, c.volumes, path);
        out << detail::describeVolumeList(volumeLabels(c), c.volumes.front().images.size());  // alike: checked above
    }
    const ScalarField f = readScanned(s, path, series, memoryBudget, volume, true);  // a single image is described, not refused
    out << "chosen: series " << chosen + 1;
    if (c.volumes.size() > 1) out << ", volume " << (volume < 0 ? 0 : volume);
    out << "\n" << detail::describeVolume(f);
    return out.str();
}

}  // namespace octrace::io
