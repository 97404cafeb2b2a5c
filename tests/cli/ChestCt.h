#pragma once
// The LIDC chest CT sample written as a CT series by the project's writer, with the scale
// docs/dev/medical.md gives it (0..255 -> RescaleSlope 8, RescaleIntercept -1000 HU).
#include "CliRunner.h"

#include "octrace/io/DicomSeriesWriter.h"
#include "octrace/io/FieldReader.h"

namespace octrace::testcli {

/// Writes the series to `folder` with `o` (its rescale is set here); returns the field in HU.
inline ScalarField writeChestCtSeries(const std::string& folder, io::DicomSeriesWriteOptions o) {
    ScalarField ct = io::readField(sharedData("medical/lidc2_chest_ct.nrrd"));
    for (float& v : ct.values) v = 8.0f * v - 1000.0f;
    o.rescale = [](int) { return dvec2(8.0, -1000.0); };
    io::DicomSeriesWriter::write(ct, folder, o);
    return ct;
}

}  // namespace octrace::testcli
