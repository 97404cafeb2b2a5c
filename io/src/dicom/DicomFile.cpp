#include "dicom/DicomFile.h"

#include "dicom/DicomValidator.h"
#include "input/InputFile.h"
#include "octrace/util/Error.h"

#include <gdcmDicts.h>
#include <gdcmGlobal.h>
#include <gdcmImage.h>
#include <gdcmImageReader.h>
#include <gdcmReader.h>
#include <gdcmSequenceOfFragments.h>
#include <gdcmSequenceOfItems.h>
#include <gdcmStringFilter.h>
#include <gdcmTrace.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>

namespace octrace::io::detail {
namespace {

// Larger than any real series (a whole-body CT is about 2,000 slices of 512^2); far below what
// a 32-bit index or a float buffer can hold.
constexpr double kMaxSamplesPerFile = 1u << 30;
constexpr long kMaxFrames = 100000;

const gdcm::Tag kPixelData(0x7fe0, 0x0010);
const gdcm::Tag kPerFrameGroups(0x5200, 0x9230), kSharedGroups(0x5200, 0x9229);
const gdcm::Tag kPlanePosition(0x0020, 0x9113), kPlaneOrientation(0x0020, 0x9116);
const gdcm::Tag kPixelMeasures(0x0028, 0x9110), kValueTransformation(0x0028, 0x9145);
const gdcm::Tag kPosition(0x0020, 0x0032), kOrientation(0x0020, 0x0037), kPixelSpacing(0x0028, 0x0030);
const gdcm::Tag kSlope(0x0028, 0x1053), kIntercept(0x0028, 0x1052);
const gdcm::Tag kSliceThickness(0x0018, 0x0050), kSpacingBetweenSlices(0x0018, 0x0088);
const gdcm::Tag kFrameVoiLut(0x0028, 0x9132), kWindowCentre(0x0028, 0x1050), kWindowWidth(0x0028, 0x1051);
// What tells the volumes of a series apart (DicomSeries.h, VolumeAttribute): the functional
// group macro that holds an attribute in enhanced files, the attribute, and the classic one.
const gdcm::Tag kFrameContent(0x0020, 0x9111), kCardiacSync(0x0018, 0x9118), kMrEcho(0x0018, 0x9114),
    kMrDiffusion(0x0018, 0x9117), kGradientDirectionSeq(0x0018, 0x9076), kMrFrameType(0x0018, 0x9226),
    kCtFrameType(0x0018, 0x9329), kDimensionIndexSeq(0x0020, 0x9222), kDimensionIndexPointer(0x0020, 0x9165);
const gdcm::Tag kTemporalPositionIndex(0x0020, 0x9128), kTemporalPositionIdentifier(0x0020, 0x0100),
    kNominalTriggerDelay(0x0020, 0x9153), kTriggerTimeTag(0x0018, 0x1060), kStackId(0x0020, 0x9056),
    kInStackPosition(0x0020, 0x9057), kEchoNumbers(0x0018, 0x0086), kEffectiveEchoTime(0x0018, 0x9082),
    kEchoTimeTag(0x0018, 0x0081), kBValueTag(0x0018, 0x9087), kGradientOrientation(0x0018, 0x9089), kFrameType(0x0008, 0x9007),
    kImageTypeTag(0x0008, 0x0008), kComplexComponentTag(0x0008, 0x9208), kDimensionIndexValues(0x0020, 0x9157),
    kFrameAcquisitionDateTime(0x0018, 0x9074), kAcquisitionDateTime(0x0008, 0x002a), kAcquisitionTime(0x0008, 0x0032);

// GDCM (and the codecs under it) would print to stderr; octrace reports its own one-line errors.
void silenceGdcm() {
    static const bool once = [] {
        gdcm::Trace::DebugOff();
        gdcm::Trace::WarningOff();
        gdcm::Trace::ErrorOff();
        return true;
    }();
    (void)once;
}

// Values of the attributes a frame's geometry and rescale come from, looked up in the
// frame's Per-frame Functional Groups item, then the Shared one, then the top level. Keeps the
// sequences it opened alive (GDCM may decode one on request and hand out the only reference).
class Attributes {
public:
    explicit Attributes(const gdcm::File& file) : top_(file.GetDataSet()) { filter_.SetFile(file); }

    std::optional<std::string> text(const gdcm::DataSet& ds, gdcm::Tag tag) const {
        if (!ds.FindDataElement(tag)) return std::nullopt;
        const gdcm::DataElement& de = ds.GetDataElement(tag);
        if (de.IsEmpty()) return std::nullopt;
        return trim(filter_.ToString(de));
    }
    std::optional<std::string> text(gdcm::Tag tag) const { return text(top_, tag); }

    /// Item `n` (0-based) of the sequence `seq` in `ds`, or null.
    const gdcm::DataSet* item(const gdcm::DataSet& ds, gdcm::Tag seq, std::size_t n) {
        if (!ds.FindDataElement(seq)) return nullptr;
        gdcm::SmartPointer<gdcm::SequenceOfItems> sq = ds.GetDataElement(seq).GetValueAsSQ();
        if (!sq || n >= sq->GetNumberOfItems()) return nullptr;
        keep_.push_back(sq);
        return &sq->GetItem(n + 1).GetNestedDataSet();  // GDCM counts items from 1
    }
    std::size_t items(gdcm::Tag seq) {
        if (!top_.FindDataElement(seq)) return 0;
        gdcm::SmartPointer<gdcm::SequenceOfItems> sq = top_.GetDataElement(seq).GetValueAsSQ();
        if (!sq) return 0;
        keep_.push_back(sq);
        return sq->GetNumberOfItems();
    }

    /// `attr` of frame `frame`: in macro `macro` of its per-frame item, of the shared item, or
    /// at the top level.
    std::optional<std::string> frameText(std::size_t frame, gdcm::Tag macro, gdcm::Tag attr) {
        return frameText(frame, macro, std::nullopt, attr);
    }
    /// The same, with `attr` in the first item of sequence `inner` of the macro.
    std::optional<std::string> frameText(std::size_t frame, gdcm::Tag macro, std::optional<gdcm::Tag> inner, gdcm::Tag attr) {
        for (const gdcm::DataSet* groups : {item(top_, kPerFrameGroups, frame), item(top_, kSharedGroups, 0)}) {
            const gdcm::DataSet* m = groups ? item(*groups, macro, 0) : nullptr;
            if (m && inner) m = item(*m, *inner, 0);
            if (auto v = m ? text(*m, attr) : std::nullopt) return v;
        }
        return text(attr);
    }
    const gdcm::DataSet& top() const { return top_; }

private:
    const gdcm::DataSet& top_;
    gdcm::StringFilter filter_;
    std::vector<gdcm::SmartPointer<gdcm::SequenceOfItems>> keep_;
};

// `count` numbers separated by backslashes (a DS or IS value); all finite.
std::optional<std::vector<double>> numbers(const std::string& text, std::size_t count) {
    auto v = dicomNumbers(text);
    if (!v || v->size() != count) return std::nullopt;
    return v;
}

// A DS/IS value for a message: its backslash separators kept, anything else unprintable escaped.
std::string printable(const std::string& text) {
    std::string out;
    for (char c : text) out += c == '\\' ? std::string(1, c) : quoteBytes(std::string(1, c));
    return out;
}

// GDCM's image reader takes attributes through gdcm::Attribute<>, which asserts (and so
// aborts the process: Debian builds GDCM with assertions on) when an element's explicit VR
// is not compatible with the one its dictionary gives (found by fuzz_dicom: a
// PixelRepresentation of VR UI). Such an element is refused first, wherever GDCM has parsed
// it: at the top level and in nested items (depth bounded as in DicomValidator.h).
void checkDictionaryVrs(const std::string& file, const gdcm::DataSet& ds, int depth) {
    static const gdcm::Dict& dict = gdcm::Global::GetInstance().GetDicts().GetPublicDict();
    for (const gdcm::DataElement& de : ds.GetDES()) {
        const gdcm::Tag& tag = de.GetTag();
        const gdcm::VR vr = de.GetVR();  // INVALID in implicit VR
        if (!tag.IsPrivate() && vr != gdcm::VR::INVALID && vr != gdcm::VR::UN) {
            const gdcm::VR want = dict.GetDictEntry(tag).GetVR();
            if (want != gdcm::VR::INVALID && want != gdcm::VR::UN && want != gdcm::VR::VR_END && !want.Compatible(vr)) {
                char name[16];
                std::snprintf(name, sizeof name, "(%04X,%04X)", tag.GetGroup(), tag.GetElement());
                throw FileError(file + ": element " + name + " has VR " + gdcm::VR::GetVRString(vr) +
                                ", the DICOM dictionary's is " + gdcm::VR::GetVRString(want));
            }
        }
        // Only sequences GDCM has parsed already (GetValueAsSQ() would parse UN values).
        if (depth >= kMaxDicomSequenceDepth || de.IsEmpty() || de.GetByteValue()) continue;
        if (const auto* sq = dynamic_cast<const gdcm::SequenceOfItems*>(&de.GetValue()))
            for (gdcm::SequenceOfItems::SizeType i = 1; i <= sq->GetNumberOfItems(); ++i)
                checkDictionaryVrs(file, sq->GetItem(i).GetNestedDataSet(), depth + 1);
    }
}

struct Context {
    const std::string& file;
    Attributes& attrs;

    [[noreturn]] void fail(const std::string& what) const { throw FileError(file + ": " + what); }

    /// The numbers of `attr` for `frame`, or nothing when absent; refused when malformed.
    std::optional<std::vector<double>> frameNumbers(std::size_t frame, gdcm::Tag macro, gdcm::Tag attr, std::size_t count,
                                                    const char* name) const {
        auto t = attrs.frameText(frame, macro, attr);
        if (!t) return std::nullopt;
        auto v = numbers(*t, count);
        if (!v)
            fail(std::string(name) + " '" + printable(*t) + "'" + (frame > 0 ? " of frame " + std::to_string(frame + 1) : "") +
                 " is not " + std::to_string(count) + " finite number" + (count > 1 ? "s" : ""));
        return v;
    }
    long integer(gdcm::Tag tag, const char* name, long fallback) const {
        auto t = attrs.text(tag);
        if (!t) return fallback;
        char* stop = nullptr;
        const long v = std::strtol(t->c_str(), &stop, 10);
        if (t->empty() || *stop != '\0') fail(std::string(name) + " '" + quoteBytes(*t) + "' is not an integer");
        return v;
    }
};

DicomFrame readFrame(const Context& c, std::size_t n) {
    DicomFrame f;
    if (auto p = c.frameNumbers(n, kPlanePosition, kPosition, 3, "ImagePositionPatient")) {
        f.hasPosition = true;
        f.position = dvec3((*p)[0], (*p)[1], (*p)[2]);
    }
    if (auto o = c.frameNumbers(n, kPlaneOrientation, kOrientation, 6, "ImageOrientationPatient")) {
        f.hasOrientation = true;
        f.rowDir = dvec3((*o)[0], (*o)[1], (*o)[2]);
        f.colDir = dvec3((*o)[3], (*o)[4], (*o)[5]);
    }
    if (auto s = c.frameNumbers(n, kPixelMeasures, kPixelSpacing, 2, "PixelSpacing")) {
        if (!((*s)[0] > 0.0 && (*s)[1] > 0.0))
            c.fail("PixelSpacing " + num((*s)[0]) + "\\" + num((*s)[1]) + " must be positive");
        f.hasPixelSpacing = true;
        f.pixelSpacing = dvec2((*s)[0], (*s)[1]);
    }
    if (auto s = c.frameNumbers(n, kValueTransformation, kSlope, 1, "RescaleSlope")) f.slope = (*s)[0];
    if (auto i = c.frameNumbers(n, kValueTransformation, kIntercept, 1, "RescaleIntercept")) f.intercept = (*i)[0];
    if (f.slope == 0.0) c.fail("RescaleSlope is 0");
    // A window is optional: one that is malformed, or has no positive width, is ignored
    // rather than refused (it only changes the default colours).
    auto firstNumber = [&](gdcm::Tag tag) -> std::optional<double> {
        auto t = c.attrs.frameText(n, kFrameVoiLut, tag);
        if (!t) return std::nullopt;
        const std::string first = t->substr(0, t->find('\\'));
        auto v = numbers(first, 1);
        return v ? std::optional<double>((*v)[0]) : std::nullopt;
    };
    auto centre = firstNumber(kWindowCentre), width = firstNumber(kWindowWidth);
    if (centre && width && *width > 0.0) {
        f.windowCentre = *centre;
        f.windowWidth = *width;
    }
    return f;
}

// The attribute tags of a gdcm AT value as text ("(0020,9056)" or "00209056"): its hex digits.
std::optional<gdcm::Tag> tagOf(const std::string& text) {
    std::string hex;
    for (char ch : text)
        if (std::isxdigit(static_cast<unsigned char>(ch))) hex += ch;
    if (hex.size() != 8) return std::nullopt;
    const unsigned long v = std::strtoul(hex.c_str(), nullptr, 16);
    return gdcm::Tag(std::uint16_t(v >> 16), std::uint16_t(v & 0xffff));
}

// Which of DimensionIndexValues' entries are spatial (the stack, the position in it, the
// position itself): those say where a frame lies, not which volume it belongs to. Nothing
// when a pointer cannot be read (the values are then not used). `names` gets the keywords of
// the others (GDCM's dictionary; "(GGGG,EEEE)" for a private or unknown one).
std::optional<std::vector<bool>> spatialDimensions(Attributes& attrs, std::string& names) {
    std::vector<bool> spatial;
    for (std::size_t i = 0, n = attrs.items(kDimensionIndexSeq); i < n; ++i) {
        const gdcm::DataSet* d = attrs.item(attrs.top(), kDimensionIndexSeq, i);
        const auto pointer = d ? attrs.text(*d, kDimensionIndexPointer) : std::nullopt;
        const auto tag = pointer ? tagOf(*pointer) : std::nullopt;
        if (!tag) return std::nullopt;
        spatial.push_back(*tag == kStackId || *tag == kInStackPosition || *tag == kPosition);
        if (spatial.back()) continue;
        static const gdcm::Dict& dict = gdcm::Global::GetInstance().GetDicts().GetPublicDict();
        // GDCM answers an unknown tag with the entry of (FFFF,FFFF).
        const gdcm::DictEntry& entry = dict.GetDictEntry(*tag);
        std::string keyword = tag->IsPrivate() || &entry == &dict.GetDictEntry(gdcm::Tag(0xffff, 0xffff)) ? "" : entry.GetKeyword();
        if (keyword.empty()) {
            char text[16];
            std::snprintf(text, sizeof text, "(%04X,%04X)", tag->GetGroup(), tag->GetElement());
            keyword = text;
        }
        names += (names.empty() ? "" : ", ") + keyword;
    }
    return spatial;
}

// The VolumeAttributes of frame `n` (DicomSeries.h) and its acquisition time.
void readVolumeKey(const Context& c, std::size_t n, const std::optional<std::vector<bool>>& spatial, DicomFrame& f) {
    Attributes& a = c.attrs;
    auto first = [](std::initializer_list<std::optional<std::string>> v) {
        for (const auto& x : v)
            if (x && !x->empty()) return *x;
        return std::string();
    };
    auto& k = f.volumeKey;
    k[kTemporalPosition] = first({a.frameText(n, kFrameContent, kTemporalPositionIndex), a.text(kTemporalPositionIdentifier)});
    k[kTriggerTime] = first({a.frameText(n, kCardiacSync, kNominalTriggerDelay), a.text(kTriggerTimeTag)});
    k[kStack] = first({a.frameText(n, kFrameContent, kStackId)});
    k[kEchoNumber] = first({a.text(kEchoNumbers)});
    k[kEchoTime] = first({a.frameText(n, kMrEcho, kEffectiveEchoTime), a.text(kEchoTimeTag)});
    k[kBValue] = first({a.frameText(n, kMrDiffusion, kBValueTag)});
    k[kGradientDirection] = first({a.frameText(n, kMrDiffusion, kGradientDirectionSeq, kGradientOrientation)});
    k[kImageType] = first({a.frameText(n, kMrFrameType, kFrameType), a.frameText(n, kCtFrameType, kFrameType), a.text(kImageTypeTag)});
    k[kComplexComponent] = first({a.frameText(n, kMrFrameType, kComplexComponentTag)});
    if (spatial && !spatial->empty()) {
        const std::string values = first({a.frameText(n, kFrameContent, kDimensionIndexValues)});
        std::string kept;
        std::size_t start = 0, index = 0;
        while (!values.empty() && start <= values.size()) {
            std::size_t end = values.find('\\', start);
            if (end == std::string::npos) end = values.size();
            if (index < spatial->size() && !(*spatial)[index]) kept += (kept.empty() ? "" : "\\") + trim(values.substr(start, end - start));
            start = end + 1;
            ++index;
        }
        k[kDimensionIndex] = kept;
    }
    f.acquired = first({a.frameText(n, kFrameContent, kFrameAcquisitionDateTime), a.text(kAcquisitionDateTime), a.text(kAcquisitionTime)});
}

// What the pixel data must occupy at least, checked against the bytes left in the file, so
// that a header declaring 100,000 frames is refused before anything is allocated for them.
void checkPixelDataFits(const Context& c, const DicomHeader& h, bool encapsulated, std::uintmax_t bytesLeft) {
    const double samples = double(h.rows) * double(h.columns) * double(h.frames.size());
    if (samples > kMaxSamplesPerFile)
        c.fail(std::to_string(h.columns) + "x" + std::to_string(h.rows) + " pixels x " + std::to_string(h.frames.size()) +
               " frames is more than octrace reads from one file (" + num(kMaxSamplesPerFile) + " samples)");
    // Compressed frames each take at least one fragment item (8 bytes); native ones their size.
    const double need = encapsulated ? 8.0 * double(h.frames.size()) : samples * h.bitsAllocated / 8.0;
    if (need > double(bytesLeft))
        c.fail("header declares " + std::to_string(h.frames.size()) + " frame(s) of " + std::to_string(h.columns) + "x" +
               std::to_string(h.rows) + " x " + std::to_string(h.bitsAllocated) + " bits, which need at least " +
               std::to_string(static_cast<unsigned long long>(need)) + " bytes, but only " + std::to_string(bytesLeft) + " bytes follow the header");
}

const char* codingName(const gdcm::TransferSyntax& ts) {
    const std::string uid = ts.GetString() ? ts.GetString() : "";
    if (uid.rfind("1.2.840.10008.1.2.4.9", 0) == 0) return "JPEG 2000";
    if (uid.rfind("1.2.840.10008.1.2.4.8", 0) == 0) return "JPEG-LS";
    if (uid.rfind("1.2.840.10008.1.2.4.", 0) == 0) return "JPEG";
    if (uid == "1.2.840.10008.1.2.5") return "RLE";
    return "uncompressed";
}

template <typename T>
void toFloat(const char* bytes, std::size_t n, std::vector<float>& out) {
    out.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        T v;
        std::memcpy(&v, bytes + i * sizeof(T), sizeof(T));
        out[i] = static_cast<float>(v);
    }
}

}  // namespace

bool looksLikeDicom(const std::string& file) {
    const std::string head = readPrefix(file, 132);
    if (head.size() == 132 && head.compare(128, 4, "DICM") == 0) return true;
    const std::string ext = lower(std::filesystem::path(file).extension().string());
    return ext == ".dcm" || ext == ".dicom" || isDicomDir(file);
}

bool isDicomDir(const std::string& file) {
    if (std::filesystem::path(file).filename() == "DICOMDIR") return true;
    const std::string head = readPrefix(file, 512);
    return head.find("1.2.840.10008.1.3.10") != std::string::npos;  // Media Storage Directory Storage
}

std::optional<DicomHeader> readDicomHeader(const std::string& file, std::string& whyNot) {
    silenceGdcm();
    // Our structure walk first: GDCM aborts the process on some corrupt files.
    if (!validateDicomFile(file, whyNot)) return std::nullopt;
    gdcm::Reader reader;
    reader.SetFileName(file.c_str());
    // Skipping the pixel data's value stops the reader just before it: the stream position
    // is then the size of the header.
    if (!reader.ReadUpToTag(kPixelData, {kPixelData})) {
        whyNot = "not a DICOM file GDCM can parse";
        return std::nullopt;
    }
    checkDictionaryVrs(file, reader.GetFile().GetDataSet(), 0);
    Attributes attrs(reader.GetFile());
    const Context c{file, attrs};
    DicomHeader h;
    h.file = file;
    h.rows = int(c.integer(gdcm::Tag(0x0028, 0x0010), "Rows", 0));
    h.columns = int(c.integer(gdcm::Tag(0x0028, 0x0011), "Columns", 0));
    if (h.rows == 0 && h.columns == 0) {
        whyNot = "a DICOM file without an image (no Rows/Columns)";
        return std::nullopt;
    }
    if (h.rows < 2 || h.columns < 2 || h.rows > 65535 || h.columns > 65535)
        c.fail("image size " + std::to_string(h.columns) + "x" + std::to_string(h.rows) +
               " (Columns x Rows) must be at least 2x2 and at most 65535");
    const long frames = c.integer(gdcm::Tag(0x0028, 0x0008), "NumberOfFrames", 1);
    if (frames < 1 || frames > kMaxFrames)
        c.fail("NumberOfFrames " + std::to_string(frames) + " must lie in 1.." + std::to_string(kMaxFrames));
    const long samplesPerPixel = c.integer(gdcm::Tag(0x0028, 0x0002), "SamplesPerPixel", 1);
    if (samplesPerPixel != 1)
        c.fail("SamplesPerPixel " + std::to_string(samplesPerPixel) + ": colour images are not supported (a volume needs one value per pixel)");
    // One value per pixel is not enough: a palette maps it to colours.
    const std::string photometric = attrs.text(gdcm::Tag(0x0028, 0x0004)).value_or("MONOCHROME2");
    if (photometric != "MONOCHROME1" && photometric != "MONOCHROME2")
        c.fail("PhotometricInterpretation " + quoteBytes(photometric) +
               ": colour images are not supported (a volume needs one grey value per pixel: MONOCHROME1 or MONOCHROME2)");
    h.monochrome1 = photometric == "MONOCHROME1";
    h.bitsAllocated = int(c.integer(gdcm::Tag(0x0028, 0x0100), "BitsAllocated", 16));
    if (h.bitsAllocated != 8 && h.bitsAllocated != 16 && h.bitsAllocated != 32)
        c.fail("BitsAllocated " + std::to_string(h.bitsAllocated) + " is not supported (8, 16 or 32)");

    h.seriesUid = attrs.text(gdcm::Tag(0x0020, 0x000e)).value_or("");
    h.modality = attrs.text(gdcm::Tag(0x0008, 0x0060)).value_or("");
    h.description = attrs.text(gdcm::Tag(0x0008, 0x103e)).value_or("");
    h.seriesNumber = int(c.integer(gdcm::Tag(0x0020, 0x0011), "SeriesNumber", 0));

    const std::size_t perFrameItems = attrs.items(kPerFrameGroups);
    if (perFrameItems > 0 && perFrameItems < std::size_t(frames))
        c.fail("Per-frame Functional Groups Sequence has " + std::to_string(perFrameItems) + " items for " +
               std::to_string(frames) + " frames");
    h.frames.resize(std::size_t(frames));
    const bool encapsulated = reader.GetFile().GetHeader().GetDataSetTransferSyntax().IsEncapsulated();
    const std::uintmax_t size = fileSize(file), at = reader.GetStreamCurrentPosition();
    checkPixelDataFits(c, h, encapsulated, size > at ? size - at : 0);

    const auto spatial = spatialDimensions(attrs, h.dimensionNames);
    for (std::size_t n = 0; n < h.frames.size(); ++n) {
        h.frames[n] = readFrame(c, n);
        readVolumeKey(c, n, spatial, h.frames[n]);
    }
    // For an image with functional groups GDCM's image reader computes the slice spacing from
    // the orientation in them (or at the top level) and asserts, aborting the process, when
    // there is none (found by fuzz_dicom).
    const bool groups = perFrameItems > 0 || attrs.items(kSharedGroups) > 0;
    if (groups && !h.frames[0].hasOrientation)
        c.fail("multi-frame image with functional groups but no ImageOrientationPatient (neither in them nor at the top level)");
    for (gdcm::Tag t : {kSpacingBetweenSlices, kSliceThickness}) {
        if (auto s = c.frameNumbers(0, kPixelMeasures, t, 1, t == kSliceThickness ? "SliceThickness" : "SpacingBetweenSlices"))
            if ((*s)[0] > 0.0 && h.sliceSpacing == 0.0) h.sliceSpacing = (*s)[0];
    }
    return h;
}

std::vector<float> decodeDicomFrames(const DicomHeader& h) {
    silenceGdcm();
    // Again: the file is opened anew, and GDCM must never see a broken structure.
    if (std::string whyNot; !validateDicomFile(h.file, whyNot)) throw FileError(h.file + ": " + whyNot);
    gdcm::ImageReader reader;
    reader.SetFileName(h.file.c_str());
    if (!reader.Read()) throw FileError(h.file + ": GDCM cannot read its image (pixel data missing or broken)");
    const gdcm::Image& image = reader.GetImage();
    const gdcm::PixelFormat& pf = image.GetPixelFormat();
    const std::size_t frames = h.frames.size();
    const unsigned depth = image.GetNumberOfDimensions() >= 3 ? image.GetDimension(2) : 1;
    if (image.GetColumns() != unsigned(h.columns) || image.GetRows() != unsigned(h.rows) || depth != frames ||
        pf.GetSamplesPerPixel() != 1 || pf.GetBitsAllocated() != unsigned(h.bitsAllocated))
        throw FileError(h.file + ": its image does not match its header (" + std::to_string(image.GetColumns()) + "x" +
                        std::to_string(image.GetRows()) + "x" + std::to_string(depth) + ")");

    const std::size_t count = std::size_t(h.rows) * std::size_t(h.columns) * frames;
    const std::size_t bytes = count * std::size_t(h.bitsAllocated / 8);
    const char* coding = codingName(image.GetTransferSyntax());
    const gdcm::DataElement& pixels = image.GetDataElement();
    if (pixels.IsEmpty()) throw FileError(h.file + ": no pixel data");
    if (const gdcm::SequenceOfFragments* fragments = pixels.GetSequenceOfFragments()) {
        if (fragments->GetNumberOfFragments() < frames)
            throw FileError(h.file + ": its " + coding + " pixel data hold " + std::to_string(fragments->GetNumberOfFragments()) +
                            " fragment(s) for " + std::to_string(frames) + " frames: truncated");
    } else if (const gdcm::ByteValue* raw = pixels.GetByteValue()) {
        if (raw->GetLength() < bytes)
            throw FileError(h.file + ": pixel data truncated: " + std::to_string(raw->GetLength()) + " bytes, the image needs " +
                            std::to_string(bytes));
    }
    if (image.GetBufferLength() != bytes)
        throw FileError(h.file + ": GDCM decodes " + std::to_string(image.GetBufferLength()) + " bytes, the image needs " +
                        std::to_string(bytes));
    std::vector<char> buffer(bytes);
    if (!image.GetBuffer(buffer.data()))
        throw FileError(h.file + ": cannot decode its " + std::string(coding) + " pixel data (transfer syntax " +
                        image.GetTransferSyntax().GetString() + "): truncated or corrupt");

    std::vector<float> values;
    const bool isSigned = pf.GetPixelRepresentation() == 1;
    switch (h.bitsAllocated) {
        case 8: isSigned ? toFloat<std::int8_t>(buffer.data(), count, values) : toFloat<std::uint8_t>(buffer.data(), count, values); break;
        case 16: isSigned ? toFloat<std::int16_t>(buffer.data(), count, values) : toFloat<std::uint16_t>(buffer.data(), count, values); break;
        default: isSigned ? toFloat<std::int32_t>(buffer.data(), count, values) : toFloat<std::uint32_t>(buffer.data(), count, values); break;
    }
    return values;
}

}  // namespace octrace::io::detail
