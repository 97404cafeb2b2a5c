// Fuzz target: molecule files (io::parseMolecule): PDB ATOM/HETATM records (fixed columns,
// alternate locations, models) and PDBx/mmCIF (the STAR tokenizer: quotes, ;-text fields,
// loops, the _atom_site category), then SphereSet::validate and the object octree built over
// the atoms, as `octrace render` does next. The input is the file's bytes. Seeds:
// tests/fuzz/corpus/fuzz_molecule (written by tests/fuzz/corpus/make_seeds.py).
#include "FuzzSupport.h"
#include "octrace/io/SphereReader.h"
#include "octrace/scene/ObjectOctree.h"
#include "octrace/util/Error.h"

#include <string_view>

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    octrace::fuzz::quietLogs();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    try {
        const std::string_view text(reinterpret_cast<const char*>(data), size);
        octrace::SphereSet set = octrace::io::parseMolecule(text, "fuzz.pdb", octrace::fuzz::kMemoryBudget);
        if (set.spheres.empty()) __builtin_trap();  // validate() refuses an empty set
        octrace::ObjectOctreeOptions o;
        o.memoryBudget = octrace::fuzz::kMemoryBudget;
        octrace::ObjectOctree tree = octrace::ObjectOctree::build(std::move(set), o);
        tree.validate();
    } catch (const octrace::Error&) {
        // A clean refusal.
    }
    return 0;
}
