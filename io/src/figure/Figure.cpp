#include "octrace/io/Figure.h"

#include "octrace/render/ImageCompare.h"
#include "octrace/render/Shading.h"
#include "octrace/util/Error.h"

#include <ft2build.h>
#include FT_FREETYPE_H

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

namespace octrace::io {
namespace {

constexpr double kLabelPoints = 9.0, kTitlePoints = 11.0;
const vec3 kInk{0.0f, 0.0f, 0.0f};           // text (linear)
const vec3 kLineInk{0.05f, 0.05f, 0.05f};    // box edges and ticks (linear, near black)
const vec3 kCoastInk{0.0f, 0.0f, 0.0f};     // coastlines (black, thinner than the box)

/// UTF-8 to code points; a broken sequence becomes U+FFFD.
std::vector<char32_t> codePoints(const std::string& s) {
    std::vector<char32_t> out;
    for (std::size_t i = 0; i < s.size();) {
        const unsigned char c = static_cast<unsigned char>(s[i]);
        const int n = c < 0x80 ? 1 : (c >> 5) == 6 ? 2 : (c >> 4) == 14 ? 3 : (c >> 3) == 30 ? 4 : 0;
        if (n == 0 || i + std::size_t(n) > s.size()) {
            out.push_back(0xFFFD);
            ++i;
            continue;
        }
        char32_t cp = n == 1 ? c : c & (0x7F >> n);
        bool ok = true;
        for (int k = 1; k < n; ++k) {
            const unsigned char d = static_cast<unsigned char>(s[i + std::size_t(k)]);
            ok = ok && (d >> 6) == 2;
            cp = (cp << 6) | (d & 0x3F);
        }
        out.push_back(ok ? cp : char32_t(0xFFFD));
        i += ok ? std::size_t(n) : 1;
    }
    return out;
}

/// The figure being drawn: the frame, which pixels carry overlay, and linear blending.
struct Canvas {
    Frame& f;
    std::vector<std::uint8_t>* overlay;
    void blend(int x, int y, float a, vec3 ink) {
        if (x < 0 || y < 0 || x >= f.width || y >= f.height || a <= 0.0f) return;
        const std::size_t p = f.pixel(x, y);
        a = std::min(a, 1.0f);
        f.rgba[p] = vec4(vec3(f.rgba[p]) * (1.0f - a) + ink * a, 1.0f);
        if (overlay) (*overlay)[p] = 1;
    }
    void fill(int x0, int y0, int w, int h, vec3 c) {
        for (int y = y0; y < y0 + h; ++y)
            for (int x = x0; x < x0 + w; ++x) blend(x, y, 1.0f, c);
    }
    /// A line `width` pixels wide (square pen), no anti-aliasing: crisp in print.
    void line(dvec2 a, dvec2 b, double width, vec3 ink) {
        const double len = glm::length(b - a);
        const int steps = std::max(1, int(std::ceil(len * 2.0)));
        const int r0 = int(std::floor(-width / 2.0 + 0.5)), r1 = r0 + std::max(1, int(std::lround(width))) - 1;
        int lastX = INT32_MIN, lastY = INT32_MIN;
        for (int s = 0; s <= steps; ++s) {
            const dvec2 p = a + (b - a) * (double(s) / double(steps));
            const int cx = int(std::floor(p.x)), cy = int(std::floor(p.y));
            if (cx == lastX && cy == lastY) continue;
            lastX = cx, lastY = cy;
            for (int dy = r0; dy <= r1; ++dy)
                for (int dx = r0; dx <= r1; ++dx) blend(cx + dx, cy + dy, 1.0f, ink);
        }
    }
};

/// DejaVu Sans through FreeType; one per figure (FreeType objects are not shared).
class Font {
public:
    explicit Font(const std::string& path) {
        if (path.empty()) throw OutputError("figure: no DejaVu Sans font found (install Debian package fonts-dejavu-core)");
        if (FT_Init_FreeType(&lib_)) throw OutputError("figure: FreeType failed to start");
        if (FT_New_Face(lib_, path.c_str(), 0, &face_)) {
            FT_Done_FreeType(lib_);
            throw OutputError("figure: cannot read the font " + path);
        }
    }
    ~Font() {
        FT_Done_Face(face_);
        FT_Done_FreeType(lib_);
    }
    Font(const Font&) = delete;
    Font& operator=(const Font&) = delete;

    void size(double pixels) { FT_Set_Pixel_Sizes(face_, 0, FT_UInt(std::max(1L, std::lround(pixels)))); }
    double width(const std::string& text) {
        double w = 0.0;
        for (char32_t cp : codePoints(text))
            if (!FT_Load_Char(face_, cp, FT_LOAD_DEFAULT)) w += double(face_->glyph->advance.x) / 64.0;
        return w;
    }
    /// Height of capitals above the baseline, pixels.
    double capHeight() {
        if (FT_Load_Char(face_, 'H', FT_LOAD_DEFAULT)) return 0.0;
        return double(face_->glyph->metrics.height) / 64.0;
    }
    /// Draws `text` with its baseline's left end at (x, baseline).
    void draw(Canvas& c, const std::string& text, double x, double baseline, vec3 ink) {
        double pen = x;
        for (char32_t cp : codePoints(text)) {
            if (FT_Load_Char(face_, cp, FT_LOAD_RENDER)) continue;
            const FT_GlyphSlot g = face_->glyph;
            const FT_Bitmap& bm = g->bitmap;
            const int left = int(std::lround(pen)) + g->bitmap_left, top = int(std::lround(baseline)) - g->bitmap_top;
            for (unsigned r = 0; r < bm.rows; ++r)
                for (unsigned col = 0; col < bm.width; ++col) {
                    const unsigned char v = bm.buffer[std::ptrdiff_t(r) * bm.pitch + col];
                    if (v) c.blend(left + int(col), top + int(r), float(v) / 255.0f, ink);
                }
            pen += double(g->advance.x) / 64.0;
        }
    }
    /// Draws `text` centred on (cx, cy) (the capitals' middle).
    void drawCentred(Canvas& c, const std::string& text, double cx, double cy, vec3 ink) {
        draw(c, text, cx - width(text) / 2.0, cy + capHeight() / 2.0, ink);
    }

private:
    FT_Library lib_ = nullptr;
    FT_Face face_ = nullptr;
};

std::string tickText(double v, double step) {
    std::ostringstream s;
    const int decimals = step >= 1.0 ? 0 : int(std::ceil(-std::log10(step) - 1e-9));
    s.setf(std::ios::fixed);
    s.precision(decimals);
    s << (std::abs(v) < step * 1e-9 ? 0.0 : v);
    return s.str();
}

}  // namespace

std::string figureFontPath() {
    for (const char* p : {"/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf", "/usr/share/fonts/TTF/DejaVuSans.ttf",
                          "/usr/share/fonts/dejavu/DejaVuSans.ttf", "/usr/local/share/fonts/DejaVuSans.ttf"})
        if (std::filesystem::exists(p)) return p;
    return {};
}

std::vector<double> niceTicks(double lo, double hi, int count) {
    std::vector<double> t;
    if (!(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi) || count < 1) return t;
    const double raw = (hi - lo) / double(count);
    const double p = std::pow(10.0, std::floor(std::log10(raw)));
    double step = p;
    for (double m : {1.0, 2.0, 5.0, 10.0})
        if (m * p >= raw) {
            step = m * p;
            break;
        }
    for (double v = std::ceil(lo / step - 1e-9) * step; v <= hi + step * 1e-9; v += step) t.push_back(v);
    return t;
}

double scaleBarLength(double worldPerPixel, int plotWidth) {
    const double most = worldPerPixel * plotWidth / 5.0;
    if (!(most > 0.0) || !std::isfinite(most)) return 0.0;
    const double p = std::pow(10.0, std::floor(std::log10(most)));
    for (double m : {5.0, 2.0, 1.0})
        if (m * p <= most * (1.0 + 1e-12)) return m * p;
    return p;
}

FigureLayout layoutFigure(int width, int height, int dpi, bool colourBar) {
    FigureLayout l;
    l.width = width;
    l.height = height;
    l.dpi = dpi;
    l.labelPx = kLabelPoints * dpi / 72.0;
    l.titlePx = kTitlePoints * dpi / 72.0;
    const int m = int(std::lround(0.8 * l.labelPx));
    l.plotX = m;
    l.plotY = m + int(std::lround(1.5 * l.titlePx + 1.5 * l.labelPx));
    // The panel leaves room left of the bar for tick labels on the box's right edges.
    const int panel = colourBar ? int(std::lround(12.0 * l.labelPx)) : 0;
    l.plotW = width - l.plotX - m - panel;
    l.plotH = height - l.plotY - m;
    if (l.plotW < 16 || l.plotH < 16) {
        std::ostringstream s;
        s << "figure: " << width << "x" << height << " pixels at " << dpi
          << " dpi leave no room for the plot beside the text (make it larger or lower the dpi)";
        throw UsageError(s.str());
    }
    if (colourBar) {
        l.barW = int(std::lround(1.2 * l.labelPx));
        l.barX = l.plotX + l.plotW + int(std::lround(4.2 * l.labelPx));
        l.barY = l.plotY + int(std::lround(2.0 * l.labelPx));
        l.barH = std::max(8, l.plotH - int(std::lround(3.0 * l.labelPx)));
    }
    return l;
}

Frame composeFigure(const Frame& plot, const FigureSpec& spec, const FigureLayout& l, std::vector<std::uint8_t>* overlay) {
    if (plot.width != l.plotW || plot.height != l.plotH)
        throw UsageError("figure: the plot is " + std::to_string(plot.width) + "x" + std::to_string(plot.height) +
                         ", the layout's plot area " + std::to_string(l.plotW) + "x" + std::to_string(l.plotH));
    Frame f(l.width, l.height);
    std::fill(f.rgba.begin(), f.rgba.end(), vec4(1.0f));
    if (overlay) overlay->assign(f.rgba.size(), 0);
    for (int y = 0; y < plot.height; ++y)
        for (int x = 0; x < plot.width; ++x) {
            const vec4 c = plot.rgba[plot.pixel(x, y)];
            // Paper behind a transparent background: the figure is opaque.
            f.rgba[f.pixel(l.plotX + x, l.plotY + y)] = vec4(vec3(c) * c.a + vec3(1.0f) * (1.0f - c.a), 1.0f);
        }
    Canvas canvas{f, overlay};
    Font font(figureFontPath());
    const double lineWidth = std::max(1.0, l.dpi / 110.0);

    // Box edges and labelled ticks, in plot pixels.
    const dvec2 origin(l.plotX, l.plotY);
    const double coastWidth = std::max(1.0, l.dpi / 160.0);
    for (const auto& line : spec.coastlines)
        for (std::size_t i = 1; i < line.size(); ++i) canvas.line(origin + line[i - 1], origin + line[i], coastWidth, kCoastInk);
    for (const auto& [a, b] : spec.lines) canvas.line(origin + a, origin + b, lineWidth, kLineInk);
    font.size(l.labelPx);
    for (const FigureLabel& lab : spec.labels) {
        const dvec2 p = origin + lab.at;
        canvas.fill(int(std::floor(p.x - lineWidth)), int(std::floor(p.y - lineWidth)), int(std::lround(2 * lineWidth)) + 1,
                    int(std::lround(2 * lineWidth)) + 1, kLineInk);
        font.drawCentred(canvas, lab.text, p.x + lab.dx * l.labelPx, p.y + lab.dy * l.labelPx, kInk);
    }

    // Scale bar: a bar with end ticks in the plot's lower left corner, its length above it.
    if (spec.scaleBarPx > 0.0) {
        const double x0 = l.plotX + 1.2 * l.labelPx, y = l.plotY + l.plotH - 1.2 * l.labelPx;
        const double x1 = x0 + spec.scaleBarPx, tick = 0.4 * l.labelPx, w = 2.0 * lineWidth;
        canvas.line({x0, y}, {x1, y}, w, kLineInk);
        canvas.line({x0, y - tick}, {x0, y + tick}, w, kLineInk);
        canvas.line({x1, y - tick}, {x1, y + tick}, w, kLineInk);
        font.drawCentred(canvas, spec.scaleBarLabel, 0.5 * (x0 + x1), y - tick - 0.8 * l.labelPx, kInk);
    }

    // Title and subtitle.
    const double m = 0.8 * l.labelPx;
    font.size(l.titlePx);
    if (!spec.title.empty()) font.draw(canvas, spec.title, l.plotX, m + font.capHeight(), kInk);
    font.size(l.labelPx);
    if (!spec.subtitle.empty()) font.draw(canvas, spec.subtitle, l.plotX, m + 1.5 * l.titlePx + font.capHeight() * 0.5, kInk);

    // Colour bar: each row the map's colour for its value, high at the top, a frame around.
    if ((!spec.colormap.empty() || spec.greyRamp) && l.barW > 0) {
        for (int r = 0; r < l.barH; ++r) {
            const float t = 1.0f - (float(r) + 0.5f) / float(l.barH);
            const float grey = srgb8ToLinear(std::uint8_t(std::lround((spec.invertedGrey ? 1.0f - t : t) * 255.0f)));
            const vec3 c = spec.greyRamp ? vec3(grey) : colormap(spec.colormap, t);
            for (int x = 0; x < l.barW; ++x) f.rgba[f.pixel(l.barX + x, l.barY + r)] = vec4(c, 1.0f);
        }
        const double x0 = l.barX - 0.5, x1 = l.barX + l.barW - 0.5 + 1.0, y0 = l.barY - 0.5, y1 = l.barY + l.barH - 0.5 + 1.0;
        const double e = 1.0;  // the frame lies outside the bar's pixels
        canvas.line({x0 - e, y0 - e}, {x1, y0 - e}, 1.0, kLineInk);
        canvas.line({x0 - e, y1}, {x1, y1}, 1.0, kLineInk);
        canvas.line({x0 - e, y0 - e}, {x0 - e, y1}, 1.0, kLineInk);
        canvas.line({x1, y0 - e}, {x1, y1}, 1.0, kLineInk);
        font.draw(canvas, spec.barLabel, l.barX, l.barY - 0.8 * l.labelPx, kInk);
        const std::vector<double> ticks = niceTicks(spec.low, spec.high, 5);
        const double step = ticks.size() > 1 ? ticks[1] - ticks[0] : std::max(1e-12, spec.high - spec.low);
        for (double v : ticks) {
            const double y = l.barY + (1.0 - (v - spec.low) / (spec.high - spec.low)) * l.barH;
            const double xs = l.barX + l.barW + 1.0;
            canvas.line({xs, y}, {xs + 0.4 * l.labelPx, y}, lineWidth, kLineInk);
            font.draw(canvas, tickText(v, step), xs + 0.6 * l.labelPx, y + font.capHeight() / 2.0, kInk);
        }
    }
    return f;
}

}  // namespace octrace::io
