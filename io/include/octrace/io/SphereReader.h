#pragma once
/// @file SphereReader.h
/// Molecules as sphere scenes: PDB (.pdb, .ent) and PDBx/mmCIF (.cif, .mmcif) files, every
/// atom a sphere of its element's van der Waals radius (Bondi 1964) and colour (Jmol's CPK
/// colours). Only the first model is read; of alternate locations, the blank one and the first
/// letter met. Coordinates in angstroms (SphereSet::units "angstrom").
#include "octrace/scene/Spheres.h"

#include <cstdint>
#include <string>
#include <string_view>

namespace octrace::io {

/// Whether `path` names a molecule file by its extension (.pdb, .ent, .cif, .mmcif, any case).
bool isMoleculeFile(const std::string& path);

/// Reads a molecule file; the format follows the content (a line starting "data_" or a
/// `_atom_site.` loop: mmCIF; ATOM/HETATM records: PDB).
/// @throws InputError "PATH: no such file"; FileError "PATH: file is empty (0 bytes)", a
///         malformed record (with its line number and the field), "no atoms"; LimitError when
///         the atoms would need more than `memoryBudget` bytes (0 = no limit) or the file holds
///         more than kMaxSpheres atom records (checked before the spheres are allocated).
SphereSet readMolecule(const std::string& path, std::uint64_t memoryBudget = 0);

/// readMolecule on text already in memory; `name` stands for the path in messages.
SphereSet parseMolecule(std::string_view text, const std::string& name, std::uint64_t memoryBudget = 0);

/// Van der Waals radius in angstroms of an element symbol (any case): Bondi (1964),
/// "van der Waals volumes and radii", J. Phys. Chem. 68, 441; elements Bondi does not list
/// (Fe, Ca, Mn, Co, ...) get 2.0. `known` (optional) tells whether Bondi lists it.
double vanDerWaalsRadius(std::string_view element, bool* known = nullptr);
/// Linear RGB colour of an element (Jmol's CPK colours, converted from sRGB); pink for the
/// unknown ones.
vec3 elementColour(std::string_view element);

}  // namespace octrace::io
