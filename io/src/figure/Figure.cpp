#include "octrace/io/Figure.h"

#include "octrace/render/ImageCompare.h"
#include "octrace/render/Shading.h"
#include "octrace/util/Error.h"

#include <ft2build.h>
#include FT_FREETYPE_H

#include <algorithm>
#include <bit>
#include <cmath>
#include <climits>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <sstream>
#include <utility>

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

/// A text and where it goes: its baseline's left end (x, baseline) at font size `px`; with
/// `centred`, the text is centred on (cx, cy) instead, at whatever size it is set.
struct Candidate {
    std::string text;
    double x = 0.0, baseline = 0.0;
    bool centred = false;
    double cx = 0.0, cy = 0.0;
};

/// Line heights (pixels) of the title and of 9 pt text.
double titleLine(const FigureLayout& l) { return std::round(1.3 * l.titlePx); }
double labelLine(const FigureLayout& l) { return std::round(1.3 * l.labelPx); }
/// The outer margin and the gap between neighbours.
int outerMargin(double labelPx) { return int(std::lround(0.8 * labelPx)); }
int gapOf(double labelPx) { return std::max(1, int(std::lround(0.3 * labelPx))); }

/// `text` split into lines no wider than `room` pixels at the font's current size: at whole
/// "; " or ", " parts first, then at spaces; a word wider than the room stays whole.
std::vector<std::string> wrapped(Font& font, const std::string& text, double room) {
    std::vector<std::string> lines;
    if (text.empty()) return lines;
    // Pieces: parts ending in their separator; a part wider than the room split at its spaces.
    std::vector<std::string> pieces;
    std::size_t start = 0;
    for (;;) {
        const std::size_t a = text.find("; ", start), b = text.find(", ", start);
        const std::size_t cut = std::min(a, b);
        const std::string part = cut == std::string::npos ? text.substr(start) : text.substr(start, cut + 2 - start);
        if (font.width(part) <= room) {
            pieces.push_back(part);
        } else {
            std::size_t w = 0;
            for (;;) {
                const std::size_t sp = part.find(' ', w);
                pieces.push_back(sp == std::string::npos ? part.substr(w) : part.substr(w, sp + 1 - w));
                if (sp == std::string::npos) break;
                w = sp + 1;
            }
        }
        if (cut == std::string::npos) break;
        start = cut + 2;
    }
    auto trimmed = [](std::string t) {
        while (!t.empty() && t.back() == ' ') t.pop_back();
        return t;
    };
    std::string line;
    for (const std::string& piece : pieces) {
        if (!line.empty() && font.width(trimmed(line + piece)) > room) {
            lines.push_back(trimmed(line));
            line.clear();
        }
        line += piece;
    }
    if (!trimmed(line).empty()) lines.push_back(trimmed(line));
    return lines;
}

/// The colour bar's label as lines: one when it is no wider than `room`, else split before its
/// units (" (") or at its last space.
std::vector<std::string> barLabelLines(Font& font, const std::string& label, double room) {
    if (label.empty()) return {};
    if (font.width(label) <= room) return {label};
    std::size_t cut = label.rfind(" (");
    if (cut == std::string::npos) cut = label.rfind(' ');
    if (cut == std::string::npos || cut == 0) return {label};
    return {label.substr(0, cut), label.substr(cut + 1)};
}

/// The bar's tick values (round values of what it reads) and their step.
std::vector<double> barTicks(const FigureSpec& spec, double& step) {
    const double lo = spec.barPositiveDown ? -spec.high : spec.low, hi = spec.barPositiveDown ? -spec.low : spec.high;
    // About 5 round values; more when those leave fewer than 3 on a short range.
    std::vector<double> ticks;
    for (int count = 5; count <= 20 && ticks.size() < 3; count *= 2) ticks = niceTicks(lo, hi, count);
    step = ticks.size() > 1 ? ticks[1] - ticks[0] : std::max(1e-12, hi - lo);
    return ticks;
}

bool hasBar(const FigureSpec& spec) { return !spec.colormap.empty() || spec.greyRamp; }

/// The ink box of a tick label of the box at its place (figure pixels), at label size.
InkBox labelBox(Font& font, const FigureLabel& lab, const FigureLayout& l) {
    const dvec2 p = font.centred(lab.text, l.plotX + lab.at.x + lab.dx * l.labelPx, l.plotY + lab.at.y + lab.dy * l.labelPx);
    return font.draw(nullptr, lab.text, p.x, p.y);
}

/// The labels of each axis on each of its places (FigureLabel::edge), in order of first
/// appearance, and how far apart their points lie.
struct AxisLabels {
    int axis = 0, edge = 0;
    std::vector<const FigureLabel*> labels;
    double span = 0.0;
    bool endOn(double labelPx) const;
    /// The widest ink of its labels along the line through its two farthest points, at the
    /// smallest size they are set in (pixels); `bare`: of their texts without the unit.
    double extent(Font& font, double labelPx, bool bare) const;
    /// Whether `count` of its labels can lie apart along its span at the smallest size.
    bool roomFor(std::size_t count, Font& font, double labelPx, bool bare) const;
    /// Whether its labels have a text without the unit.
    bool hasBare() const {
        return std::any_of(labels.begin(), labels.end(), [](const FigureLabel* l) { return !l->bare.empty(); });
    }
};
/// The text of `lab` with its unit, or without it (`bare`) where it has such a text.
const std::string& labelText(const FigureLabel& lab, bool bare) { return bare && !lab.bare.empty() ? lab.bare : lab.text; }
std::vector<AxisLabels> axesOf(const FigureSpec& spec) {
    std::vector<AxisLabels> out;
    for (const FigureLabel& lab : spec.labels) {
        auto it = std::find_if(out.begin(), out.end(), [&](const AxisLabels& a) { return a.axis == lab.axis && a.edge == lab.edge; });
        if (it == out.end()) it = out.insert(out.end(), AxisLabels{lab.axis, lab.edge, {}, 0.0});
        for (const FigureLabel* o : it->labels) it->span = std::max(it->span, glm::length(o->at - lab.at));
        it->labels.push_back(&lab);
    }
    return out;
}

/// An axis whose labels' points lie within this many label heights is an edge seen end on: its
/// labels would all say different things at one place, and none is drawn.
constexpr double kEndOnSpan = 0.5;
bool AxisLabels::endOn(double labelPx) const { return labels.size() >= 2 && span < kEndOnSpan * labelPx; }

/// Labels that collide are set at these sizes (of the label size), in turn.
constexpr double kLabelScales[] = {1.0, 0.85, 0.7};
/// The gap kept between texts (pixels).
int textGap(double labelPx) { return std::max(1, int(std::lround(0.15 * labelPx))); }

double AxisLabels::extent(Font& font, double labelPx, bool bare) const {
    dvec2 u(0.0);
    for (const FigureLabel* a : labels)
        for (const FigureLabel* b : labels)
            if (glm::length(b->at - a->at) >= span && span > 0.0) u = (b->at - a->at) / span;
    font.size(labelPx * kLabelScales[std::size(kLabelScales) - 1]);
    double widest = 0.0;
    for (const FigureLabel* lab : labels) {
        const InkBox b = font.draw(nullptr, labelText(*lab, bare), 0.0, 0.0);
        if (!b.empty()) widest = std::max(widest, (b.x1 - b.x0) * std::abs(u.x) + (b.y1 - b.y0) * std::abs(u.y));
    }
    return widest;
}

bool AxisLabels::roomFor(std::size_t count, Font& font, double labelPx, bool bare) const {
    return labels.size() >= count && span >= double(count - 1) * (extent(font, labelPx, bare) + textGap(labelPx));
}

/// The subsets of `size` of 0..n-1 (sorted), the most evenly spread first: by their smallest
/// step between neighbours, then by the span they cover; none when every k-th already gives
/// them (size < 3, or n <= size) or there are too many to try (n > 16).
std::vector<std::vector<std::size_t>> spreadSubsets(std::size_t n, std::size_t size) {
    std::vector<std::vector<std::size_t>> out;
    if (size < 3 || n <= size || n > 16) return out;
    for (std::uint32_t mask = 0; mask < (1u << n); ++mask) {
        if (std::size_t(std::popcount(mask)) != size) continue;
        std::vector<std::size_t> keep;
        for (std::size_t i = 0; i < n; ++i)
            if (mask & (1u << i)) keep.push_back(i);
        out.push_back(std::move(keep));
    }
    const auto smallestStep = [](const std::vector<std::size_t>& k) {
        std::size_t m = k.back() - k.front();
        for (std::size_t i = 1; i < k.size(); ++i) m = std::min(m, k[i] - k[i - 1]);
        return m;
    };
    std::stable_sort(out.begin(), out.end(), [&](const auto& a, const auto& b) {
        const std::size_t sa = smallestStep(a), sb = smallestStep(b);
        if (sa != sb) return sa > sb;
        return a.back() - a.front() > b.back() - b.front();
    });
    return out;
}

/// Places the figure's texts one after another from their ink boxes (measured with FreeType
/// before anything is drawn), each where it keeps a small gap to everything placed before and
/// stays inside the figure, and keeps what it placed.
class TextLayout {
public:
    TextLayout(Font& font, Canvas& canvas, const FigureLayout& l)
        : font_(font), canvas_(&canvas), l_(l), gap_(textGap(l.labelPx)) {}

    /// A copy that places as this one would from here on but draws nothing: to try an order.
    TextLayout trial() const {
        TextLayout t = *this;
        t.canvas_ = nullptr;
        return t;
    }
    /// How many texts of `role` were placed.
    std::size_t count(const std::string& role) const {
        return std::size_t(std::count_if(placed_.begin(), placed_.end(), [&](const FigureTextBox& b) { return b.role == role; }));
    }

    const std::vector<FigureTextBox>& placed() const { return placed_; }
    /// Whether `b` lies inside the figure, clear of everything placed.
    bool isFree(const InkBox& b) const { return free(b); }

    /// A drawn shape that text keeps clear of.
    void graphic(const std::string& role, const InkBox& b) {
        taken_.push_back(b);
        placed_.push_back({role, "", b.x0, b.y0, b.x1, b.y1, true});
    }

    /// `lines` of text from the baseline `baseline` down, `step` apart, at size `px`, each from `x`
    /// and at most `room` wide; when there are more than `most` lines, the last one kept ends in an
    /// ellipsis.
    void placeLines(const std::string& role, std::vector<std::string> lines, std::size_t most, double px, double x, double baseline,
                    double step, double room) {
        font_.size(px);
        if (lines.size() > most) {
            lines.resize(most);
            if (!lines.empty()) lines.back() = fitted(lines.back() + "\u2026", x, baseline, x + room, true);
        }
        for (std::size_t i = 0; i < lines.size(); ++i) {
            const double b = baseline + double(i) * step;
            draw(role, fitted(lines[i], x, b, x + room, false), x, b);
        }
    }

    /// Labels of one kind (an axis's ticks) at size `px`: all of them if none collides, else every
    /// k-th (the smallest k, at least `least` kept), else `least` of them as evenly spread as
    /// fit (every k-th cannot keep 3 of 4: only 4 or 2), else the same at 85% and 70% of the
    /// size, else each that fits, in order. With `clamp`, a label that would leave the figure is
    /// moved inside it first.
    void placeThinned(const std::string& role, const std::vector<Candidate>& labels, bool clamp, double px, std::size_t least) {
        const std::size_t n = labels.size();
        if (n == 0) return;
        least = std::min(least, n);
        std::vector<Candidate> at;
        std::vector<InkBox> box;
        const auto fits = [&](const std::vector<std::size_t>& keep) {
            for (std::size_t a = 0; a < keep.size(); ++a) {
                if (!free(box[keep[a]])) return false;
                for (std::size_t b = 0; b < a; ++b)
                    if (box[keep[a]].near(box[keep[b]], gap_)) return false;
            }
            return true;
        };
        const auto place = [&](const std::vector<std::size_t>& keep) {
            for (std::size_t i : keep) draw(role, at[i].text, at[i].x, at[i].baseline);
        };
        const std::vector<std::vector<std::size_t>> spread = spreadSubsets(n, least);
        for (double scale : kLabelScales) {
            measure(labels, clamp, px * scale, at, box);
            for (std::size_t k = 1; k <= n; ++k)
                for (std::size_t first = 0; first < k; ++first) {
                    std::vector<std::size_t> keep;
                    for (std::size_t i = first; i < n; i += k) keep.push_back(i);
                    if (keep.size() < least || !fits(keep)) continue;
                    place(keep);
                    return;
                }
            for (const std::vector<std::size_t>& keep : spread)
                if (fits(keep)) {
                    place(keep);
                    return;
                }
        }
        for (std::size_t i = 0; i < n; ++i)
            if (free(box[i])) draw(role, at[i].text, at[i].x, at[i].baseline);
    }

private:
    /// Where `labels` go at size `px` and their ink, moved inside the figure with `clamp`;
    /// leaves the font at that size.
    void measure(const std::vector<Candidate>& labels, bool clamp, double px, std::vector<Candidate>& at, std::vector<InkBox>& box) {
        font_.size(px);
        at = labels;
        box.assign(labels.size(), InkBox{});
        for (std::size_t i = 0; i < at.size(); ++i) {
            if (at[i].centred) {
                const dvec2 p = font_.centred(at[i].text, at[i].cx, at[i].cy);
                at[i].x = p.x, at[i].baseline = p.y;
            } else {
                at[i].baseline = at[i].cy + font_.capHeight() / 2.0;
            }
            box[i] = font_.draw(nullptr, at[i].text, at[i].x, at[i].baseline);
            if (clamp) {
                const int dx = box[i].x0 < 0 ? -box[i].x0 : box[i].x1 > l_.width ? l_.width - box[i].x1 : 0;
                const int dy = box[i].y0 < 0 ? -box[i].y0 : box[i].y1 > l_.height ? l_.height - box[i].y1 : 0;
                box[i] = box[i].moved(dx, dy);
                at[i].x += dx, at[i].baseline += dy;
            }
        }
    }
    bool free(const InkBox& b) const {
        if (!b.inside(l_.width, l_.height)) return false;
        for (const InkBox& t : taken_)
            if (b.near(t, gap_)) return false;
        return true;
    }
    void draw(const std::string& role, const std::string& text, double x, double baseline) {
        if (text.empty()) return;
        const InkBox b = font_.draw(canvas_, text, x, baseline, kInk);
        taken_.push_back(b);
        placed_.push_back({role, text, b.x0, b.y0, b.x1, b.y1, false});
    }
    /// `text`, or the most of it (code points; then an ellipsis) whose ink from (x, baseline)
    /// ends before `right`; `ellipsis`: `text` already ends in one.
    std::string fitted(const std::string& text, double x, double baseline, double right, bool ellipsis) {
        auto fits = [&](const std::string& t) { return font_.draw(nullptr, t, x, baseline).x1 <= right; };
        if (fits(text)) return text;
        std::vector<char32_t> cps = codePoints(text);
        if (ellipsis && !cps.empty()) cps.pop_back();
        while (!cps.empty()) {
            cps.pop_back();
            while (!cps.empty() && (cps.back() == U' ' || cps.back() == U',' || cps.back() == U';')) cps.pop_back();
            const std::string e = utf8(cps) + "\u2026";
            if (fits(e)) return e;
        }
        return {};
    }

    Font& font_;
    Canvas* canvas_;  ///< null: a trial, nothing drawn
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

/// One JSON line: the figure's size, its plot, the label size, each axis's place drawn (or its
/// preferred one when none is) with its candidates, the span and the widest label extent along
/// it (smallest size) of each of its places not seen end on, and the boxes
/// (OCTRACE_TEST_FIGURE_TEXT).
void appendTextBoxes(const std::string& path, const FigureLayout& l, const std::vector<AxisLabels>& axes,
                     const std::vector<AxisLabels>& groups, Font& font, const std::vector<FigureTextBox>& boxes) {
    std::ostringstream s;
    s << "{\"width\": " << l.width << ", \"height\": " << l.height << ", \"plot\": [" << l.plotX << ", " << l.plotY << ", "
      << l.plotX + l.plotW << ", " << l.plotY + l.plotH << "], \"labelPx\": " << l.labelPx << ", \"axes\": [";
    for (std::size_t i = 0; i < axes.size(); ++i) {
        s << (i ? ", " : "") << "{\"axis\": \"axis " << axes[i].axis << "\", \"edge\": " << axes[i].edge
          << ", \"candidates\": " << axes[i].labels.size() << ", \"span\": " << axes[i].span << ", \"places\": [";
        const char* sep = "";
        for (const AxisLabels& g : groups)
            if (g.axis == axes[i].axis && !g.endOn(l.labelPx))
                s << std::exchange(sep, ", ") << "[" << g.span << ", " << g.extent(font, l.labelPx, true) << "]";
        s << "]}";
    }
    s << "], \"boxes\": [";
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

/// Subtitle and title lines at most (more end in an ellipsis).
constexpr int kMostTitleLines = 2, kMostSubtitleLines = 3;

}  // namespace

std::string figureFontPath() {
    for (const char* p : {"/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf", "/usr/share/fonts/TTF/DejaVuSans.ttf",
                          "/usr/share/fonts/dejavu/DejaVuSans.ttf", "/usr/local/share/fonts/DejaVuSans.ttf"})
        if (std::filesystem::exists(p)) return p;
    return {};
}

double labelWidthEstimate(const std::string& text) {
    int n = 0;
    for (unsigned char ch : text) n += (ch & 0xC0) != 0x80;
    return 0.6 * n;
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

FigureLayout layoutFigure(int width, int height, int dpi, bool colourBar, const FigureRoom& room) {
    FigureLayout l;
    l.width = width;
    l.height = height;
    l.dpi = dpi;
    l.labelPx = kLabelPoints * dpi / 72.0;
    l.titlePx = kTitlePoints * dpi / 72.0;
    l.room = room;
    const int m = outerMargin(l.labelPx), g = gapOf(l.labelPx);
    const int letter = room.letter > 0 ? room.letter + 2 * g : 0;
    const int band = m + int(room.titleLines * titleLine(l) + room.subtitleLines * labelLine(l));
    l.plotX = m + room.left + letter;
    l.plotY = band + g + room.top + letter;
    const int right = room.right + letter;
    // The panel: a gap, the bar, its ticks and their labels, the margin (estimated for short
    // labels until measured).
    const int panel = !colourBar ? m : room.panel > 0 ? room.panel : int(std::lround(6.5 * l.labelPx));
    l.plotW = width - l.plotX - right - panel;
    l.plotH = height - l.plotY - m - room.bottom - letter;
    if (l.plotW < 16 || l.plotH < 16) {
        std::ostringstream s;
        s << "figure: " << width << "x" << height << " pixels at " << dpi
          << " dpi leave no room for the plot beside the text (make it larger or lower the dpi)";
        throw UsageError(s.str());
    }
    if (colourBar) {
        l.barW = int(std::lround(1.2 * l.labelPx));
        l.barX = l.plotX + l.plotW + right + int(std::lround(0.8 * l.labelPx));
        // Below its label, with room for half a tick label above the bar's top.
        l.barY = l.plotY + int(std::lround(room.barLabelLines * labelLine(l) + 0.6 * l.labelPx));
        l.barH = std::max(8, l.plotY + l.plotH - int(std::lround(0.5 * l.labelPx)) - l.barY);
    }
    return l;
}

FigureRoom figureRoom(const FigureSpec& spec, const FigureLayout& l) {
    FigureRoom r;
    Font font(figureFontPath());
    const int m = outerMargin(l.labelPx), g = gapOf(l.labelPx);
    const double across = l.width - 2.0 * m;
    font.size(l.titlePx);
    r.titleLines = std::min<int>(kMostTitleLines, int(wrapped(font, spec.title, across).size()));
    font.size(l.labelPx);
    r.subtitleLines = std::min<int>(kMostSubtitleLines, int(wrapped(font, spec.subtitle, across).size()));
    // Tick labels beyond the plot (those of an edge seen end on are not drawn); an axis's other
    // places are moved inside the figure when one is drawn.
    const double most = 8.0 * l.labelPx;
    for (const AxisLabels& axis : axesOf(spec)) {
        if (axis.edge != 0 || axis.endOn(l.labelPx)) continue;
        for (const FigureLabel* lab : axis.labels) {
            const InkBox b = labelBox(font, *lab, l);
            if (b.empty()) continue;
            auto grow = [&](int& side, double beyond) {
                if (beyond > 0.0) side = std::max(side, int(std::ceil(std::min(beyond, most))) + g);
            };
            grow(r.left, l.plotX - b.x0);
            grow(r.top, l.plotY - b.y0);
            grow(r.right, b.x1 - (l.plotX + l.plotW));
            grow(r.bottom, b.y1 - (l.plotY + l.plotH));
        }
    }
    for (const std::string& letter : spec.sideLetters)
        if (!letter.empty()) {
            const InkBox b = font.draw(nullptr, letter, 0.0, 0.0);
            r.letter = std::max({r.letter, b.x1 - b.x0, b.y1 - b.y0});
        }
    // The colour bar's panel: its ticks' labels and its label above it.
    if (hasBar(spec)) {
        double step = 1.0, widest = 0.0;
        for (double v : barTicks(spec, step)) widest = std::max(widest, font.width(tickText(v, step)));
        const double lead = std::round(0.8 * l.labelPx), barW = std::round(1.2 * l.labelPx);
        const double ticks = lead + barW + 1.0 + 0.6 * l.labelPx + widest + m;
        const std::vector<std::string> lines = barLabelLines(font, spec.barLabel, std::max(ticks - lead - m, l.width / 5.0));
        double label = 0.0;
        for (const std::string& t : lines) label = std::max(label, lead + font.width(t) + m);
        r.panel = int(std::ceil(std::max(ticks, label)));
        r.barLabelLines = int(lines.size());
    }
    return r;
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

    // The text in order of precedence, each placed where it overlaps nothing placed before:
    // title and subtitle, the colour bar with its label and ticks, the patient's letters, the
    // axes, the scale bar.
    const int m = outerMargin(l.labelPx), g = gapOf(l.labelPx);
    const double across = l.width - 2.0 * m;
    font.size(l.titlePx);
    text.placeLines("title", wrapped(font, spec.title, across), std::size_t(l.room.titleLines), l.titlePx, m, m + 0.95 * l.titlePx,
                    titleLine(l), across);
    font.size(l.labelPx);
    const double subTop = m + l.room.titleLines * titleLine(l);
    text.placeLines("subtitle", wrapped(font, spec.subtitle, across), std::size_t(l.room.subtitleLines), l.labelPx, m,
                    subTop + 0.95 * l.labelPx, labelLine(l), across);

    // Colour bar: each row the map's colour for its value, high at the top, a frame around.
    if (hasBar(spec) && l.barW > 0) {
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
        // The label above the bar, in the lines the room made for it, moved left if it would
        // leave the figure.
        const std::vector<std::string> lines = barLabelLines(font, spec.barLabel, std::max(l.width - m - double(l.barX), l.width / 5.0));
        double widest = 0.0;
        for (const std::string& t : lines) widest = std::max(widest, font.width(t));
        const double labelX = std::max(double(l.plotX + l.plotW), std::min(double(l.barX), l.width - m - widest));
        text.placeLines("bar label", lines, std::size_t(std::max(1, l.room.barLabelLines)), l.labelPx, labelX, l.plotY + 0.95 * l.labelPx,
                        labelLine(l), l.width - m - labelX);
        // Ticks: round values of what the bar reads (heights, or depths positive down).
        double step = 1.0;
        const std::vector<double> ticks = barTicks(spec, step);
        const double lo = spec.barPositiveDown ? -spec.high : spec.low, hi = spec.barPositiveDown ? -spec.low : spec.high;
        std::vector<Candidate> labels;
        for (double v : ticks) {
            const double u = (v - lo) / (hi - lo);  // 0 at the reading's low end
            const double y = l.barY + (spec.barPositiveDown ? u : 1.0 - u) * l.barH;
            const double xs = l.barX + l.barW + 1.0;
            canvas.line({xs, y}, {xs + 0.4 * l.labelPx, y}, lineWidth, kLineInk);
            labels.push_back({tickText(v, step), xs + 0.6 * l.labelPx, 0.0, false, 0.0, y});
        }
        text.placeThinned("bar tick", labels, false, l.labelPx, 3);
    }

    // The patient's letters outside the plot at the middle of each side, beyond its tick labels.
    if (l.room.letter > 0) {
        const double half = 0.5 * l.room.letter, midX = l.plotX + 0.5 * l.plotW, midY = l.plotY + 0.5 * l.plotH;
        const dvec2 at[4] = {{l.plotX - l.room.left - g - half, midY},
                             {midX, l.plotY - l.room.top - g - half},
                             {l.plotX + l.plotW + l.room.right + g + half, midY},
                             {midX, l.plotY + l.plotH + l.room.bottom + g + half}};
        for (int side = 0; side < 4; ++side)
            if (!spec.sideLetters[std::size_t(side)].empty())
                text.placeThinned("letter", {{spec.sideLetters[std::size_t(side)], 0.0, 0.0, true, at[side].x, at[side].y}}, true,
                                  l.labelPx, 1);
    }

    // Tick labels on the bounding box, axis by axis; none on an edge seen end on. The axes are
    // placed in the first order (x, y, z, then the others) in which the most of them keep 3
    // labels (all, with fewer candidates): an edge foreshortened by the perspective may need the
    // room that a long one, placed later, can give up. Each axis goes on its preferred place
    // (edge 0) if it keeps 3 there, else on the first of its other places (other box edges)
    // where it does, else on the one where it keeps the most.
    std::vector<AxisLabels> groups = axesOf(spec), axes;
    for (const AxisLabels& g : groups)
        if (g.edge == 0 && !g.endOn(l.labelPx)) axes.push_back(g);
    const auto places = [&](const AxisLabels& axis) {
        std::vector<const AxisLabels*> out;
        for (const AxisLabels& g : groups)
            if (g.axis == axis.axis && !g.endOn(l.labelPx)) out.push_back(&g);
        std::stable_sort(out.begin(), out.end(), [](const AxisLabels* a, const AxisLabels* b) { return a->edge < b->edge; });
        return out;
    };
    const auto candidates = [&](const AxisLabels& axis, bool bare) {
        std::vector<Candidate> labels;
        for (const FigureLabel* lab : axis.labels)
            labels.push_back({labelText(*lab, bare), 0.0, 0.0, true, origin.x + lab->at.x + lab->dx * l.labelPx,
                              origin.y + lab->at.y + lab->dy * l.labelPx});
        return labels;
    };
    constexpr std::size_t kLeastTicks = 3;
    // Places the axes in `order` on `layout`, choosing each one's place; returns the places and
    // counts the axes that kept 3 in `kept`.
    const auto placeAxes = [&](TextLayout& layout, const std::vector<std::size_t>& order, std::size_t& kept) {
        std::vector<const AxisLabels*> chosen;
        kept = 0;
        for (std::size_t i : order) {
            const std::string role = "axis " + std::to_string(axes[i].axis);
            const std::vector<const AxisLabels*> all = places(axes[i]);
            const AxisLabels* pick = nullptr;
            std::size_t most = 0;
            bool bare = false;
            // With their unit on each place in turn, then (labels that have one) without it.
            for (const bool b : {false, true}) {
                if (b && !axes[i].hasBare()) break;
                for (const AxisLabels* place : all) {
                    TextLayout t = layout.trial();
                    t.placeThinned(role, candidates(*place, b), true, l.labelPx, kLeastTicks);
                    if (!pick || t.count(role) > most) pick = place, most = t.count(role), bare = b;
                    if (most >= std::min(kLeastTicks, place->labels.size())) break;
                }
                if (most >= std::min(kLeastTicks, pick->labels.size())) break;
            }
            // An axis too short for 3 labels on each of its places (docs/dev/figures.md) keeps 2
            // where they fit, as evenly spread as they can be, with their unit.
            std::size_t least = kLeastTicks;
            if (most < std::min(kLeastTicks, pick->labels.size()) &&
                std::none_of(all.begin(), all.end(), [&](const AxisLabels* p) { return p->roomFor(kLeastTicks, font, l.labelPx, true); })) {
                least = 2;
                pick = nullptr, most = 0, bare = false;
                for (const AxisLabels* place : all) {
                    TextLayout t = layout.trial();
                    t.placeThinned(role, candidates(*place, false), true, l.labelPx, least);
                    if (!pick || t.count(role) > most) pick = place, most = t.count(role);
                }
            }
            layout.placeThinned(role, candidates(*pick, bare), true, l.labelPx, least);
            kept += most >= std::min(least, pick->labels.size());
            chosen.push_back(pick);
        }
        return chosen;
    };
    std::vector<std::size_t> order(axes.size()), best;
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::size_t bestKept = 0;
    do {
        TextLayout trial = text.trial();
        std::size_t kept = 0;
        placeAxes(trial, order, kept);
        if (best.empty() || kept > bestKept) best = order, bestKept = kept;
    } while (bestKept < axes.size() && std::next_permutation(order.begin(), order.end()));
    std::size_t kept = 0;
    std::vector<AxisLabels> drawn;  // each axis's place drawn, else its preferred one
    for (const AxisLabels* place : placeAxes(text, best, kept)) drawn.push_back(*place);
    for (const AxisLabels& g : groups)
        if (g.edge == 0 && std::none_of(drawn.begin(), drawn.end(), [&](const AxisLabels& d) { return d.axis == g.axis; }))
            drawn.push_back(g);
    // The tick marks of the places drawn (and of an edge seen end on).
    for (const AxisLabels& place : drawn)
        for (const FigureLabel* lab : place.labels) {
            const dvec2 p = origin + lab->at;
            canvas.fill(int(std::floor(p.x - lineWidth)), int(std::floor(p.y - lineWidth)), int(std::lround(2 * lineWidth)) + 1,
                        int(std::lround(2 * lineWidth)) + 1, kLineInk);
        }

    // Scale bar: a bar with end ticks in the plot's lower left corner, its length above it;
    // in the lower right corner where tick labels take the left one, else none.
    if (spec.scaleBarPx > 0.0) {
        const double y = l.plotY + l.plotH - 1.2 * l.labelPx, tick = 0.4 * l.labelPx, w = 2.0 * lineWidth;
        font.size(l.labelPx);
        for (double x0 : {l.plotX + 1.2 * l.labelPx, l.plotX + l.plotW - 1.2 * l.labelPx - spec.scaleBarPx}) {
            const double x1 = x0 + spec.scaleBarPx;
            const dvec2 p = font.centred(spec.scaleBarLabel, 0.5 * (x0 + x1), y - tick - 0.8 * l.labelPx);
            const InkBox label = font.draw(nullptr, spec.scaleBarLabel, p.x, p.y);
            const InkBox bar{int(std::floor(x0 - w)), int(std::floor(y - tick - w)), int(std::ceil(x1 + w)), int(std::ceil(y + tick + w))};
            if (!text.isFree(label) || !text.isFree(bar)) continue;
            canvas.line({x0, y}, {x1, y}, w, kLineInk);
            canvas.line({x0, y - tick}, {x0, y + tick}, w, kLineInk);
            canvas.line({x1, y - tick}, {x1, y + tick}, w, kLineInk);
            text.graphic("scale bar line", bar);
            text.placeThinned("scale bar", {{spec.scaleBarLabel, 0.0, 0.0, true, 0.5 * (x0 + x1), y - tick - 0.8 * l.labelPx}}, false,
                              l.labelPx, 1);
            break;
        }
    }

    if (textOut) *textOut = text.placed();
    if (const char* path = std::getenv("OCTRACE_TEST_FIGURE_TEXT"); path && *path) appendTextBoxes(path, l, drawn, groups, font, text.placed());
    return f;
}

}  // namespace octrace::io
