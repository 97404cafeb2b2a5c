#include "octrace/io/ImageWriter.h"

#include "ImageTestSupport.h"
#include "octrace/io/AtomicFile.h"
#include "octrace/io/ExrWriter.h"
#include "octrace/io/PngWriter.h"
#include "octrace/util/Error.h"

#include <gtest/gtest.h>

#include <filesystem>

#include <unistd.h>

using namespace octrace;
using octrace::io::imageExtensions;
using octrace::io::writeImage;
using octrace::test::readBytes;
using octrace::test::ScratchDir;

namespace {

Frame greyFrame(int w, int h, float value) {
    Frame f(w, h);
    for (std::size_t i = 0; i < f.rgba.size(); ++i) {
        f.rgba[i] = vec4(value, value, value, 1.0f);
        f.depth[i] = float(i);
    }
    return f;
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

const std::vector<std::uint8_t> kPngSignature{0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
const std::vector<std::uint8_t> kExrMagic{0x76, 0x2f, 0x31, 0x01};

std::vector<std::uint8_t> head(const std::vector<std::uint8_t>& bytes, std::size_t n) {
    return {bytes.begin(), bytes.begin() + std::ptrdiff_t(std::min(n, bytes.size()))};
}

}  // namespace

TEST(ImageWriter, ListsTheSupportedExtensions) {
    EXPECT_EQ(imageExtensions(), (std::vector<std::string>{".png", ".exr", ".tif", ".tiff"}));
}

TEST(ImageWriter, ChoosesTheFormatByExtensionIgnoringCase) {
    ScratchDir dir;
    Frame f = greyFrame(6, 4, 0.5f);
    for (const char* name : {"a.png", "b.PNG", "c.Png"}) {
        writeImage(f, dir.file(name));
        auto bytes = readBytes(dir.file(name));
        EXPECT_EQ(head(bytes, 8), kPngSignature) << name;
        EXPECT_EQ(bytes, io::PngWriter::encode(f)) << name;
    }
    for (const char* name : {"d.exr", "e.EXR", "f.eXr"}) {
        writeImage(f, dir.file(name));
        auto bytes = readBytes(dir.file(name));
        EXPECT_EQ(head(bytes, 4), kExrMagic) << name;
        EXPECT_EQ(bytes, io::ExrWriter::encode(f)) << name;
    }
    EXPECT_EQ(dir.entries().size(), 6u);
}

TEST(ImageWriter, PassesTheAlphaOptionToPng) {
    ScratchDir dir;
    io::ImageWriteOptions options;
    options.alpha = true;
    writeImage(greyFrame(2, 2, 0.5f), dir.file("a.png"), options);
    auto png = octrace::test::decodePng(readBytes(dir.file("a.png")));
    EXPECT_EQ(png.channels, 4);
    EXPECT_EQ(png.at(0, 0, 0), 188);
}

TEST(ImageWriter, RejectsAnUnknownExtensionNamingItAndTheSupportedOnes) {
    ScratchDir dir;
    try {
        writeImage(greyFrame(2, 2, 0.5f), dir.file("figure.jpg"));
        FAIL() << "expected UsageError";
    } catch (const UsageError& e) {
        const std::string msg = e.what();
        EXPECT_TRUE(contains(msg, ".jpg")) << msg;
        EXPECT_TRUE(contains(msg, ".png")) << msg;
        EXPECT_TRUE(contains(msg, ".exr")) << msg;
    }
    EXPECT_THROW(writeImage(greyFrame(2, 2, 0.5f), dir.file("figure")), UsageError);
    EXPECT_THROW(writeImage(greyFrame(2, 2, 0.5f), dir.file("figure.png.bak")), UsageError);
    EXPECT_TRUE(dir.entries().empty());
}

TEST(ImageWriter, ReportsAMissingFolderAndLeavesNoFile) {
    ScratchDir dir;
    for (const char* name : {"missing/out.png", "missing/out.exr"}) {
        const std::string path = dir.file(name);
        try {
            writeImage(greyFrame(3, 3, 0.2f), path);
            FAIL() << "expected OutputError for " << name;
        } catch (const OutputError& e) {
            const std::string msg = e.what();
            EXPECT_TRUE(contains(msg, path)) << msg;
            EXPECT_TRUE(contains(msg, "does not exist")) << msg;
        }
    }
    EXPECT_TRUE(dir.entries().empty());  // neither the folder nor any temporary was created
}

TEST(ImageWriter, ReportsAFolderInTheWayOfTheTarget) {
    ScratchDir dir;
    std::filesystem::create_directory(dir.path() / "taken.png");
    EXPECT_THROW(writeImage(greyFrame(2, 2, 0.2f), dir.file("taken.png")), OutputError);
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"taken.png"});
    EXPECT_TRUE(std::filesystem::is_directory(dir.path() / "taken.png"));
}

TEST(ImageWriter, ReportsPermissionDeniedAndLeavesNoFile) {
    if (::geteuid() == 0) GTEST_SKIP() << "root ignores folder permissions";
    ScratchDir dir;
    std::filesystem::create_directory(dir.path() / "locked");
    std::filesystem::permissions(dir.path() / "locked",
                                 std::filesystem::perms::owner_read | std::filesystem::perms::owner_exec);
    const std::string path = dir.file("locked/out.png");
    try {
        writeImage(greyFrame(2, 2, 0.2f), path);
        FAIL() << "expected OutputError";
    } catch (const OutputError& e) {
        EXPECT_TRUE(contains(e.what(), path)) << e.what();
        EXPECT_TRUE(contains(e.what(), "ermission")) << e.what();
    }
    std::filesystem::permissions(dir.path() / "locked", std::filesystem::perms::owner_all);
    EXPECT_TRUE(std::filesystem::is_empty(dir.path() / "locked"));
}

TEST(ImageWriter, LeavesOnlyTheTargetAfterSuccess) {
    ScratchDir dir;
    writeImage(greyFrame(8, 8, 0.7f), dir.file("out.png"));
    writeImage(greyFrame(8, 8, 0.7f), dir.file("out.exr"));
    EXPECT_EQ(dir.entries(), (std::vector<std::string>{"out.exr", "out.png"}));
}

TEST(ImageWriter, ReplacesAnExistingFileWhole) {
    ScratchDir dir;
    const std::string path = dir.file("out.png");
    writeImage(greyFrame(300, 200, 0.3f), path);
    Frame small = greyFrame(2, 2, 0.9f);
    writeImage(small, path);
    EXPECT_EQ(readBytes(path), io::PngWriter::encode(small));
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"out.png"});
}

TEST(ImageWriter, LeavesAnExistingFileUntouchedWhenWritingFails) {
    ScratchDir dir;
    const std::string path = dir.file("out.exr");
    writeImage(greyFrame(4, 4, 0.3f), path);
    const auto before = readBytes(path);
    Frame broken(4, 4);
    broken.depth.resize(3);
    try {
        writeImage(broken, path);
        FAIL() << "expected OutputError";
    } catch (const OutputError& e) {
        EXPECT_TRUE(contains(e.what(), path)) << e.what();
        EXPECT_TRUE(contains(e.what(), "depth")) << e.what();
    }
    EXPECT_EQ(readBytes(path), before);
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"out.exr"});
}

TEST(AtomicFile, WritesTextAndBytes) {
    ScratchDir dir;
    io::writeFileAtomically(dir.file("s.json"), std::string_view("{\"a\": 1}\n"));
    const std::vector<std::uint8_t> bytes{0, 1, 2, 255};
    io::writeFileAtomically(dir.file("b.bin"), bytes);
    auto text = readBytes(dir.file("s.json"));
    EXPECT_EQ(std::string(text.begin(), text.end()), "{\"a\": 1}\n");
    EXPECT_EQ(readBytes(dir.file("b.bin")), bytes);
    EXPECT_EQ(dir.entries(), (std::vector<std::string>{"b.bin", "s.json"}));
}
