#include "octrace/io/VideoWriter.h"

#include "octrace/io/AtomicFile.h"
#include "octrace/util/Error.h"
#include "octrace/util/Log.h"

// FFmpeg's headers for its types and macros only: the libraries are opened when the first video
// is written (dlopen), not linked. Linked, they and the libraries only they need (88 on Debian 12,
// codecs mostly) were loaded and relocated by every octrace process at its start, about 40
// ms of each `octrace render`, though only `animate` and Python's VideoWriter write videos.
extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/imgutils.h>
#include <libavutil/log.h>
#include <libavutil/macros.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

#include <dlfcn.h>

#include <algorithm>
#include <cstring>
#include <mutex>
#include <vector>

namespace octrace::io {
namespace {

// The FFmpeg functions this file calls, per library: X(library, function).
#define OCTRACE_FFMPEG_FUNCTIONS(X)                                                                                        \
    X(util, av_strerror) X(util, av_log_set_level) X(util, av_opt_set) X(util, av_malloc) X(util, av_free) X(util, av_freep) \
    X(util, av_frame_alloc) X(util, av_frame_free) X(util, av_frame_get_buffer) X(util, av_frame_make_writable)            \
    X(codec, avcodec_find_encoder_by_name) X(codec, avcodec_find_encoder) X(codec, avcodec_alloc_context3)                  \
    X(codec, avcodec_open2) X(codec, avcodec_parameters_from_context) X(codec, avcodec_send_frame)                          \
    X(codec, avcodec_receive_packet) X(codec, avcodec_free_context) X(codec, av_packet_alloc) X(codec, av_packet_free)       \
    X(codec, av_packet_rescale_ts) X(format, avformat_alloc_output_context2) X(format, avformat_new_stream)                  \
    X(format, avformat_write_header) X(format, av_interleaved_write_frame) X(format, av_write_trailer)                       \
    X(format, avformat_free_context) X(format, avio_alloc_context) X(format, avio_context_free) X(format, avio_flush)         \
    X(scale, sws_getContext) X(scale, sws_scale) X(scale, sws_freeContext)

/// FFmpeg's functions, from the libraries of the major versions these headers declare (their ABI).
struct Ffmpeg {
#define OCTRACE_FFMPEG_POINTER(lib, f) decltype(&::f) f = nullptr;
    OCTRACE_FFMPEG_FUNCTIONS(OCTRACE_FFMPEG_POINTER)
#undef OCTRACE_FFMPEG_POINTER
};

/// The libraries' file names (sonames), e.g. libavcodec.so.59.
constexpr const char* kLibUtil = "libavutil.so." AV_STRINGIFY(LIBAVUTIL_VERSION_MAJOR);
constexpr const char* kLibCodec = "libavcodec.so." AV_STRINGIFY(LIBAVCODEC_VERSION_MAJOR);
constexpr const char* kLibFormat = "libavformat.so." AV_STRINGIFY(LIBAVFORMAT_VERSION_MAJOR);
constexpr const char* kLibScale = "libswscale.so." AV_STRINGIFY(LIBSWSCALE_VERSION_MAJOR);
/// Debian's packages of those libraries (libavutil's comes with them).
constexpr const char* kDebianPackages = "libavcodec" AV_STRINGIFY(LIBAVCODEC_VERSION_MAJOR) " libavformat" AV_STRINGIFY(
    LIBAVFORMAT_VERSION_MAJOR) " libswscale" AV_STRINGIFY(LIBSWSCALE_VERSION_MAJOR);

/// FFmpeg, opened the first time a video is written (and kept: its codecs' threads and tables
/// outlive any one video). @throws OutputError naming `path`, the library that did not open and
/// why, and the Debian packages that hold them.
const Ffmpeg& ffmpeg(const std::string& path) {
    static std::once_flag once;
    static Ffmpeg table;
    static std::string failure;  // empty when every function was found
    std::call_once(once, [] {
        struct Library {
            const char* name;
            void* handle = nullptr;
        };
        Library util{kLibUtil}, codec{kLibCodec}, format{kLibFormat}, scale{kLibScale};
        for (Library* l : {&util, &codec, &format, &scale})
            if (!(l->handle = dlopen(l->name, RTLD_NOW | RTLD_LOCAL))) {
                const char* why = dlerror();
                failure = why ? why : std::string(l->name) + " did not open";
                return;
            }
        const auto find = [](const Library& l, const char* name) -> void* {
            void* f = dlsym(l.handle, name);
            if (!f && failure.empty()) failure = std::string(l.name) + " has no function " + name;
            return f;
        };
#define OCTRACE_FFMPEG_FIND(lib, f) table.f = reinterpret_cast<decltype(table.f)>(find(lib, #f));
        OCTRACE_FFMPEG_FUNCTIONS(OCTRACE_FFMPEG_FIND)
#undef OCTRACE_FFMPEG_FIND
    });
    if (!failure.empty())
        throw OutputError(path + ": writing a video needs FFmpeg's libraries (" + kLibCodec + ", " + kLibFormat + ", " + kLibUtil +
                          ", " + kLibScale + "; Debian: apt-get install " + kDebianPackages + "): " + failure);
    return table;
}

std::string averror(const Ffmpeg& ff, int code) {
    char text[AV_ERROR_MAX_STRING_SIZE] = {};
    ff.av_strerror(code, text, sizeof text);
    return text;
}

// The MP4 muxer seeks back to write sizes: an in-memory file with a write position.
struct MemoryFile {
    std::vector<std::uint8_t> bytes;
    std::int64_t pos = 0;
};

#if LIBAVFORMAT_VERSION_MAJOR >= 61
int writePacket(void* opaque, const std::uint8_t* buf, int size) {
#else
int writePacket(void* opaque, std::uint8_t* buf, int size) {
#endif
    auto* f = static_cast<MemoryFile*>(opaque);
    const std::size_t end = std::size_t(f->pos) + std::size_t(size);
    if (end > f->bytes.size()) f->bytes.resize(end);
    std::memcpy(f->bytes.data() + f->pos, buf, std::size_t(size));
    f->pos = std::int64_t(end);
    return size;
}

std::int64_t seekPacket(void* opaque, std::int64_t offset, int whence) {
    auto* f = static_cast<MemoryFile*>(opaque);
    whence &= ~AVSEEK_FORCE;
    if (whence == AVSEEK_SIZE) return std::int64_t(f->bytes.size());
    const std::int64_t base = whence == SEEK_CUR ? f->pos : whence == SEEK_END ? std::int64_t(f->bytes.size()) : 0;
    if (base + offset < 0) return AVERROR(EINVAL);
    f->pos = base + offset;
    return f->pos;
}

const AVCodec* chooseEncoder(const Ffmpeg& ff, const std::string& path) {
    if (const AVCodec* c = ff.avcodec_find_encoder_by_name("libx264")) return c;
    if (const AVCodec* c = ff.avcodec_find_encoder(AV_CODEC_ID_H264)) return c;
    if (const AVCodec* c = ff.avcodec_find_encoder(AV_CODEC_ID_MPEG4)) {
        log::warning(path + ": FFmpeg's libavcodec has no H.264 encoder: the video is MPEG-4 part 2 (plays as widely, "
                            "larger at the same quality)");
        return c;
    }
    throw OutputError(path + ": FFmpeg's libavcodec has neither an H.264 nor an MPEG-4 encoder (Debian: libavcodec" AV_STRINGIFY(
                                 LIBAVCODEC_VERSION_MAJOR) " with libx264)");
}

}  // namespace

struct VideoWriter::Impl {
    const Ffmpeg* ff = nullptr;  ///< set once the arguments are checked (null: nothing of FFmpeg's to free)
    std::string path, codec;
    int width = 0, height = 0, evenW = 0, evenH = 0, frames = 0;
    bool finished = false;
    MemoryFile file;
    AVFormatContext* format = nullptr;
    AVCodecContext* encoder = nullptr;
    AVStream* stream = nullptr;
    AVFrame* frame = nullptr;
    AVPacket* packet = nullptr;
    SwsContext* sws = nullptr;
    std::vector<std::uint8_t> padded;  // RGBA at the even size

    ~Impl() {
        if (!ff) return;
        ff->sws_freeContext(sws);
        ff->av_packet_free(&packet);
        ff->av_frame_free(&frame);
        ff->avcodec_free_context(&encoder);
        if (format) {
            if (format->pb) {
                ff->av_freep(&format->pb->buffer);
                ff->avio_context_free(&format->pb);
            }
            ff->avformat_free_context(format);
        }
    }

    void check(int code, const std::string& what) const {
        if (code < 0) throw OutputError(path + ": " + what + ": " + averror(*ff, code));
    }

    // Sends `f` (null: end of stream) and writes the packets the encoder has ready.
    void encode(const AVFrame* f) {
        check(ff->avcodec_send_frame(encoder, f), "encoding a frame (" + codec + ")");
        while (true) {
            const int r = ff->avcodec_receive_packet(encoder, packet);
            if (r == AVERROR(EAGAIN) || r == AVERROR_EOF) return;
            check(r, "encoding a frame (" + codec + ")");
            // Every frame lasts one tick of 1/fps. The encoder leaves the duration 0, and the MP4
            // muxer then ends its edit list at the last frame's start: players dropped it.
            if (packet->duration <= 0) packet->duration = 1;
            ff->av_packet_rescale_ts(packet, encoder->time_base, stream->time_base);
            packet->stream_index = stream->index;
            check(ff->av_interleaved_write_frame(format, packet), "writing a frame");
        }
    }
};

VideoWriter::VideoWriter(std::string path, int width, int height, int fps, int quality) : impl_(std::make_unique<Impl>()) {
    Impl& m = *impl_;
    m.path = std::move(path);
    if (width < 1 || height < 1) throw UsageError(m.path + ": a video needs a size of at least 1x1 pixels");
    if (fps < 1 || fps > 240) throw UsageError(m.path + ": `fps` must be within [1, 240], got " + std::to_string(fps));
    m.width = width;
    m.height = height;
    m.evenW = width + (width & 1);
    m.evenH = height + (height & 1);
    if (m.evenW != width || m.evenH != height)
        log::info(m.path + ": " + std::to_string(width) + "x" + std::to_string(height) + " padded to " + std::to_string(m.evenW) +
                  "x" + std::to_string(m.evenH) + " (yuv420p needs even sides)");

    m.ff = &ffmpeg(m.path);
    m.ff->av_log_set_level(AV_LOG_ERROR);  // x264's statistics are not octrace's messages; errors are thrown
    m.check(m.ff->avformat_alloc_output_context2(&m.format, nullptr, "mp4", nullptr), "FFmpeg's MP4 muxer");
    const AVCodec* codec = chooseEncoder(*m.ff, m.path);
    m.codec = codec->name;
    m.encoder = m.ff->avcodec_alloc_context3(codec);
    if (!m.encoder) throw OutputError(m.path + ": out of memory for the encoder");
    m.encoder->width = m.evenW;
    m.encoder->height = m.evenH;
    m.encoder->time_base = AVRational{1, fps};
    m.encoder->framerate = AVRational{fps, 1};
    m.encoder->pix_fmt = AV_PIX_FMT_YUV420P;
    m.encoder->gop_size = std::max(1, 2 * fps);
    m.encoder->colorspace = AVCOL_SPC_SMPTE170M;  // BT.601, swscale's default matrix
    m.encoder->color_range = AVCOL_RANGE_MPEG;
    if (m.format->oformat->flags & AVFMT_GLOBALHEADER) m.encoder->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
    if (codec->id == AV_CODEC_ID_H264) {
        m.ff->av_opt_set(m.encoder->priv_data, "preset", "medium", 0);
        m.ff->av_opt_set(m.encoder->priv_data, "crf", std::to_string(std::clamp(quality, 0, 51)).c_str(), 0);
        if (std::string(codec->name) == "libx264" && quality == 0) m.ff->av_opt_set(m.encoder->priv_data, "profile", "high444", 0);
    } else {
        m.encoder->flags |= AV_CODEC_FLAG_QSCALE;
        m.encoder->global_quality = FF_QP2LAMBDA * std::clamp(1 + quality / 8, 1, 31);
    }
    m.check(m.ff->avcodec_open2(m.encoder, codec, nullptr), "opening the " + m.codec + " encoder");
    m.stream = m.ff->avformat_new_stream(m.format, nullptr);
    if (!m.stream) throw OutputError(m.path + ": out of memory for the video stream");
    m.stream->time_base = m.encoder->time_base;
    m.check(m.ff->avcodec_parameters_from_context(m.stream->codecpar, m.encoder), "the stream's parameters");

    constexpr int kBuffer = 1 << 16;
    auto* buffer = static_cast<unsigned char*>(m.ff->av_malloc(kBuffer));
    if (!buffer) throw OutputError(m.path + ": out of memory for the video buffer");
    m.format->pb = m.ff->avio_alloc_context(buffer, kBuffer, 1, &m.file, nullptr, writePacket, seekPacket);
    if (!m.format->pb) {
        m.ff->av_free(buffer);
        throw OutputError(m.path + ": out of memory for the video buffer");
    }
    m.format->flags |= AVFMT_FLAG_CUSTOM_IO | AVFMT_FLAG_BITEXACT;  // no encoder version in the file: same frames, same bytes
    m.check(m.ff->avformat_write_header(m.format, nullptr), "writing the MP4 header");

    m.frame = m.ff->av_frame_alloc();
    m.packet = m.ff->av_packet_alloc();
    if (!m.frame || !m.packet) throw OutputError(m.path + ": out of memory for a video frame");
    m.frame->format = AV_PIX_FMT_YUV420P;
    m.frame->width = m.evenW;
    m.frame->height = m.evenH;
    m.check(m.ff->av_frame_get_buffer(m.frame, 0), "a video frame");
    m.sws = m.ff->sws_getContext(m.evenW, m.evenH, AV_PIX_FMT_RGBA, m.evenW, m.evenH, AV_PIX_FMT_YUV420P, SWS_POINT, nullptr, nullptr,
                           nullptr);
    if (!m.sws) throw OutputError(m.path + ": swscale cannot convert RGBA to yuv420p");
    m.padded.resize(std::size_t(m.evenW) * std::size_t(m.evenH) * 4);
}

VideoWriter::~VideoWriter() = default;

void VideoWriter::add(std::span<const std::uint8_t> rgba) {
    Impl& m = *impl_;
    if (m.finished) throw UsageError(m.path + ": a frame added after the video was finished");
    const std::size_t row = std::size_t(m.width) * 4, evenRow = std::size_t(m.evenW) * 4;
    if (rgba.size() != row * std::size_t(m.height))
        throw UsageError(m.path + ": a frame of " + std::to_string(rgba.size()) + " bytes, expected " + std::to_string(m.width) + "x" +
                         std::to_string(m.height) + " RGBA");
    for (int y = 0; y < m.evenH; ++y) {
        const std::uint8_t* src = rgba.data() + std::size_t(std::min(y, m.height - 1)) * row;
        std::uint8_t* dst = m.padded.data() + std::size_t(y) * evenRow;
        std::memcpy(dst, src, row);
        if (m.evenW != m.width) std::memcpy(dst + row, src + row - 4, 4);
    }
    m.check(m.ff->av_frame_make_writable(m.frame), "a video frame");
    const std::uint8_t* planes[1] = {m.padded.data()};
    const int strides[1] = {int(evenRow)};
    m.ff->sws_scale(m.sws, planes, strides, 0, m.evenH, m.frame->data, m.frame->linesize);
    m.frame->pts = m.frames++;
    m.encode(m.frame);
}

void VideoWriter::finish() {
    Impl& m = *impl_;
    if (m.finished) return;
    if (m.frames == 0) throw OutputError(m.path + ": no frame to write");
    m.finished = true;
    m.encode(nullptr);
    m.check(m.ff->av_write_trailer(m.format), "ending the MP4 file");
    m.ff->avio_flush(m.format->pb);
    writeFileAtomically(m.path, std::span<const std::uint8_t>(m.file.bytes));
}

const std::string& VideoWriter::codec() const { return impl_->codec; }
int VideoWriter::frames() const { return impl_->frames; }

}  // namespace octrace::io
