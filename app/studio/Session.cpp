#include "Session.h"

#include "octrace/model/SolidSpec.h"
#include "octrace/model/Surface.h"
#include "octrace/csg/Solid.h"
#include "octrace/model/OptionTable.h"
#include "octrace/model/Settings.h"
#include "octrace/io/AtomicFile.h"
#include "octrace/octree/Octree.h"
#include "octrace/render/Renderer.h"
#include "octrace/render/Shading.h"
#include "octrace/util/Error.h"

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>

#include <array>
#include <map>
#include <optional>
#include <type_traits>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace octrace::studio {
namespace {

/// Version 2 added the `layout` group (four-up, crosshair, slice positions and window);
/// version 1 files open as before (the layout as a new window has it).
constexpr int kFormatVersion = 2;
constexpr int kOldestFormatVersion = 1;
const char* kFormatKey = "octrace_studio_session";

QJsonArray array(const dvec3& v) { return {v.x, v.y, v.z}; }
QJsonArray array(const vec3& v) { return {double(v.x), double(v.y), double(v.z)}; }
QJsonArray array(const vec4& v) { return {double(v.x), double(v.y), double(v.z), double(v.w)}; }

/// Reads the members of one JSON object, refusing wrong types with the member's path.
class Reader {
public:
    Reader(const QJsonObject& o, QString path) : o_(o), path_(std::move(path)) {}

    bool has(const char* key) const { return o_.contains(QLatin1String(key)) && !o_.value(QLatin1String(key)).isNull(); }
    /// Whether `key` holds the string `word`.
    bool isText(const char* key, const char* word) const { return o_.value(QLatin1String(key)) == QJsonValue(QLatin1String(word)); }
    [[noreturn]] void fail(const char* key, const QString& what) const {
        throw InputError((path_ + QLatin1String(key) + QStringLiteral(": ") + what).toStdString());
    }
    Reader object(const char* key) const {
        const QJsonValue v = o_.value(QLatin1String(key));
        if (v.isUndefined() || v.isNull()) return Reader({}, path_ + QLatin1String(key) + QLatin1Char('.'));
        if (!v.isObject()) fail(key, QStringLiteral("must be an object"));
        return Reader(v.toObject(), path_ + QLatin1String(key) + QLatin1Char('.'));
    }
    void text(const char* key, std::string& out) const {
        if (!has(key)) return;
        const QJsonValue v = o_.value(QLatin1String(key));
        if (!v.isString()) fail(key, QStringLiteral("must be a string"));
        out = v.toString().toStdString();
    }
    void flag(const char* key, bool& out) const {
        if (!has(key)) return;
        const QJsonValue v = o_.value(QLatin1String(key));
        if (!v.isBool()) fail(key, QStringLiteral("must be true or false"));
        out = v.toBool();
    }
    double number(const char* key, double lo, double hi) const {
        const QJsonValue v = o_.value(QLatin1String(key));
        if (!v.isDouble() || !std::isfinite(v.toDouble())) fail(key, QStringLiteral("must be a number"));
        const double d = v.toDouble();
        if (d < lo || d > hi) fail(key, QStringLiteral("%1 is outside [%2, %3]").arg(d).arg(lo).arg(hi));
        return d;
    }
    /// A numeric setting of the options table, stored under its session member: the range (and
    /// whether it must be whole) come from the table.
    template <typename T>
    void setting(const model::Option& o, T& out) const {
        const std::string member = model::sessionMember(o);
        const char* key = member.c_str();
        if (!has(key)) return;
        const QJsonValue v = o_.value(QLatin1String(key));
        if (!v.isDouble() || !std::isfinite(v.toDouble())) fail(key, QStringLiteral("must be a number"));
        if (auto problem = model::valueProblem(o, v.toDouble())) fail(key, QString::fromStdString(*problem));
        out = T(v.toDouble());
    }
    /// An on|off or Flag setting of the options table, stored as true or false.
    void onOff(const model::Option& o, bool& out) const { flag(model::sessionMember(o).c_str(), out); }
    void integer(const char* key, int& out, int lo, int hi) const {
        if (!has(key)) return;
        const double d = number(key, lo, hi);
        if (d != std::floor(d)) fail(key, QStringLiteral("must be a whole number"));
        out = int(d);
    }
    /// An array of n finite numbers within [lo, hi].
    std::vector<double> numbers(const char* key, int n, double lo, double hi) const {
        const QJsonValue v = o_.value(QLatin1String(key));
        if (!v.isArray() || v.toArray().size() != n) fail(key, QStringLiteral("must be an array of %1 numbers").arg(n));
        std::vector<double> out;
        for (const QJsonValue& e : v.toArray()) {
            if (!e.isDouble() || !std::isfinite(e.toDouble())) fail(key, QStringLiteral("must be an array of %1 numbers").arg(n));
            if (e.toDouble() < lo || e.toDouble() > hi)
                fail(key, QStringLiteral("%1 is outside [%2, %3]").arg(e.toDouble()).arg(lo).arg(hi));
            out.push_back(e.toDouble());
        }
        return out;
    }
    /// An array of n members, each a finite number or null (unset).
    template <std::size_t N>
    std::array<std::optional<double>, N> optionalNumbers(const char* key) const {
        const QJsonValue v = o_.value(QLatin1String(key));
        const QString what = QStringLiteral("must be an array of %1 numbers or nulls").arg(N);
        if (!v.isArray() || std::size_t(v.toArray().size()) != N) fail(key, what);
        std::array<std::optional<double>, N> out;
        for (std::size_t i = 0; i < N; ++i) {
            const QJsonValue e = v.toArray().at(qsizetype(i));
            if (e.isNull()) continue;
            if (!e.isDouble() || !std::isfinite(e.toDouble())) fail(key, what);
            out[i] = e.toDouble();
        }
        return out;
    }
    void vector3(const char* key, dvec3& out, double limit) const {
        if (!has(key)) return;
        const auto v = numbers(key, 3, -limit, limit);
        out = dvec3(v[0], v[1], v[2]);
    }
    /// An array of 3 (4: with alpha) numbers in [0,1], or a text the options table's colour
    /// parser takes ("steelblue", "#4682b4"), as a hand-written session may give.
    void colour(const char* key, vec3& out) const {
        if (!has(key)) return;
        if (const auto text = colourText(key, false)) {
            out = vec3(*text);
            return;
        }
        const auto v = numbers(key, 3, 0.0, 1.0);
        out = vec3(float(v[0]), float(v[1]), float(v[2]));
    }
    void colour(const char* key, vec4& out) const {
        if (!has(key)) return;
        if (const auto text = colourText(key, true)) {
            out = *text;
            return;
        }
        const auto v = numbers(key, 4, 0.0, 1.0);
        out = vec4(float(v[0]), float(v[1]), float(v[2]), float(v[3]));
    }

private:
    std::optional<vec4> colourText(const char* key, bool alpha) const {
        const QJsonValue v = o_.value(QLatin1String(key));
        if (!v.isString()) return std::nullopt;
        const model::Option& o = alpha ? model::opt::background : model::opt::colour;
        try {
            return model::parseColour(o, v.toString().toStdString(), alpha);
        } catch (const UsageError& e) {
            const std::string why = e.what();
            fail(key, QString::fromStdString(why.substr(why.find(": ") == std::string::npos ? 0 : why.find(": ") + 2)));
        }
    }

    QJsonObject o_;
    QString path_;
};

void checkRenderer(const Reader& r, const char* key, const std::string& name) {
    // A name or an alias (area+colour), as on the command line.
    bool known = false;
    try {
        known = makeRenderer(resolveRendererName(name).renderer)->drawsVoxels();
    } catch (const UsageError&) {
    }
    if (!known) r.fail(key, QStringLiteral("unknown renderer '%1'").arg(QString::fromStdString(name)));
}

}  // namespace

QByteArray sessionJson(const StudioState& s) {
    QJsonObject input{{"path", QString::fromStdString(s.input)},
                      {"variable", QString::fromStdString(s.variable)},
                      {"time", QString::fromStdString(s.time)},
                      {"series", QString::fromStdString(s.series)}};
    const auto member = [](const model::Option& o) { return QString::fromStdString(model::sessionMember(o)); };
    QJsonObject surface{{"iso", s.iso ? QJsonValue(*s.iso) : QJsonValue()},
                        {member(model::opt::depth), s.depth ? QJsonValue(*s.depth) : QJsonValue("auto")},
                        {"cut", QString::fromStdString(s.cut)},
                        {"clip", s.clip}};
    QJsonObject renderers{{"main", QString::fromStdString(s.renderer)},
                          {"second", QString::fromStdString(s.secondRenderer)},
                          {"split", s.split}};
    QJsonObject camera;
    if (s.cameraSet) {
        camera.insert("position", array(s.position));
        camera.insert("look_at", array(s.lookAt));
        camera.insert("up", array(s.up));
    }
    QJsonObject shading{{"light", array(s.light)},
                        {"colour", array(s.colour)},
                        {"colormap", QString::fromStdString(s.colormap)},
                        {"window", QString::fromStdString(s.window)},
                        {member(model::opt::lighting), QString::fromStdString(s.lighting)}};
    if (s.background) shading.insert("background", array(*s.background));  // absent: contrasting with the surface
    QJsonObject exportSettings{{"transparent", s.transparent},
                               {member(model::opt::title), QString::fromStdString(s.title)}};
    // The bound settings (StudioState.h), each under its group and member of the table.
    const std::map<QString, QJsonObject*> groups{{"input", &input}, {"surface", &surface}, {"renderers", &renderers}, {"camera", &camera},
                                                 {"shading", &shading}, {"export", &exportSettings}};
    for (const Binding& b : bindings()) {
        const QString path = QString::fromLatin1(b.option->session);
        const qsizetype dot = path.indexOf(QLatin1Char('.'));
        QJsonObject* group = groups.at(path.left(dot));
        std::visit([&](auto m) { group->insert(path.mid(dot + 1), QJsonValue(s.*m)); }, b.member);
    }
    // The text settings (StudioState::settings): those given, under their table members, as
    // the table's kind says (a Flag true, a number a number, else the text).
    for (const model::Option* o : textSettings()) {
        const auto given = s.settings.find(o->key);
        if (given == s.settings.end()) continue;
        const QString path = QString::fromLatin1(o->session);
        const qsizetype dot = path.indexOf(QLatin1Char('.'));
        QJsonValue value = QString::fromStdString(given->second);
        if (o->kind == model::OptionKind::Flag) value = true;
        else if (o->kind == model::OptionKind::Integer || o->kind == model::OptionKind::Number) value = std::stod(given->second);
        groups.at(path.left(dot))->insert(path.mid(dot + 1), value);
    }
    QJsonObject layout{{"four_up", s.fourUp}, {"slice_window", QString::fromStdString(s.sliceWindow)}};
    if (s.crosshair) layout.insert("crosshair", QJsonArray{s.crosshair->x, s.crosshair->y, s.crosshair->z});
    QJsonArray at;
    for (const auto& a : s.sliceAt) at.append(a ? QJsonValue(*a) : QJsonValue());
    layout.insert("slice_at", at);
    QJsonObject root{{kFormatKey, kFormatVersion}, {"input", input},     {"surface", surface}, {"renderers", renderers},
                     {"camera", camera},           {"shading", shading}, {"export", exportSettings}, {"layout", layout}};
    return QJsonDocument(root).toJson(QJsonDocument::Indented);
}

StudioState parseSession(const QByteArray& json, const QString& baseFolder) {
    QJsonParseError err{};
    const QJsonDocument doc = QJsonDocument::fromJson(json, &err);
    if (err.error != QJsonParseError::NoError)
        throw InputError(QStringLiteral("not a session file: JSON error at byte %1: %2").arg(err.offset).arg(err.errorString()).toStdString());
    if (!doc.isObject()) throw InputError("not a session file: the JSON is not an object");
    const Reader root(doc.object(), QString());
    if (!root.has(kFormatKey)) throw InputError(std::string("not a session file: no '") + kFormatKey + "' member");
    int version = 0;
    root.integer(kFormatKey, version, 1, 1000000);
    if (version < kOldestFormatVersion || version > kFormatVersion)
        root.fail(kFormatKey, QStringLiteral("format version %1 is not supported (this studio reads %2 to %3)")
                                  .arg(version)
                                  .arg(kOldestFormatVersion)
                                  .arg(kFormatVersion));

    StudioState s;
    const Reader input = root.object("input");
    input.text("path", s.input);
    if (!s.input.empty() && s.input.rfind("analytic:", 0) != 0 && QFileInfo(QString::fromStdString(s.input)).isRelative() &&
        !baseFolder.isEmpty())
        s.input = QDir(baseFolder).filePath(QString::fromStdString(s.input)).toStdString();
    input.text("variable", s.variable);
    input.text("time", s.time);
    input.text("series", s.series);

    // The bound settings (StudioState.h): each group's members of the table, with their ranges.
    for (const Binding& b : bindings()) {
        const std::string path = b.option->session;
        const Reader group = root.object(path.substr(0, path.find('.')).c_str());
        std::visit(
            [&](auto m) {
                if constexpr (std::is_same_v<decltype(m), bool StudioState::*>) group.onOff(*b.option, s.*m);
                else group.setting(*b.option, s.*m);
            },
            b.member);
    }

    // The text settings, each checked as the CLI checks its flag.
    for (const model::Option* o : textSettings()) {
        const std::string path = o->session, member = model::sessionMember(*o);
        const Reader group = root.object(path.substr(0, path.find('.')).c_str());
        std::string text;
        if (o->kind == model::OptionKind::Flag) {
            bool on = false;
            group.flag(member.c_str(), on);
            if (on) text = "on";
        } else if (o->kind == model::OptionKind::Integer || o->kind == model::OptionKind::Number) {
            if (!group.has(member.c_str())) continue;
            double v = 0.0;
            group.setting(*o, v);
            char buf[64];
            std::snprintf(buf, sizeof buf, "%.17g", v);
            text = buf;
        } else {
            group.text(member.c_str(), text);
        }
        if (text.empty()) continue;
        try {
            checkSetting(*o, text);
        } catch (const UsageError& e) {
            group.fail(member.c_str(), QString::fromStdString(e.what()));
        }
        s.settings[o->key] = text;
    }

    const Reader surface = root.object("surface");
    if (surface.has("iso")) s.iso = surface.number("iso", -1e300, 1e300);
    // `depth`: a number in the table's range, or "auto" (absent: auto, the table's default).
    const std::string depthMember = model::sessionMember(model::opt::depth);
    if (surface.has(depthMember.c_str()) && !surface.isText(depthMember.c_str(), "auto")) {
        int depth = 0;
        surface.setting(model::opt::depth, depth);
        s.depth = depth;
    }
    surface.text("cut", s.cut);
    if (!s.cut.empty()) {
        try {
            model::checkSolidArgument(s.cut);  // a primitive or relief:FILE, as --cut takes
        } catch (const UsageError& e) {
            surface.fail("cut", QString::fromStdString(e.what()));
        }
    }
    surface.flag("clip", s.clip);

    const Reader renderers = root.object("renderers");
    renderers.text("main", s.renderer);
    checkRenderer(renderers, "main", s.renderer);
    renderers.text("second", s.secondRenderer);
    if (s.secondRenderer != kOpenGlPane) checkRenderer(renderers, "second", s.secondRenderer);
    renderers.flag("split", s.split);

    const Reader camera = root.object("camera");
    const int given = int(camera.has("position")) + int(camera.has("look_at")) + int(camera.has("up"));
    if (given != 0 && given != 3) camera.fail("position", QStringLiteral("position, look_at and up go together"));
    if (given == 3) {
        constexpr double kLimit = ScalarField::kMaxWorldCoordinate;
        camera.vector3("position", s.position, kLimit);
        camera.vector3("look_at", s.lookAt, kLimit);
        camera.vector3("up", s.up, kLimit);
        s.cameraSet = true;
        Camera c;
        c.position = s.position;
        c.lookAt = s.lookAt;
        c.up = s.up;
        c.fovYDegrees = s.fov;
        try {
            c.validate();
        } catch (const UsageError& e) {
            camera.fail("position", QString::fromStdString(e.what()));
        }
    }

    const Reader shading = root.object("shading");
    shading.vector3("light", s.light, 1e6);
    if (!(glm::length(s.light) > 0.0)) shading.fail("light", QStringLiteral("direction must not be zero"));
    shading.colour("colour", s.colour);
    shading.text("colormap", s.colormap);
    if (!s.colormap.empty()) {
        const auto names = colormapNames();
        if (std::find(names.begin(), names.end(), s.colormap) == names.end())
            shading.fail("colormap", QStringLiteral("unknown colour map '%1'").arg(QString::fromStdString(s.colormap)));
    }
    shading.text("window", s.window);
    if (!s.window.empty()) {
        try {
            model::displayWindow(s.window);
        } catch (const UsageError& e) {
            shading.fail("window", QString::fromStdString(e.what()));
        }
        if (!s.colormap.empty() && s.window != "none")
            shading.fail("window", QStringLiteral("a display window and a colour map both colour the surface: give one"));
    }
    if (shading.has("background")) {
        vec4 background;
        shading.colour("background", background);
        s.background = background;
    }
    shading.text("lighting", s.lighting);
    if (!s.lighting.empty() && s.lighting != "baked" && s.lighting != "dynamic")
        shading.fail("lighting", QStringLiteral("expected \"\", \"baked\" or \"dynamic\", got '%1'").arg(QString::fromStdString(s.lighting)));

    const Reader exportSettings = root.object("export");
    exportSettings.flag("transparent", s.transparent);
    exportSettings.text(model::sessionMember(model::opt::title).c_str(), s.title);

    // Version 2: the layout and the slice panes (absent: the 3-D view alone, the middle sample).
    const Reader layout = root.object("layout");
    layout.flag("four_up", s.fourUp);
    if (layout.has("crosshair")) {
        // Sample indices, as the CLI's `index` counts them (its range from the table).
        const auto c = layout.numbers("crosshair", 3, model::opt::index.min, model::opt::index.max);
        for (double v : c)
            if (v != std::floor(v)) layout.fail("crosshair", QStringLiteral("%1 is not a whole number").arg(v));
        s.crosshair = ivec3(int(c[0]), int(c[1]), int(c[2]));
    }
    if (layout.has("slice_at")) s.sliceAt = layout.optionalNumbers<3>("slice_at");
    layout.text("slice_window", s.sliceWindow);
    if (!s.sliceWindow.empty()) {
        try {
            if (model::displayWindow(s.sliceWindow).width <= 0.0) throw UsageError("not a window");
        } catch (const UsageError& e) {
            layout.fail("slice_window", QString::fromStdString(e.what()));
        }
    }
    return s;
}

void saveSession(const StudioState& state, const QString& path) {
    StudioState s = state;
    // A file input as an absolute path: the session opens from any folder.
    if (!s.input.empty() && s.input.rfind("analytic:", 0) != 0)
        s.input = QFileInfo(QString::fromStdString(s.input)).absoluteFilePath().toStdString();
    const QByteArray json = sessionJson(s);
    io::writeFileAtomically(path.toStdString(), std::string_view(json.constData(), std::size_t(json.size())));
}

StudioState loadSession(const QString& path) {
    QFile f(path);
    if (!f.exists()) throw InputError(path.toStdString() + ": no such file");
    if (!f.open(QIODevice::ReadOnly)) throw InputError(path.toStdString() + ": cannot read: " + f.errorString().toStdString());
    constexpr qint64 kMaxSessionBytes = 1 << 20;
    if (f.size() > kMaxSessionBytes) throw InputError(path.toStdString() + ": too large for a session file (over 1 MiB)");
    try {
        return parseSession(f.readAll(), QFileInfo(path).absolutePath());
    } catch (const InputError& e) {
        throw InputError(path.toStdString() + ": " + e.what());
    }
}

}  // namespace octrace::studio
