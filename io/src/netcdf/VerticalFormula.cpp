#include "netcdf/VerticalFormula.h"

#include "input/InputFile.h"
#include "octrace/util/Error.h"
#include "octrace/util/Memory.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace octrace::io::detail {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct Formula {
    const char* standardName;
    VerticalKind kind;
    std::vector<const char*> terms;  // the terms CF Appendix D gives the formula
};

const std::vector<Formula>& formulas() {
    static const std::vector<Formula> f = {
        {"ocean_s_coordinate_g1", VerticalKind::SigmaG1, {"s", "C", "eta", "depth", "depth_c"}},
        {"ocean_s_coordinate_g2", VerticalKind::SigmaG2, {"s", "C", "eta", "depth", "depth_c"}},
        {"ocean_sigma_coordinate", VerticalKind::Sigma, {"sigma", "eta", "depth"}},
        {"ocean_double_sigma_coordinate", VerticalKind::DoubleSigma, {"sigma", "depth", "z1", "z2", "a", "href", "k_c"}},
        {"ocean_s_coordinate", VerticalKind::SCoordinate, {"s", "eta", "depth", "a", "b", "depth_c"}},
    };
    return f;
}

std::string knownFormulas() {
    std::string s;
    for (const auto& f : formulas()) s += (s.empty() ? "" : ", ") + std::string(f.standardName);
    return s;
}

const VariableInfo* findVariable(const CfSource& file, const std::string& shortName) {
    for (const auto& v : file.variables())
        if (v.shortName == shortName) return &v;
    return nullptr;
}

// A term's values over the field's columns: value(i, j, k) at the column's stored indices.
struct Term {
    std::vector<double> values;
    std::array<std::size_t, 3> stride{};  // per field axis x, y, z; 0 where the term is constant
    double at(std::size_t xs, std::size_t ys, std::size_t k) const {
        return values[xs * stride[0] + ys * stride[1] + k * stride[2]];
    }
};

class TermReader {
public:
    TermReader(const std::string& path, const CfSource& file, const VariableInfo& var, const ParametricVertical& p,
               const ColumnSelection& sel)
        : path_(path), file_(file), var_(var), p_(p), sel_(sel) {}

    // The variable of `term` (the given depth variable when `term` is empty).
    Term read(const std::string& term, std::uint64_t& bytes) const {
        std::string name = p_.coordinateVariable;
        if (!term.empty()) {
            name.clear();
            for (const auto& t : p_.terms)
                if (t.term == term) name = t.variable;
        }
        const std::string what = path_ + ": the formula_terms of '" + p_.coordinateVariable + "' (" + p_.formula +
                                 ") name variable '" + name + "' for term '" + term + "'";
        const VariableInfo* tv = findVariable(file_, name);
        if (!tv) {
            if (auto s = file_.scalar(name)) return Term{{*s}, {}};
            throw InputError(what + ", which the file does not have (or it is not numeric): the depths of variable " +
                             var_.signature() + " cannot be computed");
        }
        if (!tv->numeric) throw InputError(what + ", which is not numeric");
        Term t;
        const std::size_t nd = tv->dimNames.size();
        std::vector<std::uint64_t> start(nd, 0);
        std::vector<std::size_t> count(nd, 1);
        std::vector<int> axisOf(nd, -1);
        for (std::size_t e = 0; e < nd; ++e) {
            auto d = std::find(var_.dimNames.begin(), var_.dimNames.end(), tv->dimNames[e]);
            if (d == var_.dimNames.end()) {
                if (tv->dimSizes[e] == 1) continue;
                throw InputError(what + " " + tv->signature() + ": its dimension '" + tv->dimNames[e] +
                                 "' is not one of variable " + var_.signature() +
                                 "'s: the term does not lie on the field's grid");
            }
            std::size_t fd = std::size_t(d - var_.dimNames.begin());
            if (tv->dimSizes[e] != var_.dimSizes[fd])
                throw InputError(what + " " + tv->signature() + ": its dimension '" + tv->dimNames[e] + "' has " +
                                 std::to_string(tv->dimSizes[e]) + " points, variable '" + var_.shortName + "' has " +
                                 std::to_string(var_.dimSizes[fd]));
            for (int a = 0; a < 3; ++a)
                if (sel_.dim[std::size_t(a)] == fd) axisOf[e] = a;
            if (axisOf[e] >= 0) count[e] = tv->dimSizes[e];
            else start[e] = sel_.fixedIndex[fd];
        }
        std::uint64_t n = hyperslabSamples(path_, *tv, count);
        bytes = saturatingMultiply(n, sizeof(double));
        t.values = file_.read(*tv, start, count);
        SampleRules r = file_.rules(*tv);
        for (double& v : t.values) v = r.isValid(v) ? v * r.scale + r.offset : kNaN;
        std::size_t stride = 1;
        for (std::size_t e = nd; e-- > 0;) {
            if (axisOf[e] >= 0) t.stride[std::size_t(axisOf[e])] = stride;
            stride *= count[e];
        }
        return t;
    }

private:
    const std::string& path_;
    const CfSource& file_;
    const VariableInfo& var_;
    const ParametricVertical& p_;
    const ColumnSelection& sel_;
};

// Depth (positive down) of level k of column (xs, ys) by the formula, from z (positive up).
struct Evaluator {
    VerticalKind kind;
    std::map<std::string, Term> t;
    double givenToM = 1.0;

    double get(const char* term, std::size_t xs, std::size_t ys, std::size_t k) const {
        return t.at(term).at(xs, ys, k);
    }
    // z at level k; surface and floor of the column (depths) through `top` and `bottom`.
    double depth(std::size_t xs, std::size_t ys, std::size_t k, double& top, double& bottom) const {
        if (kind == VerticalKind::GivenDepth) return t.at("").at(xs, ys, k) * givenToM;
        const double depthTerm = get("depth", xs, ys, k);
        bottom = depthTerm;
        top = 0.0;
        if (kind == VerticalKind::DoubleSigma) {
            const double sigma = get("sigma", xs, ys, k), z1 = get("z1", xs, ys, k), z2 = get("z2", xs, ys, k);
            const double a = get("a", xs, ys, k), href = get("href", xs, ys, k);
            const double f = 0.5 * (z1 + z2) + 0.5 * (z1 - z2) * std::tanh(2.0 * a / (z1 - z2) * (depthTerm - href));
            // CF's branch k <= k_c is the upper sigma layer, where sigma <= 1; both branches
            // give f at sigma = 1, so choosing by sigma needs no guess of k_c's index base.
            const double z = sigma <= 1.0 ? sigma * f : f + (sigma - 1.0) * (depthTerm - f);
            return std::abs(z);  // CF gives this z no sign convention; depth grows away from the surface
        }
        const double eta = get("eta", xs, ys, k);
        top = -eta;
        if (!(depthTerm > 0.0)) return kNaN;  // land or no water column
        double z = kNaN;
        switch (kind) {
            case VerticalKind::Sigma: z = eta + get("sigma", xs, ys, k) * (depthTerm + eta); break;
            case VerticalKind::SigmaG1: {
                const double s = get("s", xs, ys, k), C = get("C", xs, ys, k), hc = get("depth_c", xs, ys, k);
                const double S = hc * s + (depthTerm - hc) * C;
                z = S + eta * (1.0 + S / depthTerm);
                break;
            }
            case VerticalKind::SigmaG2: {
                const double s = get("s", xs, ys, k), C = get("C", xs, ys, k), hc = get("depth_c", xs, ys, k);
                const double S = (hc * s + depthTerm * C) / (hc + depthTerm);
                z = eta + (eta + depthTerm) * S;
                break;
            }
            case VerticalKind::SCoordinate: {
                const double s = get("s", xs, ys, k), a = get("a", xs, ys, k), b = get("b", xs, ys, k);
                const double hc = get("depth_c", xs, ys, k);
                const double C = (1.0 - b) * std::sinh(a * s) / std::sinh(a) +
                                 b * (std::tanh(a * (s + 0.5)) / (2.0 * std::tanh(0.5 * a)) - 0.5);
                z = eta * (1.0 + s) + hc * s + (depthTerm - hc) * C;
                break;
            }
            default: break;
        }
        return -z;
    }
};

// The finite depths of column (j, i), ascending, with their native level indices.
void sortedColumn(const ColumnDepths& c, std::size_t j, std::size_t i, std::vector<std::pair<double, std::size_t>>& out) {
    out.clear();
    for (std::size_t k = 0; k < c.nk; ++k) {
        double d = c.depth[(k * c.ny + j) * c.nx + i];
        if (std::isfinite(d)) out.emplace_back(d, k);
    }
    std::sort(out.begin(), out.end());
}

}  // namespace

std::vector<FormulaTerm> parseFormulaTerms(const std::string& text, const std::string& what) {
    // Glue "term :" and "term : var" into "term:" tokens first.
    std::vector<std::string> tokens;
    for (const auto& w : words(text)) {
        std::string rest = w;
        while (!rest.empty()) {
            auto colon = rest.find(':');
            if (colon == std::string::npos) {
                tokens.push_back(rest);
                break;
            }
            std::string head = rest.substr(0, colon + 1);
            if (head == ":") {
                if (tokens.empty() || tokens.back().back() == ':')
                    throw InputError(what + ": formula_terms '" + text + "' is malformed: a ':' without a term");
                tokens.back() += ":";
            } else {
                tokens.push_back(head);
            }
            rest = rest.substr(colon + 1);
        }
    }
    std::vector<FormulaTerm> terms;
    for (std::size_t n = 0; n < tokens.size(); n += 2) {  // "term:" then its variable
        const std::string& tok = tokens[n];
        if (tok.back() != ':')
            throw InputError(what + ": formula_terms '" + text + "' is malformed: '" + tok +
                             "' is not of the form 'term:' (expected \"term: variable term: variable ...\")");
        if (n + 1 >= tokens.size() || tokens[n + 1].back() == ':')
            throw InputError(what + ": formula_terms '" + text + "' is malformed: term '" + tok.substr(0, tok.size() - 1) +
                             "' names no variable");
        FormulaTerm t{tok.substr(0, tok.size() - 1), tokens[n + 1]};
        for (const auto& u : terms)
            if (u.term == t.term)
                throw InputError(what + ": formula_terms '" + text + "' is malformed: term '" + t.term + "' comes twice");
        terms.push_back(std::move(t));
    }
    if (terms.empty()) throw InputError(what + ": formula_terms '" + text + "' is empty");
    return terms;
}

std::vector<std::string> formulaTermVariables(const CfSource& file) {
    std::vector<std::string> names;
    for (const auto& v : file.variables()) {
        if (!v.coordinate) continue;  // formula_terms belong to a vertical coordinate variable
        const std::string ft = file.attributeText(v, "formula_terms");
        if (ft.empty()) continue;
        try {
            for (const auto& t : parseFormulaTerms(ft, v.shortName))
                if (t.variable != v.shortName) names.push_back(t.variable);
        } catch (const InputError&) {  // said when the field is read
        }
    }
    return names;
}

std::string ParametricVertical::text() const {
    std::string s = formula;
    if (terms.empty()) return s;
    s += " (";
    for (std::size_t n = 0; n < terms.size(); ++n) s += (n ? ", " : "") + terms[n].term + ": " + terms[n].variable;
    return s + ")";
}

std::optional<ParametricVertical> findParametricVertical(const std::string& path, const CfSource& file,
                                                         const VariableInfo& var, std::size_t verticalDim) {
    const AxisInfo axis = file.axis(var, verticalDim);
    const VariableInfo* cv = axis.coordinateVariable.empty() ? nullptr : findVariable(file, axis.coordinateVariable);
    std::string ft = cv ? trim(file.attributeText(*cv, "formula_terms")) : std::string();
    const std::string sn = lower(trim(axis.standardName));
    const Formula* formula = nullptr;
    for (const auto& f : formulas())
        if (sn == f.standardName) formula = &f;
    if (cv && (formula || !ft.empty())) {
        const std::string what = path + ": vertical coordinate variable '" + cv->shortName + "'";
        if (!formula)
            throw InputError(what + " has formula_terms '" + ft + "' but standard_name '" + axis.standardName +
                             "', not a formula octrace evaluates (" + knownFormulas() + ")");
        if (ft.empty())
            throw InputError(what + " is " + formula->standardName +
                             " but has no formula_terms attribute: its depths cannot be computed (CF Appendix D)");
        ParametricVertical p;
        p.kind = formula->kind;
        p.formula = formula->standardName;
        p.coordinateVariable = cv->shortName;
        p.terms = parseFormulaTerms(ft, what);
        for (const char* need : formula->terms)
            if (std::none_of(p.terms.begin(), p.terms.end(), [&](const FormulaTerm& t) { return t.term == need; }))
                throw InputError(what + ": formula_terms '" + ft + "' lacks term '" + need + "', which " +
                                 formula->standardName + " needs");
        return p;
    }
    // Depths given outright: a variable named in `coordinates` over the vertical dimension and
    // others of the field's, whose attributes say depth or height.
    for (const auto& name : words(var.coordinates)) {
        const VariableInfo* c = findVariable(file, name);
        if (!c || !c->numeric || c->dimNames.size() < 3) continue;
        if (std::find(c->dimNames.begin(), c->dimNames.end(), var.dimNames[verticalDim]) == c->dimNames.end()) continue;
        AxisInfo a;
        a.name = c->shortName;
        a.units = c->units;
        a.standardName = c->standardName;
        a.positive = file.attributeText(*c, "positive");
        a.axis = file.attributeText(*c, "axis");
        AxisClass cls = classifyAxis(a);
        if (cls.role != AxisRole::Vertical) continue;
        ParametricVertical p;
        p.kind = VerticalKind::GivenDepth;
        p.formula = "depths given by " + c->signature();
        p.coordinateVariable = c->shortName;
        p.givenToM = cls.toKm * 1000.0 * (cls.positiveDown ? 1.0 : -1.0);
        return p;
    }
    return std::nullopt;
}

ColumnDepths evaluateColumns(const std::string& path, const CfSource& file, const VariableInfo& var,
                             const ParametricVertical& p, const ColumnSelection& sel, std::uint64_t memoryBudget) {
    ColumnDepths c;
    c.nk = var.dimSizes.at(sel.dim[2]);
    c.ny = sel.y.size();
    c.nx = sel.x.size();
    const std::uint64_t samples = saturatingMultiply(saturatingMultiply(c.nk, c.ny), c.nx);
    checkMemoryBudget(path + ": the depths of variable '" + var.shortName + "' (" + std::to_string(c.nk) +
                          " levels x " + std::to_string(c.ny * c.nx) + " columns)",
                      saturatingMultiply(samples, 2 * sizeof(double) + 1), memoryBudget);
    TermReader reader(path, file, var, p, sel);
    Evaluator e;
    e.kind = p.kind;
    e.givenToM = p.givenToM;
    std::uint64_t termBytes = 0;
    if (p.kind == VerticalKind::GivenDepth) {
        std::uint64_t b = 0;
        e.t.emplace("", reader.read("", b));
        termBytes = b;
    } else {
        for (const auto& f : formulas())
            if (f.kind == p.kind)
                for (const char* term : f.terms) {
                    if (std::string(term) == "k_c") continue;  // checked below, not used (see Evaluator)
                    std::uint64_t b = 0;
                    e.t.emplace(term, reader.read(term, b));
                    termBytes = b > UINT64_MAX - termBytes ? UINT64_MAX : termBytes + b;
                    checkMemoryBudget(path + ": the formula terms of '" + p.coordinateVariable + "'", termBytes,
                                      memoryBudget);
                }
        if (p.kind == VerticalKind::DoubleSigma) {
            std::uint64_t b = 0;
            reader.read("k_c", b);  // a missing or misshapen k_c is refused like any term
        }
    }
    c.depth.assign(std::size_t(samples), kNaN);
    c.top.assign(c.ny * c.nx, kNaN);
    c.bottom.assign(c.ny * c.nx, kNaN);
    for (std::size_t j = 0; j < c.ny; ++j)
        for (std::size_t i = 0; i < c.nx; ++i) {
            double top = kNaN, bottom = kNaN, lo = INFINITY, hi = -INFINITY;
            int order = 0;  // +1 deeper with k, -1 shallower
            bool monotonic = true;
            double previous = kNaN;
            std::size_t finite = 0;
            for (std::size_t k = 0; k < c.nk; ++k) {
                double d = e.depth(sel.x[i], sel.y[j], k, top, bottom);
                c.depth[(k * c.ny + j) * c.nx + i] = d;
                if (!std::isfinite(d)) continue;
                ++finite;
                lo = std::min(lo, d);
                hi = std::max(hi, d);
                if (std::isfinite(previous) && d != previous) {
                    int o = d > previous ? 1 : -1;
                    if (order != 0 && o != order) monotonic = false;
                    order = o;
                }
                previous = d;
            }
            if (p.kind == VerticalKind::GivenDepth) {
                top = lo;
                bottom = hi;
            }
            const std::size_t col = j * c.nx + i;
            if (finite < 2 || !monotonic || !(hi > lo) || !std::isfinite(top) || !std::isfinite(bottom) ||
                !(bottom > top)) {
                if (finite >= 2) ++c.badColumns;
                for (std::size_t k = 0; k < c.nk; ++k) c.depth[(k * c.ny + j) * c.nx + i] = kNaN;
                continue;
            }
            c.top[col] = std::min(top, lo) + 0.0;  // + 0.0: no -0
            c.bottom[col] = std::max(bottom, hi);
        }
    return c;
}

std::vector<double> chooseLattice(const std::string& path, const ColumnDepths& c) {
    // At most ~4096 columns, evenly strided, make the statistics.
    const std::size_t columns = c.ny * c.nx;
    const std::size_t step = std::max<std::size_t>(1, columns / 4096);
    std::vector<std::vector<double>> cols;
    std::vector<std::pair<double, std::size_t>> sorted;
    double top = INFINITY, bottom = -INFINITY;
    for (std::size_t col = 0; col < columns; col += step) {
        if (!std::isfinite(c.top[col])) continue;
        sortedColumn(c, col / c.nx, col % c.nx, sorted);
        std::vector<double> d;
        for (const auto& s : sorted)
            if (d.empty() || s.first > d.back()) d.push_back(s.first);
        if (d.size() < 2) continue;
        top = std::min(top, c.top[col]);
        bottom = std::max(bottom, c.bottom[col]);
        d.insert(d.begin(), c.top[col]);  // the column spans top..bottom: its first and last gaps reach them
        d.push_back(c.bottom[col]);
        cols.push_back(std::move(d));
    }
    if (cols.empty() || !(bottom > top))
        throw EmptyResultError(path + ": no water column with two levels of finite, monotonic depth in the selection");
    const double minStep = (bottom - top) / double(kMaxLatticeLevels - 1);
    std::vector<double> lattice;
    std::vector<double> gaps;
    double d = top;
    while (true) {
        lattice.push_back(d);
        gaps.clear();
        for (const auto& col : cols) {
            if (d < col.front() || d >= col.back()) continue;
            auto it = std::upper_bound(col.begin(), col.end(), d);  // col[p] <= d < col[p+1]
            gaps.push_back(*it - *(it - 1));
        }
        double s = minStep;
        if (!gaps.empty()) {
            auto mid = gaps.begin() + std::ptrdiff_t(gaps.size() / 2);
            std::nth_element(gaps.begin(), mid, gaps.end());
            s = std::max(s, *mid);
        }
        if (d + 1.5 * s >= bottom || lattice.size() + 1 >= kMaxLatticeLevels) {
            lattice.push_back(bottom);
            break;
        }
        d += s;
    }
    return lattice;
}

void resampleColumn(const ColumnDepths& c, std::size_t j, std::size_t i, const double* values, const std::uint8_t* valid,
                    std::size_t stride, const std::vector<double>& depthM, double* out, std::uint8_t* outValid) {
    std::fill(outValid, outValid + depthM.size(), std::uint8_t(0));
    const std::size_t col = j * c.nx + i;
    const double top = c.top[col], bottom = c.bottom[col];
    if (!std::isfinite(top)) return;
    std::vector<std::pair<double, std::size_t>> levels;  // (depth, native k), ascending
    sortedColumn(c, j, i, levels);
    if (levels.empty()) return;
    const double tol = 1e-9 * std::max(1.0, std::abs(bottom));
    auto ok = [&](std::size_t k) { return valid[k * stride] != 0; };
    for (std::size_t n = 0; n < depthM.size(); ++n) {
        const double d = depthM[n];
        if (d < top - tol || d > bottom + tol) continue;
        // the first native level at or below d
        auto below = std::lower_bound(levels.begin(), levels.end(), std::make_pair(d, std::size_t(0)),
                                      [](const auto& a, const auto& b) { return a.first < b.first; });
        if (below == levels.begin() || (below != levels.end() && below->first == d)) {
            // above the shallowest level (its half layer) or exactly on a level
            std::size_t k = below == levels.end() ? levels.back().second : below->second;
            if (ok(k)) {
                out[n] = values[k * stride];
                outValid[n] = 1;
            }
            continue;
        }
        auto above = below - 1;
        if (below == levels.end()) {  // between the deepest level and the floor
            if (ok(above->second)) {
                out[n] = values[above->second * stride];
                outValid[n] = 1;
            }
            continue;
        }
        if (!ok(above->second) || !ok(below->second)) continue;
        const double w = (d - above->first) / (below->first - above->first);
        out[n] = values[above->second * stride] * (1.0 - w) + values[below->second * stride] * w;
        outValid[n] = 1;
    }
}

}  // namespace octrace::io::detail
