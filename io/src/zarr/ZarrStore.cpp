#include "zarr/ZarrStore.h"

#include "octrace/util/Error.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <iterator>
#include <fstream>

namespace fs = std::filesystem;
using nlohmann::json;

namespace octrace::io::detail {
namespace {

constexpr std::uintmax_t kMaxMetadataBytes = std::uintmax_t(256) << 20;

// The pre-final v3 draft names its protocol by URL in zarr.json's zarr_format (GDAL 3.6 writes
// and reads this layout: zarr.json, meta/root.group.json, data/root/...).
const char* kV3DraftFormat = "https://purl.org/zarr/spec/protocol/core/3.0";

std::optional<std::string> readIfPresent(const fs::path& file) {
    std::error_code ec;
    if (!fs::is_regular_file(file, ec)) return std::nullopt;
    const std::uintmax_t size = fs::file_size(file, ec);
    if (ec) throw FileError(file.string() + ": cannot be read (" + ec.message() + ")");
    if (size > kMaxMetadataBytes)
        throw FileError(file.string() + ": Zarr metadata of " + std::to_string(size) +
                        " bytes, more than the 256 MiB octrace reads");
    std::ifstream in(file, std::ios::binary);
    if (!in) throw FileError(file.string() + ": cannot be opened (permission denied?)");
    std::string bytes(std::size_t(size), '\0');
    in.read(bytes.data(), std::streamsize(size));
    bytes.resize(std::size_t(std::max<std::streamsize>(0, in.gcount())));
    return bytes;
}

json parseObject(const std::string& store, const char* name, const std::string& bytes) {
    json doc;
    try {
        doc = json::parse(bytes);
    } catch (const json::exception& e) {
        throw FileError(store + ": its Zarr metadata " + name + " are not valid JSON (" + e.what() + ")");
    }
    if (!doc.is_object()) throw FileError(store + ": its Zarr metadata " + name + " are not a JSON object");
    return doc;
}

std::string formatText(const json& value) {
    std::string text = value.dump();
    return text.size() > 80 ? text.substr(0, 77) + "..." : text;
}

// "Convert it ..." with the store's own name and a v2 copy beside it.
std::string conversionHint(const std::string& store) {
    std::string copy = store;
    while (copy.size() > 1 && copy.back() == '/') copy.pop_back();
    if (copy.ends_with(".zarr")) copy.resize(copy.size() - 5);
    return "Convert it to Zarr v2 first, e.g. with xarray: xr.open_zarr(\"" + store + "\").drop_encoding().to_zarr(\"" + copy +
           "_v2.zarr\", zarr_format=2)";
}

// The zarr_format of a v2 `.zgroup` or `.zarray`: 2, or a refusal naming the file.
void requireV2(const std::string& store, const char* name, const std::string& bytes) {
    const json doc = parseObject(store, name, bytes);
    const auto f = doc.find("zarr_format");
    if (f == doc.end()) throw FileError(store + ": its Zarr metadata " + name + " have no \"zarr_format\"");
    if (!(f->is_number_integer() && f->get<long long>() == 2))
        throw FormatNotSupported(store + ": " + name + " says \"zarr_format\": " + formatText(*f) +
                                 "; a " + name + " belongs to Zarr v2 (\"zarr_format\": 2)");
}

// The arrays listed in consolidated metadata (keys ".../.zarray" of "metadata").
std::size_t consolidatedArrays(const std::string& store, const std::string& bytes) {
    const json doc = parseObject(store, ".zmetadata", bytes);
    const auto version = doc.find("zarr_consolidated_format");
    if (version != doc.end() && !(version->is_number_integer() && version->get<long long>() == 1))
        throw FormatNotSupported(store + ": .zmetadata says \"zarr_consolidated_format\": " + formatText(*version) +
                                 ", GDAL reads version 1");
    const auto meta = doc.find("metadata");
    if (meta == doc.end() || !meta->is_object())
        throw FileError(store + ": its consolidated Zarr metadata .zmetadata have no \"metadata\" object");
    std::size_t arrays = 0;
    for (const auto& [key, value] : meta->items()) {
        const bool isArray = key == ".zarray" || key.ends_with("/.zarray");
        if (!isArray) continue;
        if (!value.is_object()) throw FileError(store + ": .zmetadata's entry \"" + key + "\" is not a JSON object");
        const auto f = value.find("zarr_format");
        if (f != value.end() && !(f->is_number_integer() && f->get<long long>() == 2))
            throw FormatNotSupported(store + ": .zmetadata's entry \"" + key + "\" says \"zarr_format\": " +
                                     formatText(*f) + ", Zarr v2 arrays say 2");
        ++arrays;
    }
    return arrays;
}

}  // namespace

namespace {
// The metadata files whose presence at a folder's root makes it a store.
constexpr const char* kRootMetadata[] = {".zgroup", ".zarray", ".zmetadata", "zarr.json"};
}  // namespace

bool isZarrFolder(const std::string& folder) {
    std::error_code ec;
    for (const char* name : kRootMetadata)
        if (fs::is_regular_file(fs::path(folder) / name, ec)) return true;
    return false;
}

std::string storeOfMetadataFile(const std::string& path) {
    const fs::path p(path);
    const std::string name = p.filename().string();
    // A store's own metadata files, and its attributes (which alone make no store).
    const bool metadata = name == ".zattrs" || std::any_of(std::begin(kRootMetadata), std::end(kRootMetadata),
                                                           [&](const char* m) { return name == m; });
    std::error_code ec;
    if (!metadata || !fs::is_regular_file(p, ec)) return {};
    const fs::path folder = p.has_parent_path() ? p.parent_path() : fs::path(".");
    return isZarrFolder(folder.string()) ? folder.string() : std::string();
}

ZarrMetadata readZarrMetadata(const std::string& folder) {
    const fs::path root(folder);
    ZarrMetadata m;
    m.zgroup = readIfPresent(root / ".zgroup");
    m.zarray = readIfPresent(root / ".zarray");
    m.zmetadata = readIfPresent(root / ".zmetadata");
    m.zarrJson = readIfPresent(root / "zarr.json");
    return m;
}

ZarrStoreInfo classifyZarrMetadata(const std::string& store, const ZarrMetadata& m) {
    ZarrStoreInfo info;
    if (m.zgroup || m.zarray || m.zmetadata) {
        info.layout = ZarrLayout::V2;
        if (m.zgroup) requireV2(store, ".zgroup", *m.zgroup);
        if (m.zarray) requireV2(store, ".zarray", *m.zarray);
        std::string what = m.zarray && !m.zgroup ? "Zarr v2 array" : "Zarr v2 store";
        if (m.zmetadata) {
            const std::size_t arrays = consolidatedArrays(store, *m.zmetadata);
            what += " (consolidated metadata, .zmetadata: " + std::to_string(arrays) + " array" +
                    (arrays == 1 ? "" : "s") + ")";
        } else {
            what += " (metadata not consolidated)";
        }
        info.description = what;
        return info;
    }
    if (!m.zarrJson) throw FormatNotSupported(store + ": no Zarr metadata (.zgroup, .zarray, .zmetadata or zarr.json)");
    const json doc = parseObject(store, "zarr.json", *m.zarrJson);
    const auto f = doc.find("zarr_format");
    if (f == doc.end()) throw FileError(store + ": its Zarr metadata zarr.json have no \"zarr_format\"");
    if (f->is_string() && f->get<std::string>() == kV3DraftFormat) {
        info.layout = ZarrLayout::V3Draft;
        info.description = "Zarr v3 store in the pre-final draft layout (zarr.json, meta/)";
        return info;
    }
    if (f->is_number_integer() && f->get<long long>() == 3)
        throw FormatNotSupported(store + ": a Zarr v3 store in the final layout (zarr.json with \"zarr_format\": 3, as "
                                 "zarr-python 3 writes by default); GDAL 3.6's Zarr driver reads only Zarr v2 and the "
                                 "pre-final v3 draft, and would see an empty group. " + conversionHint(store));
    throw FormatNotSupported(store + ": zarr.json says \"zarr_format\": " + formatText(*f) +
                             "; GDAL reads Zarr v2 and the pre-final v3 draft");
}

std::string checkZarrOnDisk(const std::string& folder) {
    std::error_code ec;
    if (!fs::exists(folder, ec)) throw InputError(folder + ": no such file");
    return classifyZarrMetadata(folder, readZarrMetadata(folder)).description;
}

}  // namespace octrace::io::detail
