// Embree peer (bench/peers.py): traces the lattice isosurface mesh that VTK draws (dumped by
// vtk_peer.py) with Embree 3's packet API, at octrace's camera, and writes the frame and its times.
//
//   embree_peer MESH.bin OUT.json OUT.png --pos X,Y,Z --look X,Y,Z --up X,Y,Z --fov DEG --size WxH
//               --threads N [--frames K]
//
// MESH.bin: "OCTMESH1", uint64 points, uint64 triangles, float32 xyz per point, float32 normal
// per point, int32 three indices per triangle (little endian).
// Camera: octrace's pinhole (core Camera.cpp): vertical fov, pixel centres at +0.5, row 0 at the top.
// Rays are traced as coherent packets of 4x4 pixels (rtcIntersect16, the context flagged
// RTC_INTERSECT_CONTEXT_FLAG_COHERENT) over 8x8-pixel tiles handed to N std::threads from one
// atomic counter. Shading as vtk_peer.py: one light fixed to the camera (camera space
// 0.4,0.6,1), two-sided, ambient 0.15 + diffuse 0.85, the point normals interpolated with the
// hit's barycentric coordinates, colour 0.85,0.62,0.35, white background.
// Times (std::chrono::steady_clock): the BVH build (rtcCommitScene, RTC_BUILD_QUALITY_HIGH) and
// each frame after a first one; render_ms = the fastest of K frames.
#include <embree3/rtcore.h>
#include <zlib.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace {

struct V3 {
    double x = 0, y = 0, z = 0;
};
V3 operator-(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
V3 operator+(V3 a, V3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
V3 operator*(V3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
double dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
V3 cross(V3 a, V3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
V3 unit(V3 a) { return a * (1.0 / std::sqrt(dot(a, a))); }

V3 parseV3(const std::string& s) {
    V3 v;
    if (std::sscanf(s.c_str(), "%lf,%lf,%lf", &v.x, &v.y, &v.z) != 3) throw std::runtime_error("not x,y,z: " + s);
    return v;
}

struct Mesh {
    std::vector<float> points, normals;
    std::vector<std::int32_t> triangles;
};

Mesh readMesh(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    char magic[8];
    std::uint64_t np = 0, nt = 0;
    in.read(magic, 8);
    in.read(reinterpret_cast<char*>(&np), 8);
    in.read(reinterpret_cast<char*>(&nt), 8);
    if (!in || std::memcmp(magic, "OCTMESH1", 8) != 0) throw std::runtime_error(path + ": not an OCTMESH1 file");
    Mesh m;
    m.points.resize(3 * np);
    m.normals.resize(3 * np);
    m.triangles.resize(3 * nt);
    in.read(reinterpret_cast<char*>(m.points.data()), std::streamsize(m.points.size() * 4));
    in.read(reinterpret_cast<char*>(m.normals.data()), std::streamsize(m.normals.size() * 4));
    in.read(reinterpret_cast<char*>(m.triangles.data()), std::streamsize(m.triangles.size() * 4));
    if (!in) throw std::runtime_error(path + ": truncated");
    return m;
}

void writePng(const std::string& path, int w, int h, const std::vector<std::uint8_t>& rgb) {
    std::vector<std::uint8_t> raw;
    raw.reserve(std::size_t(h) * (3 * w + 1));
    for (int y = 0; y < h; ++y) {
        raw.push_back(0);
        raw.insert(raw.end(), rgb.begin() + std::ptrdiff_t(3) * w * y, rgb.begin() + std::ptrdiff_t(3) * w * (y + 1));
    }
    uLongf size = compressBound(uLong(raw.size()));
    std::vector<std::uint8_t> z(size);
    if (compress2(z.data(), &size, raw.data(), uLong(raw.size()), 6) != Z_OK) throw std::runtime_error("zlib failed");
    z.resize(size);
    std::ofstream out(path, std::ios::binary);
    const auto u32 = [&](std::uint32_t v) {
        const char b[4] = {char(v >> 24), char(v >> 16), char(v >> 8), char(v)};
        out.write(b, 4);
    };
    const auto chunk = [&](const char* type, const std::vector<std::uint8_t>& data) {
        u32(std::uint32_t(data.size()));
        std::uint32_t crc = std::uint32_t(crc32(0, reinterpret_cast<const Bytef*>(type), 4));
        if (!data.empty()) crc = std::uint32_t(crc32(crc, data.data(), uInt(data.size())));  // (a null buffer resets it)
        out.write(type, 4);
        out.write(reinterpret_cast<const char*>(data.data()), std::streamsize(data.size()));
        u32(crc);
    };
    out.write("\x89PNG\r\n\x1a\n", 8);
    std::vector<std::uint8_t> ihdr = {std::uint8_t(w >> 24), std::uint8_t(w >> 16), std::uint8_t(w >> 8), std::uint8_t(w),
                                      std::uint8_t(h >> 24), std::uint8_t(h >> 16), std::uint8_t(h >> 8), std::uint8_t(h),
                                      8, 2, 0, 0, 0};
    chunk("IHDR", ihdr);
    chunk("IDAT", z);
    chunk("IEND", {});
    if (!out) throw std::runtime_error(path + ": cannot write");
}

}  // namespace

int main(int argc, char** argv) try {
    if (argc < 4) {
        std::fprintf(stderr, "usage: embree_peer MESH.bin OUT.json OUT.png --pos --look --up --fov --size --threads [--frames]\n");
        return 2;
    }
    const std::string meshPath = argv[1], outJson = argv[2], outPng = argv[3];
    V3 pos, look, up{0, 0, 1};
    double fov = 30;
    int w = 640, h = 480, threads = 1, frames = 7;
    for (int i = 4; i + 1 < argc; i += 2) {
        const std::string k = argv[i], v = argv[i + 1];
        if (k == "--pos") pos = parseV3(v);
        else if (k == "--look") look = parseV3(v);
        else if (k == "--up") up = parseV3(v);
        else if (k == "--fov") fov = std::stod(v);
        else if (k == "--size") std::sscanf(v.c_str(), "%dx%d", &w, &h);
        else if (k == "--threads") threads = std::stoi(v);
        else if (k == "--frames") frames = std::stoi(v);
        else throw std::runtime_error("unknown option " + k);
    }
    const Mesh mesh = readMesh(meshPath);
    const std::size_t np = mesh.points.size() / 3, nt = mesh.triangles.size() / 3;

    // The BVH build uses Embree's own (TBB) threads, as many as asked.
    const std::string config = "threads=" + std::to_string(threads);
    RTCDevice device = rtcNewDevice(config.c_str());
    if (!device) throw std::runtime_error("rtcNewDevice failed");
    const auto t0 = std::chrono::steady_clock::now();
    RTCScene scene = rtcNewScene(device);
    rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), np));
    auto* ib = static_cast<std::uint32_t*>(
        rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(std::uint32_t), nt));
    std::memcpy(vb, mesh.points.data(), mesh.points.size() * 4);
    std::memcpy(ib, mesh.triangles.data(), mesh.triangles.size() * 4);
    rtcCommitGeometry(geom);
    rtcAttachGeometry(scene, geom);
    rtcReleaseGeometry(geom);
    rtcCommitScene(scene);
    const double buildMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();

    // octrace's pinhole camera.
    const V3 back = unit(pos - look), right = unit(cross(up, back)), upv = cross(back, right);
    const double halfH = std::tan(fov * M_PI / 360.0), halfW = halfH * w / h;
    const V3 lightCam = unit(V3{0.4, 0.6, 1.0});
    const V3 light = unit(right * lightCam.x + upv * lightCam.y + back * lightCam.z);
    const V3 colour{0.85, 0.62, 0.35};
    constexpr int kTile = 8;
    const int tilesX = (w + kTile - 1) / kTile, tilesY = (h + kTile - 1) / kTile;
    std::vector<std::uint8_t> rgb(std::size_t(3) * w * h, 255);
    std::vector<std::uint8_t> hit(std::size_t(w) * h, 0);

    const auto renderTile = [&](int tile) {
        const int tx = (tile % tilesX) * kTile, ty = (tile / tilesX) * kTile;
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
        for (int py = ty; py < ty + kTile; py += 4)
            for (int px = tx; px < tx + kTile; px += 4) {
                alignas(64) RTCRayHit16 rh;
                alignas(64) int valid[16];
                for (int k = 0; k < 16; ++k) {
                    const int x = px + (k & 3), y = py + (k >> 2);
                    valid[k] = x < w && y < h ? -1 : 0;
                    const double sx = ((x + 0.5) / w * 2.0 - 1.0) * halfW, sy = (1.0 - (y + 0.5) / h * 2.0) * halfH;
                    const V3 d = unit(right * sx + upv * sy - back);
                    rh.ray.org_x[k] = float(pos.x), rh.ray.org_y[k] = float(pos.y), rh.ray.org_z[k] = float(pos.z);
                    rh.ray.dir_x[k] = float(d.x), rh.ray.dir_y[k] = float(d.y), rh.ray.dir_z[k] = float(d.z);
                    rh.ray.tnear[k] = 0.0f;
                    rh.ray.tfar[k] = INFINITY;
                    rh.ray.mask[k] = ~0u;
                    rh.ray.time[k] = 0.0f;
                    rh.ray.flags[k] = 0;
                    rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
                    rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
                }
                rtcIntersect16(valid, scene, &ctx, &rh);
                for (int k = 0; k < 16; ++k) {
                    if (!valid[k] || rh.hit.geomID[k] == RTC_INVALID_GEOMETRY_ID) continue;
                    const int x = px + (k & 3), y = py + (k >> 2);
                    const std::uint32_t* t = &ib[3 * std::size_t(rh.hit.primID[k])];
                    const float u = rh.hit.u[k], v = rh.hit.v[k];
                    V3 n;
                    for (int c = 0; c < 3; ++c) {
                        const double wgt = c == 0 ? 1.0 - u - v : c == 1 ? u : v;
                        const float* nn = &mesh.normals[3 * std::size_t(t[c])];
                        n = n + V3{nn[0], nn[1], nn[2]} * wgt;
                    }
                    const double len = std::sqrt(dot(n, n));
                    const double diffuse = len > 0 ? std::abs(dot(n * (1.0 / len), light)) : 0.0;
                    const double shade = 0.15 + 0.85 * diffuse;
                    std::uint8_t* p = &rgb[3 * (std::size_t(y) * w + x)];
                    p[0] = std::uint8_t(std::lround(std::min(1.0, colour.x * shade) * 255));
                    p[1] = std::uint8_t(std::lround(std::min(1.0, colour.y * shade) * 255));
                    p[2] = std::uint8_t(std::lround(std::min(1.0, colour.z * shade) * 255));
                    hit[std::size_t(y) * w + x] = 1;
                }
            }
    };
    const auto frame = [&] {
        std::fill(rgb.begin(), rgb.end(), 255);
        std::fill(hit.begin(), hit.end(), 0);
        std::atomic<int> next{0};
        const auto worker = [&] {
            for (int t; (t = next.fetch_add(1)) < tilesX * tilesY;) renderTile(t);
        };
        const auto t1 = std::chrono::steady_clock::now();
        std::vector<std::thread> pool;
        for (int i = 1; i < threads; ++i) pool.emplace_back(worker);
        worker();
        for (auto& t : pool) t.join();
        return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t1).count();
    };
    const double firstMs = frame();
    std::vector<double> times;
    for (int i = 0; i < frames; ++i) times.push_back(frame());
    const double best = *std::min_element(times.begin(), times.end());
    std::size_t hits = 0;
    for (std::uint8_t b : hit) hits += b;
    writePng(outPng, w, h, rgb);

    int major = RTC_VERSION_MAJOR, minor = RTC_VERSION_MINOR, patch = RTC_VERSION_PATCH;
    std::ostringstream js;
    js << "{\n  \"peer\": \"embree\",\n  \"embree_version\": \"" << major << "." << minor << "." << patch << "\",\n"
       << "  \"api\": \"rtcIntersect16, 4x4-pixel packets, RTC_INTERSECT_CONTEXT_FLAG_COHERENT, 8x8-pixel tiles\",\n"
       << "  \"build_quality\": \"RTC_BUILD_QUALITY_HIGH\",\n  \"threads\": " << threads << ",\n  \"triangles\": " << nt
       << ",\n  \"points\": " << np << ",\n  \"bvh_build_ms\": " << buildMs << ",\n  \"first_frame_ms\": " << firstMs
       << ",\n  \"frame_ms\": [";
    for (std::size_t i = 0; i < times.size(); ++i) js << (i ? ", " : "") << times[i];
    js << "],\n  \"render_ms\": " << best << ",\n  \"hit_pixels\": " << hits << ",\n  \"width\": " << w << ",\n  \"height\": " << h
       << "\n}\n";
    std::ofstream(outJson) << js.str();
    rtcReleaseScene(scene);
    rtcReleaseDevice(device);
    return 0;
} catch (const std::exception& e) {
    std::fprintf(stderr, "embree_peer: %s\n", e.what());
    return 1;
}
