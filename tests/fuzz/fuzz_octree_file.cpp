// Fuzz target: .oct octree files (io::decodeOctreeFile): signature, version, header, chunk
// table, zstd chunks, the breadth-first structure and Octree::validate. The input is the
// file's bytes. Checksums would stop nearly every mutation at the first check, so in the fuzz
// build (OCTRACE_FUZZ defines FUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION, the macro name
// OSS-Fuzz uses for this; see OctreeFile.cpp) a mismatch is ignored and the parser goes on. Seeds: tests/fuzz/corpus/fuzz_octree_file (small files of `octrace build`).
#include "FuzzSupport.h"
#include "octrace/io/OctreeFile.h"
#include "octrace/util/Error.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    octrace::fuzz::quietLogs();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    try {
        octrace::Octree t = octrace::io::decodeOctreeFile(std::span<const std::uint8_t>(data, size), "fuzz.oct",
                                                          octrace::fuzz::kMemoryBudget);
        // What a reader of the file does next: every voxel, summaries for --lod.
        std::size_t n = 0;
        t.forEachVoxel([&](const octrace::ivec3&, std::uint32_t) { ++n; });
        if (n > t.voxels().size()) __builtin_trap();
        t.computeSummaries();
    } catch (const octrace::Error&) {
        // A clean refusal.
    }
    return 0;
}
