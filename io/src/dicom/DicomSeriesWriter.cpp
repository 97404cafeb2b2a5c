#include "octrace/io/DicomSeriesWriter.h"

#include "octrace/util/Error.h"

#include <gdcmDataSet.h>
#include <gdcmFile.h>
#include <gdcmFileMetaInformation.h>
#include <gdcmUIDGenerator.h>
#include <gdcmWriter.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <numeric>
#include <random>

namespace octrace::io {
namespace {

// A DS value: at most 16 characters, as many significant digits as fit.
std::string decimal(double v) {
    char buf[40];
    for (int digits = 16; digits > 1; --digits) {
        std::snprintf(buf, sizeof buf, "%.*g", digits, v);
        if (std::strlen(buf) <= 16) break;
    }
    return buf;
}

std::string decimals(std::initializer_list<double> values) {
    std::string s;
    for (double v : values) {
        if (!s.empty()) s += '\\';
        s += decimal(v);
    }
    return s;
}

// Text elements are padded to an even length: UI with a NUL, the others with a space.
void put(gdcm::DataSet& ds, std::uint16_t group, std::uint16_t element, gdcm::VR vr, std::string value) {
    if (value.size() % 2) value += vr == gdcm::VR::UI ? '\0' : ' ';
    gdcm::DataElement de(gdcm::Tag(group, element));
    de.SetVR(vr);
    de.SetByteValue(value.data(), gdcm::VL(std::uint32_t(value.size())));
    ds.Replace(de);
}

void putUS(gdcm::DataSet& ds, std::uint16_t group, std::uint16_t element, std::uint16_t value) {
    gdcm::DataElement de(gdcm::Tag(group, element));
    de.SetVR(gdcm::VR::US);
    const char bytes[2] = {char(value & 0xff), char(value >> 8)};
    de.SetByteValue(bytes, 2);
    ds.Replace(de);
}

const char* sopClass(const std::string& modality) {
    if (modality == "CT") return "1.2.840.10008.5.1.4.1.1.2";
    if (modality == "MR") return "1.2.840.10008.5.1.4.1.1.4";
    return "1.2.840.10008.5.1.4.1.1.7";  // Secondary Capture
}

}  // namespace

std::vector<std::string> DicomSeriesWriter::write(const ScalarField& field, const std::string& folder,
                                                  const DicomSeriesWriteOptions& options) {
    auto fail = [&](const std::string& what) { throw OutputError(folder + ": " + what); };
    if (field.isRectilinear(0) || field.isRectilinear(1)) fail("DICOM images need an even pixel spacing (x and y)");
    if (field.dims.x > 65535 || field.dims.y > 65535 || field.dims.x < 1 || field.dims.y < 1)
        fail("slices of " + std::to_string(field.dims.x) + "x" + std::to_string(field.dims.y) + " do not fit in DICOM's Rows/Columns");
    if (field.values.size() != field.sampleCount()) fail("the field holds no samples");
    if (field.validCount() != field.sampleCount()) fail("masked samples cannot be written to DICOM");
    std::error_code ec;
    std::filesystem::create_directories(folder, ec);
    if (ec) fail("cannot create the folder: " + ec.message());

    const int slices = field.dims.z;
    std::vector<int> nameOrder(std::size_t(slices), 0);  // slice k -> position of its name
    std::iota(nameOrder.begin(), nameOrder.end(), 0);
    if (options.descending) std::reverse(nameOrder.begin(), nameOrder.end());
    if (options.shuffleSeed) std::shuffle(nameOrder.begin(), nameOrder.end(), std::mt19937_64(options.shuffleSeed));

    gdcm::UIDGenerator uids;
    const std::string study = uids.Generate(), series = uids.Generate(), frame = uids.Generate();
    const dvec3 row = field.direction[0], column = field.direction[1], normal = field.direction[2];
    const std::size_t plane = std::size_t(field.dims.x) * std::size_t(field.dims.y);
    std::vector<std::string> names;
    std::vector<char> pixels(plane * 2);
    for (int k = 0; k < slices; ++k) {
        const dvec2 rescale = options.rescale ? options.rescale(k) : dvec2(1.0, 0.0);
        if (!(rescale.x != 0.0 && std::isfinite(rescale.x) && std::isfinite(rescale.y)))
            fail("slice " + std::to_string(k) + ": rescale slope must be finite and non-zero");
        for (std::size_t i = 0; i < plane; ++i) {
            const double v = field.values[plane * std::size_t(k) + i];
            const double stored = (v - rescale.y) / rescale.x;
            const double rounded = std::nearbyint(stored);
            if (!(std::abs(stored - rounded) <= 1e-6) || rounded < -32768.0 || rounded > 32767.0)
                fail("value " + std::to_string(v) + " of slice " + std::to_string(k) + " is not an int16 once rescaled (slope " +
                     decimal(rescale.x) + ", intercept " + decimal(rescale.y) + ")");
            const auto s = std::uint16_t(std::int16_t(rounded));
            pixels[2 * i] = char(s & 0xff);
            pixels[2 * i + 1] = char(s >> 8);
        }
        const int instance = options.descending ? slices - k : k + 1;
        const dvec3 position = field.origin + normal * field.axisPosition(2, k) +
                               column * (double(k) * options.shearRows * field.spacing.y);

        gdcm::Writer writer;
        gdcm::File& file = writer.GetFile();
        file.GetHeader().SetDataSetTransferSyntax(gdcm::TransferSyntax::ExplicitVRLittleEndian);
        gdcm::DataSet& ds = file.GetDataSet();
        const std::string sop = uids.Generate();
        put(ds, 0x0008, 0x0016, gdcm::VR::UI, sopClass(options.modality));
        put(ds, 0x0008, 0x0018, gdcm::VR::UI, sop);
        put(ds, 0x0008, 0x0060, gdcm::VR::CS, options.modality);
        if (!options.description.empty()) put(ds, 0x0008, 0x103e, gdcm::VR::LO, options.description);
        put(ds, 0x0010, 0x0010, gdcm::VR::PN, "octrace^test");
        put(ds, 0x0010, 0x0020, gdcm::VR::LO, "octrace");
        put(ds, 0x0018, 0x0050, gdcm::VR::DS, decimal(slices > 1 ? std::abs(field.axisPosition(2, 1) - field.axisPosition(2, 0)) : 1.0));
        put(ds, 0x0020, 0x000d, gdcm::VR::UI, study);
        put(ds, 0x0020, 0x000e, gdcm::VR::UI, series);
        put(ds, 0x0020, 0x0011, gdcm::VR::IS, std::to_string(options.seriesNumber));
        put(ds, 0x0020, 0x0013, gdcm::VR::IS, std::to_string(instance));
        put(ds, 0x0020, 0x0032, gdcm::VR::DS, decimals({position.x, position.y, position.z}));
        put(ds, 0x0020, 0x0037, gdcm::VR::DS, decimals({row.x, row.y, row.z, column.x, column.y, column.z}));
        put(ds, 0x0020, 0x0052, gdcm::VR::UI, frame);
        putUS(ds, 0x0028, 0x0002, 1);
        put(ds, 0x0028, 0x0004, gdcm::VR::CS, options.monochrome1 ? "MONOCHROME1" : "MONOCHROME2");
        putUS(ds, 0x0028, 0x0010, std::uint16_t(field.dims.y));
        putUS(ds, 0x0028, 0x0011, std::uint16_t(field.dims.x));
        put(ds, 0x0028, 0x0030, gdcm::VR::DS, decimals({field.spacing.y, field.spacing.x}));  // rows, columns
        putUS(ds, 0x0028, 0x0100, 16);
        putUS(ds, 0x0028, 0x0101, 16);
        putUS(ds, 0x0028, 0x0102, 15);
        putUS(ds, 0x0028, 0x0103, 1);
        if (options.window.valid()) {
            put(ds, 0x0028, 0x1050, gdcm::VR::DS, decimal(options.window.centre));
            put(ds, 0x0028, 0x1051, gdcm::VR::DS, decimal(options.window.width));
        }
        put(ds, 0x0028, 0x1052, gdcm::VR::DS, decimal(rescale.y));
        put(ds, 0x0028, 0x1053, gdcm::VR::DS, decimal(rescale.x));
        gdcm::DataElement data(gdcm::Tag(0x7fe0, 0x0010));
        data.SetVR(gdcm::VR::OW);
        data.SetByteValue(pixels.data(), gdcm::VL(std::uint32_t(pixels.size())));
        ds.Replace(data);

        char name[32];
        std::snprintf(name, sizeof name, "slice_%05d.dcm", nameOrder[std::size_t(k)]);
        const std::string path = (std::filesystem::path(folder) / name).string();
        writer.SetFileName(path.c_str());
        if (!writer.Write()) fail("cannot write " + path);
        names.push_back(name);
    }
    return names;
}

}  // namespace octrace::io
