#include "octrace/io/Figure.h"

#include "octrace/render/ImageCompare.h"
#include "octrace/render/Shading.h"
#include "octrace/util/Error.h"

#include <ft2build.h>
#include FT_FREETYPE_H

#include <algorithm>
#include <cmath>
#include <climits>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
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

/// Pixels [x0, x1) x [y0, y1); empty until a pixel is added.
struct InkBox {
    int x0 = INT32_MAX, y0 = INT32_MAX, x1 = INT32_MIN, y1 = INT32_MIN;
    bool empty() const { return x0 >= x1 || y0 >= y1; }
    void add(int x, int y) {
        x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x + 1), y1 = std::max(y1, y + 1);
    }
    /// Whether the boxes come closer than `gap` pixels.
    bool near(const InkBox& o, int gap) const {
        return !empty() && !o.empty() && x0 < o.x1 + gap && o.x0 < x1 + gap && y0 < o.y1 + gap && o.y0 < y1 + gap;
    }
    bool inside(int w, int h) const { return empty() || (x0 >= 0 && y0 >= 0 && x1 <= w && y1 <= h); }
    InkBox moved(int dx, int dy) const {
        return empty() ? *this : InkBox{x0 + dx, y0 + dy, x1 + dx, y1 + dy};
    }
};

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
    /// Draws `text` with its baseline's left end at (x, baseline) on `c` (measures only when
    /// null) and returns its inked pixels: every glyph pixel FreeType covers, in or out of the figure.
    InkBox draw(Canvas* c, const std::string& text, double x, double baseline, vec3 ink = vec3(0.0f)) {
        InkBox box;
        double pen = x;
        for (char32_t cp : codePoints(text)) {
            if (FT_Load_Char(face_, cp, FT_LOAD_RENDER)) continue;
            const FT_GlyphSlot g = face_->glyph;
            const FT_Bitmap& bm = g->bitmap;
            const int left = int(std::lround(pen)) + g->bitmap_left, top = int(std::lround(baseline)) - g->bitmap_top;
            for (unsigned r = 0; r < bm.rows; ++r)
                for (unsigned col = 0; col < bm.width; ++col) {
                    const unsigned char v = bm.buffer[std::ptrdiff_t(r) * bm.pitch + col];
                    if (!v) continue;
                    box.add(left + int(col), top + int(r));
                    if (c) c->blend(left + int(col), top + int(r), float(v) / 255.0f, ink);
                }
            pen += double(g->advance.x) / 64.0;
        }
        return box;
    }
    /// The baseline's left end that centres `text` on (cx, cy) (the capitals' middle).
    dvec2 centred(const std::string& text, double cx, double cy) { return {cx - width(text) / 2.0, cy + capHeight() / 2.0}; }
    void drawCentred(Canvas& c, const std::string& text, double cx, double cy, vec3 ink) {
        const dvec2 p = centred(text, cx, cy);
        draw(&c, text, p.x, p.y, ink);
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

/// Code points back to UTF-8.
std::string utf8(const std::vector<char32_t>& cps) {
    std::string out;
    for (char32_t c : cps) {
        if (c < 0x80) {
            out += char(c);
        } else if (c < 0x800) {
            out += char(0xC0 | (c >> 6)), out += char(0x80 | (c & 0x3F));
        } else if (c < 0x10000) {
            out += char(0xE0 | (c >> 12)), out += char(0x80 | ((c >> 6) & 0x3F)), out += char(0x80 | (c & 0x3F));
        } else {
            out += char(0xF0 | (c >> 18)), out += char(0x80 | ((c >> 12) & 0x3F)), out += char(0x80 | ((c >> 6) & 0x3F));
            out += char(0x80 | (c & 0x3F));
        }
    }
    return out;
}

/// A text and where its baseline's left end would go.
struct Candidate {
    std::string text;
    double x = 0.0, baseline = 0.0;
};

/// Places the figure's texts one after another from their ink boxes (measured with FreeType
/// before anything is drawn), each where it keeps a small gap to everything placed before and
/// stays inside the figure, and keeps what it placed.
class TextLayout {
public:
    TextLayout(Font& font, Canvas& canvas, const FigureLayout& l)
        : font_(font), canvas_(canvas), l_(l), gap_(std::max(1, int(std::lround(0.15 * l.labelPx)))) {}

    const std::vector<FigureTextBox>& placed() const { return placed_; }

    /// A drawn shape that text keeps clear of.
    void graphic(const std::string& role, const InkBox& b) {
        taken_.push_back(b);
        placed_.push_back({role, "", b.x0, b.y0, b.x1, b.y1, true});
    }

    /// `text` at (x, baseline), at most `room` pixels wide: whole, else without its last "; " or
    /// ", " parts, else cut, and then ended with an ellipsis.
    void placeFitted(const std::string& role, const std::string& text, double x, double baseline, double room) {
        draw(role, fitted(text, x, baseline, x + room), x, baseline);
    }

    /// The colour bar's label above the bar (layout `l_`), right of the plot and inside the
    /// right margin `m`: on one line at the bar, else moved left, else in two lines split
    /// before its units, else abbreviated.
    void placeBarLabel(const std::string& label, double m) {
        if (label.empty()) return;
        const double right = l_.width - m, left = l_.plotX + l_.plotW + 0.5 * l_.labelPx;
        const double baseline = l_.barY - 0.8 * l_.labelPx, lineStep = 1.25 * l_.labelPx;
        auto at = [&](const std::string& t) { return std::max(left, std::min(double(l_.barX), right - font_.width(t))); };
        auto fits = [&](const std::vector<Candidate>& lines) {
            for (const Candidate& c : lines) {
                const InkBox b = font_.draw(nullptr, c.text, c.x, c.baseline);
                if (!free(b) || b.x0 < left || b.x1 > right) return false;
            }
            return true;
        };
        std::vector<std::vector<Candidate>> tries{{{label, at(label), baseline}}};
        std::size_t cut = label.rfind(" (");
        if (cut == std::string::npos) cut = label.rfind(' ');
        if (cut != std::string::npos && cut > 0) {
            const std::string a = label.substr(0, cut), b = label.substr(cut + 1);
            tries.push_back({{a, at(a), baseline - lineStep}, {b, at(b), baseline}});
        }
        for (const auto& lines : tries)
            if (fits(lines)) {
                for (const Candidate& c : lines) draw("bar label", c.text, c.x, c.baseline);
                return;
            }
        draw("bar label", fitted(label, left, baseline, right), left, baseline);
    }

    /// Labels of one kind (an axis's ticks): all of them if none collides, else every k-th
    /// (the smallest k, at least 3 labels kept when there are 3), else each that fits, in order.
    /// With `clamp`, a label that would leave the figure is moved inside it first.
    void placeThinned(const std::string& role, const std::vector<Candidate>& labels, bool clamp) {
        const std::size_t n = labels.size();
        if (n == 0) return;
        std::vector<Candidate> at = labels;
        std::vector<InkBox> box(n);
        for (std::size_t i = 0; i < n; ++i) {
            box[i] = font_.draw(nullptr, at[i].text, at[i].x, at[i].baseline);
            if (clamp) {
                const int dx = box[i].x0 < 0 ? -box[i].x0 : box[i].x1 > l_.width ? l_.width - box[i].x1 : 0;
                const int dy = box[i].y0 < 0 ? -box[i].y0 : box[i].y1 > l_.height ? l_.height - box[i].y1 : 0;
                box[i] = box[i].moved(dx, dy);
                at[i].x += dx, at[i].baseline += dy;
            }
        }
        const std::size_t least = std::min<std::size_t>(3, n);
        for (std::size_t k = 1; k <= n; ++k)
            for (std::size_t first = 0; first < k; ++first) {
                std::vector<std::size_t> keep;
                for (std::size_t i = first; i < n; i += k) keep.push_back(i);
                if (keep.size() < least) continue;
                bool ok = true;
                for (std::size_t a = 0; a < keep.size() && ok; ++a) {
                    ok = free(box[keep[a]]);
                    for (std::size_t b = 0; b < a && ok; ++b) ok = !box[keep[a]].near(box[keep[b]], gap_);
                }
                if (!ok) continue;
                for (std::size_t i : keep) draw(role, at[i].text, at[i].x, at[i].baseline);
                return;
            }
        for (std::size_t i = 0; i < n; ++i)
            if (free(box[i])) draw(role, at[i].text, at[i].x, at[i].baseline);
    }

private:
    bool free(const InkBox& b) const {
        if (!b.inside(l_.width, l_.height)) return false;
        for (const InkBox& t : taken_)
            if (b.near(t, gap_)) return false;
        return true;
    }
    void draw(const std::string& role, const std::string& text, double x, double baseline) {
        if (text.empty()) return;
        const InkBox b = font_.draw(&canvas_, text, x, baseline, kInk);
        taken_.push_back(b);
        placed_.push_back({role, text, b.x0, b.y0, b.x1, b.y1, false});
    }
    /// `text`, or the most of it (whole "; " or ", " parts, else code points; then an ellipsis) whose ink
    /// from (x, baseline) ends before `right`.
    std::string fitted(const std::string& text, double x, double baseline, double right) {
        auto fits = [&](const std::string& t) { return font_.draw(nullptr, t, x, baseline).x1 <= right; };
        if (fits(text)) return text;
        // Whole parts first (cut at the last "; " or ", "), then code points; an ellipsis says so.
        std::string t = text;
        for (;;) {
            const std::size_t a = t.rfind("; "), b = t.rfind(", ");
            const std::size_t cut = a == std::string::npos ? b : b == std::string::npos ? a : std::max(a, b);
            if (cut == std::string::npos || cut == 0) break;
            t = t.substr(0, cut);
            if (fits(t + "\u2026")) return t + "\u2026";
        }
        std::vector<char32_t> cps = codePoints(t);
        while (!cps.empty()) {
            cps.pop_back();
            while (!cps.empty() && (cps.back() == U' ' || cps.back() == U',' || cps.back() == U';')) cps.pop_back();
            const std::string e = utf8(cps) + "\u2026";
            if (fits(e)) return e;
        }
        return {};
    }

    Font& font_;
    Canvas& canvas_;
    const FigureLayout& l_;
    int gap_;
    std::vector<InkBox> taken_;
    std::vector<FigureTextBox> placed_;
};

/// JSON string contents.
std::string jsonEscaped(const std::string& s) {
    std::string out;
    for (char c : s) {
        if (c == '"' || c == '\\') out += '\\', out += c;
        else if (static_cast<unsigned char>(c) < 0x20) out += ' ';
        else out += c;
    }
    return out;
}

/// One JSON line: the figure's size and its boxes (OCTRACE_TEST_FIGURE_TEXT).
void appendTextBoxes(const std::string& path, const FigureLayout& l, const std::vector<FigureTextBox>& boxes) {
    std::ostringstream s;
    s << "{\"width\": " << l.width << ", \"height\": " << l.height << ", \"boxes\": [";
    for (std::size_t i = 0; i < boxes.size(); ++i) {
        const FigureTextBox& b = boxes[i];
        s << (i ? ", " : "") << "{\"role\": \"" << jsonEscaped(b.role) << "\", \"text\": \"" << jsonEscaped(b.text)
          << "\", \"graphic\": " << (b.graphic ? "true" : "false") << ", \"box\": [" << b.x0 << ", " << b.y0 << ", " << b.x1
          << ", " << b.y1 << "]}";
    }
    s << "]}\n";
    static std::mutex mutex;  // an animation composes its frames in parallel
    std::lock_guard<std::mutex> lock(mutex);
    std::ofstream out(path, std::ios::app);
    out << s.str();
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

Frame composeFigure(const Frame& plot, const FigureSpec& spec, const FigureLayout& l, std::vector<std::uint8_t>* overlay,
                    std::vector<FigureTextBox>* textOut) {
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
    TextLayout text(font, canvas, l);

    // Box edges, coastlines and tick marks, in plot pixels.
    const dvec2 origin(l.plotX, l.plotY);
    const double coastWidth = std::max(1.0, l.dpi / 160.0);
    for (const auto& line : spec.coastlines)
        for (std::size_t i = 1; i < line.size(); ++i) canvas.line(origin + line[i - 1], origin + line[i], coastWidth, kCoastInk);
    for (const auto& [a, b] : spec.lines) canvas.line(origin + a, origin + b, lineWidth, kLineInk);
    for (const FigureLabel& lab : spec.labels) {
        const dvec2 p = origin + lab.at;
        canvas.fill(int(std::floor(p.x - lineWidth)), int(std::floor(p.y - lineWidth)), int(std::lround(2 * lineWidth)) + 1,
                    int(std::lround(2 * lineWidth)) + 1, kLineInk);
    }

    // The text in order of precedence, each placed where it overlaps nothing placed before:
    // title and subtitle, the colour bar with its label and ticks, the scale bar, the axes.
    const double m = 0.8 * l.labelPx;
    font.size(l.titlePx);
    if (!spec.title.empty()) text.placeFitted("title", spec.title, l.plotX, m + font.capHeight(), l.width - m - l.plotX);
    font.size(l.labelPx);
    if (!spec.subtitle.empty())
        text.placeFitted("subtitle", spec.subtitle, l.plotX, m + 1.5 * l.titlePx + font.capHeight() * 0.5, l.width - m - l.plotX);

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
        text.graphic("colour bar", InkBox{l.barX - 2, l.barY - 2, l.barX + l.barW + 2, l.barY + l.barH + 2});
        text.placeBarLabel(spec.barLabel, m);
        // Ticks: round values of what the bar reads (heights, or depths positive down).
        const double lo = spec.barPositiveDown ? -spec.high : spec.low, hi = spec.barPositiveDown ? -spec.low : spec.high;
        // About 5 round values; more when those leave fewer than 3 on a short range.
        std::vector<double> ticks;
        for (int count = 5; count <= 20 && ticks.size() < 3; count *= 2) ticks = niceTicks(lo, hi, count);
        const double step = ticks.size() > 1 ? ticks[1] - ticks[0] : std::max(1e-12, hi - lo);
        std::vector<Candidate> labels;
        for (double v : ticks) {
            const double u = (v - lo) / (hi - lo);  // 0 at the reading's low end
            const double y = l.barY + (spec.barPositiveDown ? u : 1.0 - u) * l.barH;
            const double xs = l.barX + l.barW + 1.0;
            canvas.line({xs, y}, {xs + 0.4 * l.labelPx, y}, lineWidth, kLineInk);
            labels.push_back({tickText(v, step), xs + 0.6 * l.labelPx, y + font.capHeight() / 2.0});
        }
        text.placeThinned("bar tick", labels, false);
    }

    // Scale bar: a bar with end ticks in the plot's lower left corner, its length above it.
    if (spec.scaleBarPx > 0.0) {
        const double x0 = l.plotX + 1.2 * l.labelPx, y = l.plotY + l.plotH - 1.2 * l.labelPx;
        const double x1 = x0 + spec.scaleBarPx, tick = 0.4 * l.labelPx, w = 2.0 * lineWidth;
        canvas.line({x0, y}, {x1, y}, w, kLineInk);
        canvas.line({x0, y - tick}, {x0, y + tick}, w, kLineInk);
        canvas.line({x1, y - tick}, {x1, y + tick}, w, kLineInk);
        const dvec2 p = font.centred(spec.scaleBarLabel, 0.5 * (x0 + x1), y - tick - 0.8 * l.labelPx);
        text.placeThinned("scale bar", {{spec.scaleBarLabel, p.x, p.y}}, true);
    }

    // Tick labels on the bounding box, axis by axis.
    std::vector<int> axes;
    for (const FigureLabel& lab : spec.labels)
        if (std::find(axes.begin(), axes.end(), lab.axis) == axes.end()) axes.push_back(lab.axis);
    for (int axis : axes) {
        std::vector<Candidate> labels;
        for (const FigureLabel& lab : spec.labels)
            if (lab.axis == axis) {
                const dvec2 p = font.centred(lab.text, origin.x + lab.at.x + lab.dx * l.labelPx, origin.y + lab.at.y + lab.dy * l.labelPx);
                labels.push_back({lab.text, p.x, p.y});
            }
        text.placeThinned("axis " + std::to_string(axis), labels, true);
    }

    if (textOut) *textOut = text.placed();
    if (const char* path = std::getenv("OCTRACE_TEST_FIGURE_TEXT"); path && *path) appendTextBoxes(path, l, text.placed());
    return f;
}

}  // namespace octrace::io
