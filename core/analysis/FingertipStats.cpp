#include "core/analysis/FingertipStats.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "core/stats/Resampling.h"

namespace activetouch {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct Series {
    std::vector<double> values;  ///< one taxel over one recording's frames
};

double quantile(std::vector<double> v, double q) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    const double at = q * static_cast<double>(v.size() - 1);
    const auto lo = static_cast<std::size_t>(std::floor(at));
    const std::size_t hi = std::min(lo + 1, v.size() - 1);
    return v[lo] + (at - static_cast<double>(lo)) * (v[hi] - v[lo]);
}

double mean(const std::vector<double>& v) {
    double s = 0.0;
    for (double x : v) s += x;
    return v.empty() ? 0.0 : s / static_cast<double>(v.size());
}

double standardDeviation(const std::vector<double>& v) {
    const double m = mean(v);
    double s = 0.0;
    for (double x : v) s += (x - m) * (x - m);
    return v.size() < 2 ? 0.0 : std::sqrt(s / static_cast<double>(v.size() - 1));
}

double correlation(const std::vector<double>& a, const std::vector<double>& b) {
    const double ma = mean(a), mb = mean(b);
    double sab = 0.0, saa = 0.0, sbb = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        sab += (a[i] - ma) * (b[i] - mb);
        saa += (a[i] - ma) * (a[i] - ma);
        sbb += (b[i] - mb) * (b[i] - mb);
    }
    return saa > 0.0 && sbb > 0.0 ? sab / std::sqrt(saa * sbb) : std::nan("");
}

/// What one recording says of one finger: for each taxel its resting frames' readings, and
/// the readings of the frames that were not at rest.
struct FingerInFile {
    std::vector<std::vector<double>> rest, contact;
};

FingerInFile splitFinger(const FramesFile& f, int offset, int taxels, int all, double margin) {
    std::vector<Series> series(static_cast<std::size_t>(taxels));
    for (int k = 0; k < taxels; ++k)
        for (int t = 0; t < f.frames; ++t)
            series[std::size_t(k)].values.push_back(f.at(t, offset + k, all));
    std::vector<double> level;
    for (const Series& s : series) level.push_back(quantile(s.values, 0.1));
    FingerInFile out;
    out.rest.resize(std::size_t(taxels));
    out.contact.resize(std::size_t(taxels));
    for (int t = 0; t < f.frames; ++t) {
        bool resting = true;
        for (int k = 0; k < taxels; ++k)
            resting = resting && series[std::size_t(k)].values[std::size_t(t)] <=
                                     level[std::size_t(k)] + margin;
        for (int k = 0; k < taxels; ++k)
            (resting ? out.rest : out.contact)[std::size_t(k)].push_back(
                series[std::size_t(k)].values[std::size_t(t)]);
    }
    return out;
}

/// Per recording, what each taxel's statistics are built from.
struct TaxelSamples {
    std::vector<double> offsets, sigmas, drifts, contact, restAbove, contactAbove;
    std::vector<std::vector<double>> contactByFile;  ///< each recording's readings under contact
    std::set<double> seen;
    double most = 0.0, least = kInf;
    long long readings = 0, fullScale = 0;
    int restFrames = 0;
};

void addFile(TaxelSamples& s, const std::vector<double>& rest, const std::vector<double>& contact,
             double fullScale) {
    s.restFrames += static_cast<int>(rest.size());
    if (!rest.empty()) {
        s.offsets.push_back(mean(rest));
        const double level = std::round(s.offsets.back());
        for (double x : rest) s.restAbove.push_back(std::max(0.0, x - level));
        for (double x : contact) s.contactAbove.push_back(std::max(0.0, x - level));
    }
    if (rest.size() >= 2) s.sigmas.push_back(standardDeviation(rest));
    if (rest.size() >= 3) {
        const std::size_t third = rest.size() / 3;
        const std::vector<double> first(rest.begin(), rest.begin() + long(third));
        const std::vector<double> last(rest.end() - long(third), rest.end());
        s.drifts.push_back(mean(last) - mean(first));
    }
    s.contact.insert(s.contact.end(), contact.begin(), contact.end());
    if (!contact.empty()) s.contactByFile.push_back(contact);
    for (const auto* v : {&rest, &contact})
        for (double x : *v) {
            s.seen.insert(x);
            s.most = std::max(s.most, x);
            s.least = std::min(s.least, x);
            ++s.readings;
            s.fullScale += x >= fullScale;
        }
}

TaxelStats summarise(const TaxelSamples& s, const std::string& finger, int k, double fullScale) {
    TaxelStats t;
    t.finger = finger;
    t.taxel = k;
    t.restFrames = s.restFrames;
    t.contactFrames = static_cast<int>(s.contact.size());
    t.offset = stats::studentMean(s.offsets, 0.0, fullScale);
    t.sigma = stats::studentMean(s.sigmas, 0.0, kInf);
    t.drift = stats::studentMean(s.drifts, -kInf, kInf);
    double previous = std::nan("");
    for (double v : s.seen) {
        if (!std::isnan(previous) && (t.quantum == 0.0 || v - previous < t.quantum))
            t.quantum = v - previous;
        previous = v;
    }
    t.dead = s.most <= 0.0;
    t.stuck = !t.dead && s.least == s.most;
    t.maxPressure = s.most;
    t.contactP99 = t.contactP99Low = t.contactP99High = quantile(s.contact, 0.99);
    if (s.contactByFile.size() >= 2) {
        stats::ResamplingGenerator draw(0x5eed + static_cast<std::uint64_t>(k));
        std::vector<double> resampled;
        for (int b = 0; b < 200; ++b) {
            std::vector<double> pooled;
            for (std::size_t i = 0; i < s.contactByFile.size(); ++i) {
                const auto& file = s.contactByFile[draw.below(s.contactByFile.size())];
                pooled.insert(pooled.end(), file.begin(), file.end());
            }
            resampled.push_back(quantile(pooled, 0.99));
        }
        const stats::Interval ci = stats::percentileInterval(resampled);
        t.contactP99Low = ci.low;
        t.contactP99High = ci.high;
    }
    t.atFullScale = s.readings > 0 ? double(s.fullScale) / double(s.readings) : 0.0;
    t.restAbove = s.restAbove;
    t.contactAbove = s.contactAbove;
    return t;
}

/// The mean correlation over pairs of taxels of one recording's resting frames (NaN without
/// two taxels that move).
double restCorrelation(const FingerInFile& f) {
    double sum = 0.0;
    int pairs = 0;
    for (std::size_t a = 0; a < f.rest.size(); ++a)
        for (std::size_t b = a + 1; b < f.rest.size(); ++b) {
            const double r = correlation(f.rest[a], f.rest[b]);
            if (std::isfinite(r)) sum += r, ++pairs;
        }
    return pairs > 0 ? sum / pairs : std::nan("");
}

}  // namespace

FingertipStatsReport fingertipStats(const FramesImport& frames, double restMargin) {
    FingertipStatsReport report;
    report.restMargin = restMargin;
    report.files = static_cast<int>(frames.files.size());
    for (const FramesFile& f : frames.files) report.frames += f.frames;
    const FramesLayout& layout = frames.layout;
    const int all = layout.taxelCount();
    int offset = 0;
    for (const auto& finger : layout.fingers) {
        std::vector<TaxelSamples> samples(static_cast<std::size_t>(finger.taxels));
        std::vector<double> correlations;
        for (const FramesFile& f : frames.files) {
            const FingerInFile split = splitFinger(f, offset, finger.taxels, all, restMargin);
            for (int k = 0; k < finger.taxels; ++k)
                addFile(samples[std::size_t(k)], split.rest[std::size_t(k)],
                        split.contact[std::size_t(k)], layout.fullScale);
            if (const double r = restCorrelation(split); std::isfinite(r))
                correlations.push_back(r);
        }
        for (int k = 0; k < finger.taxels; ++k)
            report.taxels.push_back(
                summarise(samples[std::size_t(k)], finger.name, k, layout.fullScale));
        report.fingers.push_back(
            {finger.name, finger.taxels, stats::studentMean(correlations, -1.0, 1.0)});
        offset += finger.taxels;
    }
    return report;
}

}  // namespace activetouch
