#include "core/recognition/PathHistogram.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace activetouch {

PathHistogram pathHistogram(const std::vector<Vec2>& points, int bins) {
    PathHistogram h;
    h.bins = std::max(1, bins);
    h.cells.assign(static_cast<std::size_t>(h.bins * h.bins), 0.0);
    if (points.empty()) return h;
    Vec2 lo = points.front(), hi = points.front();
    for (Vec2 p : points) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
    }
    auto binOf = [&](double v, double a, double b) {
        const double extent = b - a;
        if (!(extent > 1e-9)) return h.bins / 2;  // degenerate: the middle bin
        const int i = static_cast<int>((v - a) / extent * h.bins);
        return std::clamp(i, 0, h.bins - 1);
    };
    const double weight = 1.0 / static_cast<double>(points.size());
    for (Vec2 p : points)
        h.cells[static_cast<std::size_t>(binOf(p.y, lo.y, hi.y) * h.bins +
                                         binOf(p.x, lo.x, hi.x))] += weight;
    return h;
}

PathHistogram smoothed(const PathHistogram& h, double sigma) {
    if (!(sigma > 0)) return h;
    const int n = h.bins;
    const int radius = std::max(1, static_cast<int>(std::ceil(3 * sigma)));
    std::vector<double> kernel(static_cast<std::size_t>(2 * radius + 1));
    for (int i = -radius; i <= radius; ++i)
        kernel[static_cast<std::size_t>(i + radius)] = std::exp(-0.5 * i * i / (sigma * sigma));
    // Separable blur; mass that would leave the grid is dropped, then the rest renormalised.
    std::vector<double> tmp(h.cells.size(), 0.0), out(h.cells.size(), 0.0);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x)
            for (int i = -radius; i <= radius; ++i)
                if (x + i >= 0 && x + i < n)
                    tmp[static_cast<std::size_t>(y * n + x)] +=
                        kernel[static_cast<std::size_t>(i + radius)] *
                        h.cells[static_cast<std::size_t>(y * n + x + i)];
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x)
            for (int i = -radius; i <= radius; ++i)
                if (y + i >= 0 && y + i < n)
                    out[static_cast<std::size_t>(y * n + x)] +=
                        kernel[static_cast<std::size_t>(i + radius)] *
                        tmp[static_cast<std::size_t>((y + i) * n + x)];
    double total = 0.0;
    for (double v : out) total += v;
    PathHistogram s = h;
    for (std::size_t i = 0; i < out.size(); ++i) s.cells[i] = total > 0 ? out[i] / total : 0.0;
    return s;
}

double histogramDistance(const PathHistogram& a, const PathHistogram& b) {
    double sum = 0.0;
    const std::size_t n = std::min(a.cells.size(), b.cells.size());
    for (std::size_t i = 0; i < n; ++i)
        sum += (a.cells[i] - b.cells[i]) * (a.cells[i] - b.cells[i]);
    return std::sqrt(sum);
}

std::vector<Vec2> idealFollowingPath(const Polygon& outline, double offset_mm, double step_mm,
                                     double startAt_mm) {
    const std::vector<Vec2> ring = outline.offsetOutline(offset_mm);
    std::vector<Vec2> path;
    if (!(step_mm > 0)) return path;
    // Walk the offset ring edge by edge, dropping a point every step_mm of arc length.
    double nextAt = std::fmod(std::max(0.0, startAt_mm), step_mm), start = 0.0;
    for (std::size_t e = 0; e < ring.size(); ++e) {
        const Vec2 a = ring[e], b = ring[(e + 1) % ring.size()];
        const double len = distance(a, b);
        while (nextAt < start + len) {
            path.push_back(a + ((nextAt - start) / len) * (b - a));
            nextAt += step_mm;
        }
        start += len;
    }
    return path;
}

PathHistogram idealFollowingHistogram(const Polygon& outline, double offset_mm, double step_mm,
                                      int bins, int phases) {
    phases = std::max(1, phases);
    PathHistogram mean = pathHistogram({}, bins);
    for (int k = 0; k < phases; ++k) {
        const PathHistogram h = pathHistogram(
            idealFollowingPath(outline, offset_mm, step_mm, k * step_mm / phases), bins);
        for (std::size_t i = 0; i < mean.cells.size(); ++i) mean.cells[i] += h.cells[i] / phases;
    }
    return mean;
}

Recognition recognise(const std::vector<Vec2>& path, const std::vector<ShapeTemplate>& templates,
                      double sigma) {
    Recognition r;
    r.raw = pathHistogram(path, templates.empty() ? 20 : templates.front().raw.bins);
    r.smooth = smoothed(r.raw, sigma);
    double best = std::numeric_limits<double>::infinity(), bestSmooth = best;
    for (const auto& t : templates) {
        const double d = histogramDistance(r.raw, t.raw);
        const double ds = histogramDistance(r.smooth, t.smooth);
        r.distances[t.shape] = d;
        r.smoothedDistances[t.shape] = ds;
        if (d < best) {
            best = d;
            r.predicted = t.shape;
        }
        if (ds < bestSmooth) {
            bestSmooth = ds;
            r.predictedSmoothed = t.shape;
        }
    }
    return r;
}

}  // namespace activetouch
