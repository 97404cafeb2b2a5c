// octrace_write_dicom: writes a volume (any input octrace reads) as a DICOM series with
// io::DicomSeriesWriter, for benchmarks that need a series where the data exist only as NRRD
// (bench/table1.py's CT rows: the LIDC chest CT).
//
//   octrace_write_dicom INPUT FOLDER [--modality CT|MR] [--rescale SLOPE,INTERCEPT]
//                       [--window CENTRE,WIDTH] [--monochrome1 yes]
//
// --rescale: the input holds stored values; the series' real values (Hounsfield units for CT)
// are value * SLOPE + INTERCEPT, written with that RescaleSlope / RescaleIntercept.
#include "octrace/io/DicomSeriesWriter.h"
#include "octrace/io/FieldReader.h"
#include "octrace/util/Error.h"

#include <cstdio>
#include <filesystem>
#include <cstdlib>
#include <string>

int main(int argc, char** argv) {
    using namespace octrace;
    if (argc < 3) {
        std::fprintf(stderr, "usage: octrace_write_dicom INPUT FOLDER [--modality CT|MR] [--rescale SLOPE,INTERCEPT] "
                             "[--window CENTRE,WIDTH] [--monochrome1 yes]\n");
        return 2;
    }
    io::DicomSeriesWriteOptions o;
    double slope = 1.0, intercept = 0.0;
    for (int i = 3; i + 1 < argc; i += 2) {
        const std::string opt = argv[i], value = argv[i + 1];
        if (opt == "--modality") o.modality = value;
        else if (opt == "--rescale" && std::sscanf(value.c_str(), "%lf,%lf", &slope, &intercept) == 2 && slope != 0.0) continue;
        else if (opt == "--window" && std::sscanf(value.c_str(), "%lf,%lf", &o.window.centre, &o.window.width) == 2) continue;
        else if (opt == "--monochrome1" && value == "yes") o.monochrome1 = true;
        else {
            std::fprintf(stderr, "octrace_write_dicom: bad option %s %s\n", opt.c_str(), value.c_str());
            return 2;
        }
    }
    try {
        ScalarField f = io::readField(argv[1]);
        for (float& v : f.values) v = float(double(v) * slope + intercept);
        o.rescale = [=](int) { return dvec2(slope, intercept); };
        o.description = std::filesystem::path(argv[1]).filename().string();
        io::DicomSeriesWriter::write(f, argv[2], o);
    } catch (const Error& e) {
        std::fprintf(stderr, "octrace_write_dicom: %s\n", e.what());
        return 1;
    }
    return 0;
}
