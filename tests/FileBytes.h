#pragma once
// A whole file's bytes in one read. The tests' sanitizer build compiles test sources at -O0,
// where copying a file through istreambuf_iterator costs several uninlined calls per byte (and
// a fake stack frame each under detect_stack_use_after_return): minutes for the CT series.
#include <cstdint>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace octrace::testutil {

/// The bytes of `path` as a Container of char-sized elements (std::string, std::vector<char>,
/// std::vector<std::uint8_t>); throws when the file cannot be opened or read.
template <class Container = std::string>
Container fileBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    if (!in) throw std::runtime_error("cannot open " + path);
    const std::streamsize size = in.tellg();
    Container bytes(static_cast<std::size_t>(size), typename Container::value_type{});
    in.seekg(0);
    if (size > 0 && !in.read(reinterpret_cast<char*>(bytes.data()), size)) throw std::runtime_error("cannot read " + path);
    return bytes;
}

}  // namespace octrace::testutil
