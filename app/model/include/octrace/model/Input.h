#pragma once
#include "octrace/build/ScalarField.h"
#include "octrace/io/CityReader.h"
#include "octrace/io/FieldRequest.h"
#include "octrace/octree/Octree.h"
#include "octrace/scene/Spheres.h"

#include <cstdint>
#include <memory>
#include <string>

namespace octrace::model {
/// Reads INPUT: a file through io::readField, or "analytic:NAME[:SAMPLES]" (default 65 samples),
/// or a sphere scene (isSphereInput) as its signed distance field (sphereDistanceField) with
/// 2^depth + 5 samples along its longest side (`depth`: the octree depth it is built at).
/// Both refuse (LimitError) samples that would need more than req.memoryBudget.
/// `spheres`, when given, receives a sphere input's spheres (left empty for other inputs).
ScalarField loadField(const std::string& input, const io::FieldRequest& req, int depth,
                      std::shared_ptr<const SphereSet>* spheres = nullptr);
/// A sphere scene's signed distance field at `depth` as loadField makes it, from its spheres
/// `set` (loaded by the caller: `depth` auto needs their box first), which `spheres` receives.
ScalarField sphereField(const std::string& input, std::shared_ptr<const SphereSet> set, const io::FieldRequest& req, int depth,
                        std::shared_ptr<const SphereSet>* spheres = nullptr);
/// Whether INPUT is a sphere scene: "sphereflake:L" (Haines' SphereFlake, L 1..4),
/// "random:N[:SEED]" (N seeded random spheres, seed default 1) or a molecule file (.pdb,
/// .ent, .cif, .mmcif).
bool isSphereInput(const std::string& input);
/// Reads or generates a sphere scene within `memoryBudget` bytes (0 = no limit). Throws
/// UsageError for a malformed generator spec, as io::readMolecule for files.
SphereSet loadSpheres(const std::string& input, std::uint64_t memoryBudget);
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
}  // namespace octrace::model
