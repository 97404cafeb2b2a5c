#pragma once
/// @file VideoWriter.h
/// An MP4 video, frame after frame, through FFmpeg's libraries (libavcodec, libavformat,
/// libswscale; no FFmpeg type here). H.264 by libx264 when Debian's libavcodec has it (it
/// does), else any H.264 encoder, else MPEG-4 part 2 with a warning: the file still plays
/// everywhere, larger at the same quality. Pixels are yuv420p (BT.601, limited range), which
/// needs even sides: an odd width or height is padded by repeating the last column or row.
/// The encoded file is held in memory and written atomically (AtomicFile.h) by finish(): a
/// reader never sees a partial video, and Ctrl-C leaves nothing behind.
#include <cstdint>
#include <memory>
#include <span>
#include <string>

namespace octrace::io {

class VideoWriter {
public:
    /// A video of `width` x `height` pixels at `fps` frames a second, to be written to `path`.
    /// `quality`: x264's constant rate factor (0 lossless .. 51; 18 looks lossless on renders).
    /// @throws UsageError (sizes < 1, fps outside 1..240), OutputError (no MP4 muxer or no
    ///         encoder in the FFmpeg libraries, or one that refuses the settings).
    VideoWriter(std::string path, int width, int height, int fps, int quality = 18);
    ~VideoWriter();
    VideoWriter(const VideoWriter&) = delete;
    VideoWriter& operator=(const VideoWriter&) = delete;

    /// Appends a frame: width·height RGBA8 pixels, sRGB, row 0 at the top (alpha ignored).
    /// @throws UsageError (wrong size, after finish()), OutputError (the encoder fails).
    void add(std::span<const std::uint8_t> rgba);
    /// Flushes the encoder, ends the file and writes it to `path` atomically. No frame: refused.
    /// @throws OutputError as writeFileAtomically, or when no frame was added.
    void finish();

    /// The encoder used: "libx264", another H.264 encoder's name, or "mpeg4".
    const std::string& codec() const;
    int frames() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace octrace::io
