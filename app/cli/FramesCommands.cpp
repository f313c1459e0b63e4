// import-frames and fingertip-stats: real skin recordings in other layouts read in, and what they
// say of the fingertips' taxels (docs/real-fingertips.md).
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "app/cli/CliSupport.h"
#include "app/cli/CommandLine.h"
#include "app/cli/Commands.h"
#include "app/cli/FingertipComparison.h"
#include "app/figures/FigureExport.h"
#include "app/figures/FingertipFigures.h"
#include "app/figures/Installation.h"
#include "core/analysis/FingertipStats.h"
#include "core/common/InputError.h"
#include "core/io/FileDigest.h"
#include "core/io/OutputFile.h"
#include "core/records/FramesImport.h"
#include "core/run/OutputFiles.h"
#include "qcustomplot.h"

namespace activetouch::cli {

namespace fs = std::filesystem;

namespace {

/// Whether `dir` may be written: new or empty, or holding `marker` and --replace given.
std::string folderProblem(const std::string& dir, const char* marker, bool replace) {
    if (!fs::exists(dir)) return {};
    if (!fs::is_directory(dir)) return dir + " is a file, not a folder";
    if (fs::is_empty(dir)) return {};
    if (!fs::exists(fs::path(dir) / marker))
        return dir + " holds other files; choose an empty or new folder";
    if (!replace) return dir + " already holds " + marker + "; give --replace to write it again";
    return {};
}

Json statsJson(const FingertipStatsReport& r) {
    auto interval = [](const stats::MeanInterval& m) {
        return Json{{"mean", m.mean}, {"low", m.low}, {"high", m.high}};
    };
    Json taxels = Json::array(), fingers = Json::array();
    for (const TaxelStats& t : r.taxels)
        taxels.push_back(
            {{"finger", t.finger},
             {"taxel", t.taxel},
             {"rest_frames", t.restFrames},
             {"contact_frames", t.contactFrames},
             {"offset_counts", interval(t.offset)},
             {"sigma_counts", interval(t.sigma)},
             {"quantum_counts", t.quantum},
             {"drift_counts", interval(t.drift)},
             {"dead", t.dead},
             {"stuck", t.stuck},
             {"max_counts", t.maxPressure},
             {"contact_p99_counts",
              {{"value", t.contactP99}, {"low", t.contactP99Low}, {"high", t.contactP99High}}},
             {"at_full_scale", t.atFullScale}});
    for (const FingerStats& f : r.fingers)
        fingers.push_back(
            {{"finger", f.finger}, {"rest_correlation", interval(f.restCorrelation)}});
    return {{"files", r.files},
            {"frames", r.frames},
            {"rest_margin_counts", r.restMargin},
            {"taxels", taxels},
            {"fingers", fingers}};
}

void printStats(const FingertipStatsReport& r) {
    std::printf(
        "%d recordings, %d frames; at rest: every taxel of the finger within %g counts of "
        "its resting level (95 %% intervals over the recordings)\n",
        r.files, r.frames, r.restMargin);
    std::printf("%-8s %5s %6s %-22s %-20s %5s %-20s %6s %-18s %s\n", "finger", "taxel", "rest",
                "offset (counts)", "sigma (counts)", "step", "drift (counts)", "max",
                "p99 under contact", "state");
    for (const TaxelStats& t : r.taxels) {
        char offset[64], sigma[64], drift[64], p99[64];
        std::snprintf(p99, sizeof p99, "%.0f (%.0f-%.0f)", t.contactP99, t.contactP99Low,
                      t.contactP99High);
        std::snprintf(offset, sizeof offset, "%.2f (%.2f-%.2f)", t.offset.mean, t.offset.low,
                      t.offset.high);
        std::snprintf(sigma, sizeof sigma, "%.3f (%.3f-%.3f)", t.sigma.mean, t.sigma.low,
                      t.sigma.high);
        std::snprintf(drift, sizeof drift, "%+.2f (%+.2f..%+.2f)", t.drift.mean, t.drift.low,
                      t.drift.high);
        std::printf("%-8s %5d %6d %-22s %-20s %5g %-20s %6g %-18s %s\n", t.finger.c_str(), t.taxel,
                    t.restFrames, offset, sigma, t.quantum, drift, t.maxPressure, p99,
                    t.dead              ? "dead"
                    : t.stuck           ? "stuck"
                    : t.atFullScale > 0 ? "saturates"
                                        : "ok");
    }
    for (const FingerStats& f : r.fingers)
        std::printf(
            "%s: resting taxels move together with a mean correlation of %.2f "
            "(%.2f-%.2f)\n",
            f.finger.c_str(), f.restCorrelation.mean, f.restCorrelation.low,
            f.restCorrelation.high);
}

}  // namespace

int commandImportFrames(const std::vector<std::string>& args) {
    const CommandLine line = parseCommandLine(
        {{{"--out", "a folder for frames.csv and frames.json"}}, {"--replace"}}, args);
    if (!line.error.empty()) return usageError(line.error);
    if (line.positional.size() < 2)
        return usageError("import-frames takes a layout file and one or more recordings");
    const std::string out = line.value("--out");
    if (out.empty()) return usageError("import-frames needs --out <folder>");
    if (const std::string p = folderProblem(out, "frames.json", line.has("--replace")); !p.empty())
        return usageError(p);
    try {
        FramesImport frames;
        frames.layoutDocument = readJsonFile(line.positional[0]);
        frames.layout = parseFramesLayout(frames.layoutDocument, line.positional[0]);
        std::vector<std::string> digests;
        long long count = 0;
        for (std::size_t i = 1; i < line.positional.size(); ++i) {
            frames.files.push_back(readFramesFile(frames.layout, line.positional[i]));
            digests.push_back(sha256OfFile(line.positional[i]));
            count += frames.files.back().frames;
        }
        ensureOutputDirectory(out);
        writeFramesImport(out, frames, digests);
        std::printf("%lld frames of %d taxels (%zu fingers) from %zu files; wrote %s\n", count,
                    frames.layout.taxelCount(), frames.layout.fingers.size(), frames.files.size(),
                    (fs::path(out) / "frames.csv").string().c_str());
        return kOk;
    } catch (const InputError& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return kBadInput;
    }
}

namespace {

/// The scenes to compare with: --scenes (comma-separated), else the paper's.
std::vector<std::string> scenesToCompare(const CommandLine& line) {
    std::vector<std::string> out;
    std::string list = line.value("--scenes");
    if (list.empty())
        list = (fs::path(experimentsDirectory().toStdString()) / "scenes" / "paper_rectangle.json")
                   .string();
    std::size_t start = 0;
    while (start <= list.size()) {
        const std::size_t comma = std::min(list.find(',', start), list.size());
        if (comma > start) out.push_back(list.substr(start, comma - start));
        start = comma + 1;
    }
    return out;
}

/// `path` relative to the working folder where it lies inside it (as a command names it).
std::string shownPath(const std::string& path) {
    std::error_code error;
    const fs::path relative = fs::relative(path, fs::current_path(), error);
    return error || relative.empty() || *relative.begin() == ".." ? path : relative.string();
}

/// Writes the scene `report`'s finger calls for to `path`, from the first scene compared.
void writeMeasuredScene(const std::string& path, const std::string& base,
                        const FramesImport& frames, const FingertipStatsReport& report,
                        const std::string& finger, const std::string& importDir) {
    const std::string provenance =
        frames.layout.about + " Measured from " + std::to_string(report.files) + " recordings (" +
        std::to_string(report.frames) +
        " frames; the files and their SHA-256 "
        "in the import's frames.json) by: activetouch-cli import-frames " +
        frames.layout.source + " <recordings> --out " + importDir +
        "; activetouch-cli fingertip-stats " + importDir + " --finger " + finger +
        " --write-scene " + path + ". Everything not measured is as in " + shownPath(base) + ".";
    const Json scene = measuredScene(readJsonFile(base), report, finger, provenance);
    parseScene(scene, path, "", fs::path(base).parent_path().string());  // it must read back
    writeJsonAtomically(path, scene);
    std::printf("wrote %s\n", path.c_str());
}

/// figures/fingertip_stats.{png,pdf,svg} in `out`; whether they were written.
bool drawFingertipFigure(int argc, char** argv, const std::string& out,
                         const FingertipStatsReport& report, const std::string& finger,
                         const std::vector<SceneComparison>& comparisons) {
    FingertipFigureData data;
    data.finger = QString::fromStdString(finger);
    for (const TaxelStats* t : taxelsOf(report, finger)) {
        data.sigma.push_back(t->sigma.mean);
        data.sigmaLow.push_back(t->sigma.low);
        data.sigmaHigh.push_back(t->sigma.high);
    }
    QString close;
    for (const SceneComparison& c : comparisons) {
        int within = 0;
        for (double d : c.ks) within += d <= 0.1;
        const QString name = QString::fromStdString(fs::path(c.scene).stem().string());
        data.scenes.push_back({QString("%1 (sigma %2)").arg(name).arg(c.sigma), c.sigma, c.ks});
        close += QString("%1%2: %3 of %4 within 0.1")
                     .arg(close.isEmpty() ? "" : "; ", name)
                     .arg(within)
                     .arg(c.ks.size());
    }
    data.caption = QString(
                       "%1 recordings, %2 frames; resting readings above each recording's (or "
                       "tap's) resting level, clipped at 0. %3.")
                       .arg(report.files)
                       .arg(report.frames)
                       .arg(close);
    QStringList written;
    drawFigures(argc, argv, [&] {
        QCustomPlot plot;
        if (buildFingertipFigure(plot, data))
            written = exportFigure(
                plot, figuresDirectory(QString::fromStdString(out)) + "/fingertip_stats",
                {"png", "pdf", "svg"}, FigureSize::physical(kDoubleColumn_mm, 80, kFigureDpi));
    });
    return !written.isEmpty();
}

double restMarginOf(const CommandLine& line) {
    const std::string& text = line.value("--rest-margin");
    if (text.empty()) return 3.0;
    char* end = nullptr;
    const double margin = std::strtod(text.c_str(), &end);
    if (end != text.c_str() + text.size() || !(margin > 0.0 && margin < 1e6)) return -1.0;
    return margin;
}

}  // namespace

int commandFingertipStats(const std::vector<std::string>& args, int argc, char** argv) {
    const CommandLine line =
        parseCommandLine({{{"--out", "a folder for the statistics"},
                           {"--rest-margin", "counts"},
                           {"--finger", "the finger to compare with simulated fingertips"},
                           {"--scenes", "scene files, separated by commas"},
                           {"--write-scene", "a scene file to write"}},
                          {"--replace"}},
                         args);
    if (!line.error.empty()) return usageError(line.error);
    if (line.positional.size() != 1)
        return usageError("fingertip-stats takes one folder that import-frames wrote");
    const std::string out = line.value("--out");
    if (!out.empty())
        if (const std::string p = folderProblem(out, "fingertip_stats.json", line.has("--replace"));
            !p.empty())
            return usageError(p);
    const double margin = restMarginOf(line);
    if (margin < 0.0) return usageError("--rest-margin takes a number of counts above 0");
    const std::string finger = line.value("--finger").empty() ? "index" : line.value("--finger");
    try {
        const FramesImport frames = readFramesImport(line.positional[0]);
        const FingertipStatsReport report = fingertipStats(frames, margin);
        printStats(report);
        std::vector<std::string> scenes = scenesToCompare(line);
        const std::string written = line.value("--write-scene");
        if (!written.empty()) {
            writeMeasuredScene(written, scenes.front(), frames, report, finger, line.positional[0]);
            scenes.push_back(written);
        }
        const std::vector<SceneComparison> comparisons = compareWithScenes(report, finger, scenes);
        printComparison(comparisons, finger, realPressedQuantiles(report, finger));
        if (!out.empty()) {
            ensureOutputDirectory(out);
            writeJsonAtomically((fs::path(out) / "fingertip_stats.json").string(),
                                statsJson(report));
            const bool drawn = !line.has("--no-figures") &&
                               drawFingertipFigure(argc, argv, out, report, finger, comparisons);
            std::printf("wrote %s%s\n", (fs::path(out) / "fingertip_stats.json").string().c_str(),
                        drawn ? " and figures/fingertip_stats.{png,pdf,svg}" : "");
        }
        return kOk;
    } catch (const InputError& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return kBadInput;
    }
}

}  // namespace activetouch::cli
