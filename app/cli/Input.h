#pragma once
#include "octrace/build/ScalarField.h"
#include "octrace/io/CityReader.h"
#include "octrace/io/FieldRequest.h"
#include "octrace/octree/Octree.h"

#include <cstdint>
#include <string>

namespace octrace::cli {
/// Reads INPUT: a file through io::readField, or "analytic:NAME[:SAMPLES]" (default 65 samples).
/// Both refuse (LimitError) samples that would need more than req.memoryBudget.
ScalarField loadField(const std::string& input, const io::FieldRequest& req);
/// Whether INPUT is an octree file (`octrace build`'s .oct): by its extension .oct (any case),
/// so that a damaged signature is reported as such, or by its signature.
bool isOctreeInput(const std::string& input);
/// Reads an octree file within `memoryBudget` bytes (0 = no limit); throws as
/// io::readOctreeFile.
Octree loadOctree(const std::string& input, std::uint64_t memoryBudget);
/// Text for `octrace info` (`req.series` chooses a DICOM series; reads that would need more
/// than `req.memoryBudget` bytes, 0 = no limit, are left out or refused: io::describeInput);
/// a city input in the CRS and LoD `city` asks for (io::describeCityInput).
std::string describe(const std::string& input, const io::FieldRequest& req = {}, const io::CityRequest& city = {});
}  // namespace octrace::cli
