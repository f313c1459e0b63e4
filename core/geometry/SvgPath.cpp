#include "core/geometry/SvgPath.h"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <vector>

#include "core/common/InputError.h"

namespace activetouch {

namespace {

/// Reads path data: commands, numbers and arc flags, with the place of each.
class PathReader {
public:
    PathReader(const std::string& d, const std::string& source, const std::string& place)
        : d_(d), source_(source), place_(place) {}

    void skipSeparators() {
        while (at_ < d_.size() &&
               (std::isspace(static_cast<unsigned char>(d_[at_])) || d_[at_] == ','))
            ++at_;
    }
    bool atEnd() {
        skipSeparators();
        return at_ >= d_.size();
    }
    /// Whether a number (or flag) comes next rather than a command.
    bool numberNext() {
        skipSeparators();
        if (at_ >= d_.size()) return false;
        const char c = d_[at_];
        return std::isdigit(static_cast<unsigned char>(c)) || c == '-' || c == '+' || c == '.';
    }
    char command() {
        skipSeparators();
        const char c = d_[at_];
        if (!std::strchr("MmLlHhVvCcSsQqTtAaZz", c) || c == '\0')
            fail(std::string("unknown command '") + printable(c) +
                 "'; path data knows M L H V C S Q T A Z (and their lower-case relative forms)");
        command_ = c;
        ++at_;
        return c;
    }
    double number() {
        skipSeparators();
        if (at_ >= d_.size()) fail("a number is missing at the end of the path data");
        // The SVG number grammar: sign, digits, a point, digits, an exponent; "-.5.5" is two.
        std::size_t end = at_;
        if (d_[end] == '+' || d_[end] == '-') ++end;
        bool digits = false, point = false;
        while (end < d_.size()) {
            const char c = d_[end];
            if (std::isdigit(static_cast<unsigned char>(c))) {
                digits = true;
            } else if (c == '.' && !point) {
                point = true;
            } else {
                break;
            }
            ++end;
        }
        if (digits && end < d_.size() && (d_[end] == 'e' || d_[end] == 'E')) {
            std::size_t e = end + 1;
            if (e < d_.size() && (d_[e] == '+' || d_[e] == '-')) ++e;
            if (e < d_.size() && std::isdigit(static_cast<unsigned char>(d_[e]))) {
                while (e < d_.size() && std::isdigit(static_cast<unsigned char>(d_[e]))) ++e;
                end = e;
            }
        }
        if (!digits) fail(std::string("expected a number, found '") + printable(d_[at_]) + "'");
        const double v = std::strtod(d_.substr(at_, end - at_).c_str(), nullptr);
        if (!std::isfinite(v) || std::abs(v) > kMaxSvgCoordinate_mm)
            fail("the number " + d_.substr(at_, std::min<std::size_t>(end - at_, 24)) +
                 " is beyond what an outline on the stage can use (|value| <= " +
                 std::to_string(static_cast<int>(kMaxSvgCoordinate_mm)) + " mm)");
        at_ = end;
        return v;
    }
    bool flag() {
        skipSeparators();
        if (at_ >= d_.size() || (d_[at_] != '0' && d_[at_] != '1'))
            fail("an arc flag must be 0 or 1");
        return d_[at_++] == '1';
    }
    [[noreturn]] void fail(const std::string& problem) const {
        throw InputError(source_,
                         place_ + ", character " + std::to_string(at_ + 1) +
                             (command_ ? std::string(" (command ") + command_ + ")" : ""),
                         problem);
    }
    [[noreturn]] void failWhole(const std::string& problem) const {
        throw InputError(source_, place_, problem);
    }

private:
    static std::string printable(char c) {
        return std::isprint(static_cast<unsigned char>(c)) ? std::string(1, c)
                                                           : "\\x" + std::to_string(int(c));
    }
    const std::string& d_;
    const std::string& source_;
    const std::string& place_;
    std::size_t at_ = 0;
    char command_ = 0;
};

/// Points along a curve, appended without its start (the current point).
class Flattener {
public:
    explicit Flattener(double tolerance) : tolerance_(tolerance) {}

    void cubic(std::vector<Vec2>& out, Vec2 p0, Vec2 p1, Vec2 p2, Vec2 p3, int depth = 0) const {
        // Flat enough when both control points lie within the tolerance of the chord.
        const double d1 = distanceToLine(p1, p0, p3), d2 = distanceToLine(p2, p0, p3);
        if (depth >= 18 || std::max(d1, d2) <= tolerance_) {
            out.push_back(p3);
            return;
        }
        const Vec2 a = mid(p0, p1), b = mid(p1, p2), c = mid(p2, p3);
        const Vec2 ab = mid(a, b), bc = mid(b, c), m = mid(ab, bc);
        cubic(out, p0, a, ab, m, depth + 1);
        cubic(out, m, bc, c, p3, depth + 1);
    }
    void quadratic(std::vector<Vec2>& out, Vec2 p0, Vec2 c, Vec2 p2) const {
        cubic(out, p0, p0 + (2.0 / 3.0) * (c - p0), p2 + (2.0 / 3.0) * (c - p2), p2);
    }
    /// The SVG elliptical arc from `p0` to `p1` (endpoint parameterisation, SVG 1.1 F.6.5).
    /// Returns a problem instead of points when the ellipse, grown as SVG prescribes to reach
    /// `p1`, would lie beyond kMaxSvgCoordinate_mm or need more than kMaxOutlineVertices points.
    std::optional<std::string> arc(std::vector<Vec2>& out, Vec2 p0, double rx, double ry,
                                   double rotationDeg, bool large, bool sweep, Vec2 p1) const {
        if (p0 == p1) return std::nullopt;  // an arc to where it is: nothing
        rx = std::abs(rx);
        ry = std::abs(ry);
        if (rx == 0.0 || ry == 0.0) {
            out.push_back(p1);  // a straight line, as SVG says
            return std::nullopt;
        }
        const double phi = rotationDeg * M_PI / 180.0, cp = std::cos(phi), sp = std::sin(phi);
        const double dx = 0.5 * (p0.x - p1.x), dy = 0.5 * (p0.y - p1.y);
        const double x1 = cp * dx + sp * dy, y1 = -sp * dx + cp * dy;
        // Worked in the frame where the ellipse is a circle of radius rx (y divided by ry / rx),
        // with ratios and hypot instead of squared radii, so that radii from 1e-300 to 1e300
        // neither underflow nor overflow: the arc is the one SVG specifies at every scale.
        const double aspect = ry / rx;
        if ((aspect == 0.0 && y1 == 0.0) || (std::isinf(aspect) && x1 == 0.0)) {
            out.push_back(p1);  // an ellipse flat beyond doubles, along the chord: the chord
            return std::nullopt;
        }
        const double y1c = y1 == 0.0 ? 0.0 : y1 / aspect;
        const double half = std::hypot(x1, y1c);  // half the chord, in the circle's frame
        // Radii too small for the endpoints grow until they reach (lambda > 1).
        double r = std::max(rx, half);
        if (!std::isfinite(r) || !std::isfinite(aspect) || aspect == 0.0 ||
            std::max(r, r * aspect) > kMaxSvgCoordinate_mm)
            return "the arc's radii, grown to reach its end point as SVG prescribes, exceed " +
                   std::to_string(static_cast<int>(kMaxSvgCoordinate_mm)) +
                   " mm; give radii closer in proportion to the distance between its ends";
        // The centre lies k * half from the chord's middle, across it: k = sqrt((r/half)^2 - 1).
        const double over = half > 0.0 ? r / half : 1.0;
        double k = std::sqrt(std::max(0.0, (over - 1.0) * (over + 1.0)));
        if (large == sweep) k = -k;
        const double cxc = k * y1c, cyc = -k * x1;
        const double cx1 = cxc, cy1 = cyc * aspect;
        const Vec2 centre{cp * cx1 - sp * cy1 + 0.5 * (p0.x + p1.x),
                          sp * cx1 + cp * cy1 + 0.5 * (p0.y + p1.y)};
        auto angle = [](double ux, double uy, double vx, double vy) {
            return std::atan2(ux * vy - uy * vx, ux * vx + uy * vy);
        };
        const double theta = angle(1, 0, (x1 - cxc) / r, (y1c - cyc) / r);
        double delta = angle((x1 - cxc) / r, (y1c - cyc) / r, (-x1 - cxc) / r, (-y1c - cyc) / r);
        if (!sweep && delta > 0) delta -= 2 * M_PI;
        if (sweep && delta < 0) delta += 2 * M_PI;
        rx = r;
        ry = r * aspect;
        // Steps whose sagitta on the larger radius stays within the tolerance.
        // 1 - cos(step / 2) = tolerance / r, written so that it stays above zero for large r.
        r = std::max(rx, ry);
        const double step =
            r > 0.5 * tolerance_ ? 4.0 * std::asin(std::sqrt(0.5 * tolerance_ / r)) : M_PI / 2;
        const double steps = std::ceil(std::abs(delta) / std::min(step, M_PI / 2));
        if (!(steps <= static_cast<double>(kMaxOutlineVertices)))
            return "the arc needs more than " + std::to_string(kMaxOutlineVertices) +
                   " vertices at this tolerance; give a coarser tolerance or a simpler path";
        const int n = std::max(1, static_cast<int>(steps));
        for (int i = 1; i <= n; ++i) {
            const double t = theta + delta * i / n;
            const double ex = rx * std::cos(t), ey = ry * std::sin(t);
            out.push_back(
                i == n ? p1 : Vec2{cp * ex - sp * ey + centre.x, sp * ex + cp * ey + centre.y});
        }
        return std::nullopt;
    }

private:
    static Vec2 mid(Vec2 a, Vec2 b) { return 0.5 * (a + b); }
    static double distanceToLine(Vec2 p, Vec2 a, Vec2 b) {
        const Vec2 ab = b - a;
        const double length = std::hypot(ab.x, ab.y);
        if (length == 0.0) return std::hypot(p.x - a.x, p.y - a.y);
        return std::abs(ab.x * (p.y - a.y) - ab.y * (p.x - a.x)) / length;
    }
    double tolerance_;
};

}  // namespace

namespace {

/// The points a path's commands draw, one command's parameters at a time.
class PathTracer {
public:
    PathTracer(PathReader& in, double tolerance_mm) : in_(in), flat_(tolerance_mm) {}

    /// The next command with every parameter group that follows it.
    void command() {
        const char c = in_.command();
        relative_ = std::islower(static_cast<unsigned char>(c));
        const char C = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
        if (!begun && C != 'M') in_.fail("path data must begin with a move (M)");
        if (closed && C != 'Z') in_.fail("a second outline after Z; give one closed outline");
        bool first = true;
        do {
            group(C, first);
            previous_ = C == 'M' && !first ? 'L' : C;
            first = false;
            if (points.size() > kMaxOutlineVertices)
                in_.fail("the outline needs more than " + std::to_string(kMaxOutlineVertices) +
                         " vertices at this tolerance; give a coarser tolerance or a simpler path");
        } while (C != 'Z' && in_.numberNext());
        if (C == 'Z' && in_.numberNext()) in_.fail("Z takes no numbers");
    }

    std::vector<Vec2> points;
    Vec2 start;
    bool closed = false, begun = false;

private:
    Vec2 point() {
        const double x = in_.number(), y = in_.number();
        return relative_ ? current_ + Vec2{x, y} : Vec2{x, y};
    }
    /// S and T: the last control point reflected through the current point if the previous
    /// command was one of `kinds` (a curve of the same order), else the current point.
    Vec2 smoothControl(const char* kinds) const {
        return previous_ && std::strchr(kinds, previous_) ? 2.0 * current_ - lastControl_
                                                          : current_;
    }
    void lineTo(Vec2 p) {
        current_ = p;
        points.push_back(current_);
    }
    void cubicTo(Vec2 c1, Vec2 c2, Vec2 end) {
        flat_.cubic(points, current_, c1, c2, end);
        lastControl_ = c2;
        current_ = end;
    }
    void quadraticTo(Vec2 control, Vec2 end) {
        flat_.quadratic(points, current_, control, end);
        lastControl_ = control;
        current_ = end;
    }
    void arcTo() {
        const double rx = in_.number(), ry = in_.number(), rotation = in_.number();
        const bool large = in_.flag(), sweep = in_.flag();
        const Vec2 end = point();
        if (auto problem = flat_.arc(points, current_, rx, ry, rotation, large, sweep, end))
            in_.fail(*problem);
        current_ = end;
    }

    /// One parameter group of command `C`; `first` for the group right after the letter.
    void group(char C, bool first) {
        switch (C) {
            case 'M':
                if (!first) return lineTo(point());  // further pairs after a move are lines
                if (begun && points.size() == 1) {
                    // A move right after a move draws nothing: the subpath starts at the second.
                    current_ = point();
                    points.back() = start = current_;
                    return;
                }
                if (begun) in_.fail("a second move (M): give one closed outline per object");
                begun = true;
                lineTo(point());
                start = current_;
                return;
            case 'L':
                return lineTo(point());
            case 'H': {
                const double x = in_.number();
                return lineTo({relative_ ? current_.x + x : x, current_.y});
            }
            case 'V': {
                const double y = in_.number();
                return lineTo({current_.x, relative_ ? current_.y + y : y});
            }
            case 'C': {
                const Vec2 c1 = point(), c2 = point();
                return cubicTo(c1, c2, point());
            }
            case 'S': {
                const Vec2 c1 = smoothControl("CS"), c2 = point();
                return cubicTo(c1, c2, point());
            }
            case 'Q': {
                const Vec2 control = point();
                return quadraticTo(control, point());
            }
            case 'T': {
                const Vec2 control = smoothControl("QT");
                return quadraticTo(control, point());
            }
            case 'A':
                return arcTo();
            case 'Z':
                closed = true;
                current_ = start;
                return;
        }
    }

    PathReader& in_;
    const Flattener flat_;
    bool relative_ = false;
    Vec2 current_, lastControl_;
    char previous_ = 0;
};

/// The traced points as an outline: the closing vertex that repeats the first and repeated
/// points (a zero-length segment) left out.
std::vector<Vec2> outlineOf(const std::vector<Vec2>& points, double tolerance_mm) {
    std::vector<Vec2> outline;
    for (const Vec2& p : points) {
        if (!outline.empty()) {
            const Vec2 step = p - outline.back();
            if (std::hypot(step.x, step.y) <= 1e-9) continue;
        }
        outline.push_back(p);
    }
    while (outline.size() > 1) {
        const Vec2 gap = outline.back() - outline.front();
        if (std::hypot(gap.x, gap.y) > std::max(1e-9, 0.5 * tolerance_mm)) break;
        outline.pop_back();
    }
    return outline;
}

}  // namespace

Polygon polygonFromSvgPath(const std::string& d, double tolerance_mm, const std::string& source,
                           const std::string& place) {
    PathReader in(d, source, place);
    if (!(tolerance_mm > 0.0) || !std::isfinite(tolerance_mm))
        in.failWhole("the flattening tolerance must be a positive number of mm");
    if (in.atEnd()) in.failWhole("the path data is empty; give one closed outline (M ... Z)");
    PathTracer trace(in, tolerance_mm);
    while (!in.atEnd()) trace.command();
    // Closed by Z, or by ending where it began (within the tolerance).
    if (!trace.closed) {
        const Vec2 gap = trace.points.back() - trace.start;
        if (std::hypot(gap.x, gap.y) > tolerance_mm)
            in.failWhole("the path does not close: end it with Z, or where it began");
    }
    std::vector<Vec2> outline = outlineOf(trace.points, tolerance_mm);
    if (auto problem = Polygon::problemWith(outline))
        in.failWhole("the outline it draws cannot be an object: " + *problem);
    return Polygon(std::move(outline));
}

}  // namespace activetouch
