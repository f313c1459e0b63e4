#include <unistd.h>

#include <QStringList>
#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "app/cli/CliSupport.h"
#include "app/cli/Commands.h"
#include "app/figures/CalibrationFigures.h"
#include "app/figures/FigureExport.h"
#include "core/common/InputError.h"
#include "core/common/NumberText.h"
#include "core/experiment/Experiment.h"
#include "core/io/OutputFile.h"
#include "core/records/TapCsv.h"
#include "core/run/ExperimentRun.h"
#include "core/run/OutputFiles.h"
#include "core/run/RunFolder.h"
#include "devices/simulated/SceneFit.h"
#include "devices/simulated/SimulatedWorld.h"
#include "qcustomplot.h"

namespace activetouch::cli {

namespace fs = std::filesystem;

namespace {

Json validationJson(const ValidationResult& v) {
    Json byPosition = Json::array();
    for (std::size_t p = 0; p < v.angleMean.size(); ++p)
        byPosition.push_back({{"position", p + 1},
                              {"angle_error_deg", v.angleMean[p]},
                              {"position_error_mm", v.positionMean[p]}});
    return {{"angle_error_deg_mean", v.angleError_deg},
            {"position_error_mm_mean", v.positionError_mm},
            {"correct_fraction", v.correctFraction},
            {"by_position", byPosition}};
}

/// The gains test's readings: null for a taxel not read.
Json holdGainsJson(const SceneFit& fit) {
    Json gains = Json::array(), errors = Json::array();
    for (std::size_t k = 0; k < fit.holdGains.size(); ++k) {
        const bool read = std::isfinite(fit.holdGains[k]) && fit.holdGainLogSe[k] > 0;
        gains.push_back(read ? Json(fit.holdGains[k]) : Json());
        errors.push_back(read ? Json(fit.holdGainLogSe[k]) : Json());
    }
    return {{"touching_taps", fit.holdTaps},
            {"relative_gains", gains},
            {"log_standard_errors", errors},
            {"moment_fit_statistic", fit.momentGainsQ}};
}

/// What the recording shows that the fitted scene does not, as the report keeps it.
Json unmodelledJson(const SceneFit& fit) {
    Json out = Json::array();
    for (const Unmodelled& u : fit.unmodelled)
        out.push_back(
            {{"statistic", u.statistic},
             {"recorded", u.recorded},
             {"simulated",
              {{"mean", u.simulatedMean}, {"min", u.simulatedLeast}, {"max", u.simulatedLargest}}},
             {"z", u.z},
             {"suggests", u.explanation}});
    return out;
}

/// The report written beside the fitted scene.
Json calibrationReport(const std::string& recording, const SceneSpec& base, const SceneFit& fit,
                       const SceneFitSettings& settings, const Figure6Comparison& figure6,
                       const std::string& simulatedPath) {
    Json parameters = Json::array(), choices = Json::array(), taxels = Json::array();
    for (const auto& p : fit.parameters)
        parameters.push_back({{"effect", p.effect},
                              {"parameter", p.parameter},
                              {"value", p.value},
                              {"standard_error", p.standardError},
                              {"ci95", {p.low, p.high}}});
    for (const auto& ch : fit.choices)
        choices.push_back({{"effect", ch.effect},
                           {"listed", ch.listed},
                           {"estimated", ch.estimated},
                           {"test", ch.test},
                           {"statistic", ch.statistic},
                           {"threshold", ch.threshold}});
    for (const auto& tf : fit.taxels)
        taxels.push_back({{"taxel", tf.taxel},
                          {"ks", tf.ks},
                          {"ks_match_at_most", tf.ksMatch},
                          {"wasserstein_counts", tf.wasserstein},
                          {"matches", tf.matches}});
    return {
        {"recording", recording},
        {"base_scene", base.source},
        {"taps", fit.taps},
        {"samples_over_nothing", fit.nothingSamples},
        {"method", "simulated moments at the recorded poses; standard errors from " +
                       std::to_string(settings.bootstrapReplicates) +
                       " recordings simulated with the estimate; effects listed at level " +
                       numberText(settings.alpha)},
        {"level", settings.alpha},
        {"bootstrap_replicates", settings.bootstrapReplicates},
        {"parameters", parameters},
        {"dead_taxels", fit.deadTaxels},
        {"pressure_level",
         {{"value", fit.pressureScale},
          {"ci95", {fit.pressureScaleLow, fit.pressureScaleHigh}},
          {"differs", fit.pressureScaleDiffers}}},
        {"choices", choices},
        {"gains_from_holds", holdGainsJson(fit)},
        {"goodness_of_fit", taxels},
        {"unmodelled", unmodelledJson(fit)},
        {"figure6",
         {{"recorded", validationJson(figure6.recorded)},
          {"simulated_first", validationJson(figure6.simulated.front())},
          {"simulated_recordings", figure6.simulated.size()},
          {"simulated_angle_error_deg",
           {{"mean", figure6.angleMean},
            {"min", figure6.angleLeast},
            {"max", figure6.angleLargest}}},
          {"simulated_position_error_mm",
           {{"mean", figure6.positionMean},
            {"min", figure6.positionLeast},
            {"max", figure6.positionLargest}}},
          {"recorded_inside_simulated_range", figure6.recordedInsideRange}}},
        {"simulated_taps", simulatedPath},
    };
}

/// What the fit chose and estimated, as the command prints it.
void printEstimates(const SceneFit& fit) {
    std::printf("%-20s %-8s %s\n", "effect", "listed", "test (statistic against threshold)");
    for (const auto& ch : fit.choices) {
        if (ch.estimated)
            std::printf("%-20s %-8s %s: %.3g against %.3g\n", ch.effect.c_str(),
                        ch.listed ? "yes" : "no", ch.test.c_str(), ch.statistic, ch.threshold);
        else
            std::printf("%-20s %-8s %s\n", ch.effect.c_str(), "kept", ch.test.c_str());
    }
    for (const auto& p : fit.parameters)
        std::printf("  %s.%s = %.4g +/- %.2g (95 %% %.4g to %.4g)\n", p.effect.c_str(),
                    p.parameter.c_str(), p.value, p.standardError, p.low, p.high);
    if (!fit.deadTaxels.empty()) {
        std::printf("  dead taxels:");
        for (int k : fit.deadTaxels) std::printf(" %d", k);
        std::printf(" (reading %g)\n", fit.deadReading);
    }
    std::printf("  pressure level against the scene's: %.3f (95 %% %.3f to %.3f)%s\n",
                fit.pressureScale, fit.pressureScaleLow, fit.pressureScaleHigh,
                fit.pressureScaleDiffers && !fit.lists("taxel_gain")
                    ? ": the taps press every taxel differently from the scene's tapper (its "
                      "stop depth, latency or stroke, or a skin uniformly more or less "
                      "sensitive); not fitted"
                    : "");
}

/// How well the fitted scene reproduces the recording, as the command prints it.
void printGoodness(const SceneFit& fit, const Figure6Comparison& figure6) {
    std::printf(
        "  gains from the %d touching taps' holds, relative to one another "
        "(x/ one standard error):",
        fit.holdTaps);
    for (std::size_t k = 0; k < fit.holdGains.size(); ++k) {
        std::printf("%s", k % 4 == 0 ? "\n   " : "");
        if (std::isfinite(fit.holdGains[k]) && fit.holdGainLogSe[k] > 0)
            std::printf("  taxel %2zu: %.3f x/ %.3f", k, fit.holdGains[k],
                        std::exp(fit.holdGainLogSe[k]));
        else
            std::printf("  taxel %2zu: not read       ", k);
    }
    std::printf(
        "\n  the same test on the moment fit's gains: %.3g (a stroke on another "
        "schedule than the scene's moves these)\n",
        fit.momentGainsQ);
    int matching = 0;
    for (const auto& tf : fit.taxels) matching += tf.matches;
    std::printf(
        "goodness of fit: %d of %zu taxels' readings match the fitted scene's "
        "(Kolmogorov-Smirnov within what two simulations of it differ by)\n",
        matching, fit.taxels.size());
    for (const auto& tf : fit.taxels)
        std::printf("  taxel %2d: KS %.3f (match at most %.3f), Wasserstein %.3f counts%s\n",
                    tf.taxel, tf.ks, tf.ksMatch, tf.wasserstein, tf.matches ? "" : "  <- differs");
    std::printf(
        "Figure 6 recorded: angle %.2f deg, position %.3f mm; over %zu recordings simulated "
        "with the fitted scene: angle %.2f (%.2f to %.2f) deg, position %.3f (%.3f to %.3f) "
        "mm: the recording's lie %s their range\n",
        figure6.recorded.angleError_deg, figure6.recorded.positionError_mm,
        figure6.simulated.size(), figure6.angleMean, figure6.angleLeast, figure6.angleLargest,
        figure6.positionMean, figure6.positionLeast, figure6.positionLargest,
        figure6.recordedInsideRange ? "inside" : "outside");
    if (fit.unmodelled.empty()) {
        std::printf(
            "the recording shows nothing the fitted scene does not produce (on the pile at "
            "each taxel's top, the upper tail, what is held after the top, the resting "
            "level's persistence)\n");
        return;
    }
    for (const Unmodelled& u : fit.unmodelled)
        std::printf(
            "caution: the recording shows what the fitted scene does not model: %s is "
            "%.4g, where twenty recordings simulated with the fitted scene give %.4g "
            "(%.4g to %.4g; %+.1f standard deviations): %s. The intervals above assume "
            "the scene's effects; read them with care\n",
            u.statistic.c_str(), u.recorded, u.simulatedMean, u.simulatedLeast, u.simulatedLargest,
            u.z, u.explanation.c_str());
}

/// Empty, or why the files calibrate writes cannot be written: checked before the fit, so that
/// a fit of minutes is never lost to a folder that cannot take it.
std::string unwritable(const std::vector<std::string>& paths) {
    const fs::path folder = fs::path(paths.front()).parent_path();
    const std::string dir = folder.empty() ? std::string(".") : folder.string();
    try {
        ensureOutputDirectory(dir);
    } catch (const std::exception& e) {
        return e.what();
    }
    const std::string probe =
        (fs::path(dir) / (".calibrate-probe-" + std::to_string(::getpid()))).string();
    std::FILE* f = std::fopen(probe.c_str(), "w");
    if (!f)
        return dir + ": cannot write in this folder (" + std::strerror(errno) +
               "); choose another --out";
    std::fclose(f);
    std::remove(probe.c_str());
    return {};
}

/// Writes the fitted scene and the recording simulated with it.
void writeFittedScene(const std::string& outPath, const std::string& simulatedPath,
                      const std::string& recording, const std::string& reportPath,
                      const SceneSpec& base, const SceneFit& fit, const ExperimentSpec& spec,
                      const std::vector<CollectedTap>& simulated) {
    SceneSpec written = fit.fitted;
    written.description =
        "Fitted by activetouch-cli calibrate to " + recording + " (" + std::to_string(fit.taps) +
        " taps) from " +
        (base.source.empty() ? std::string("the experiment's scene") : base.source) +
        "; the estimates, their uncertainties and the tests are in " +
        fs::path(reportPath).filename().string() + ".";
    {
        OutputFile f(outPath);
        f.print("%s\n", sceneToJson(written).dump(2).c_str());
        f.close();
    }
    TapCsvWriter writer(simulatedPath, static_cast<int>(base.fingertip.taxels.size()));
    for (const auto& t : simulated) writer.append(t, spec.classes);
}

/// Draws the calibration figure as <stem>.calibration.{png,pdf,svg}; whether it was written.
bool drawCalibrationFigure(int argc, char** argv, const SceneFit& fit,
                           const Figure6Comparison& figure6, const std::string& stem) {
    QStringList figures;
    drawFigures(argc, argv, [&] {
        QCustomPlot plot;
        if (buildCalibrationFigure(plot, fit, figure6))
            figures = exportFigure(plot, QString::fromStdString(stem + ".calibration"),
                                   {"png", "pdf", "svg"},
                                   FigureSize::physical(kDoubleColumn_mm, 90, kFigureDpi));
    });
    return !figures.isEmpty();
}

}  // namespace

/// calibrate: a scene fitted to recorded training and test taps (docs/calibration.md).
int commandCalibrate(const std::vector<std::string>& args, int argc, char** argv) {
    const RunArguments parsed = parseRunArguments(args, "calibrate", {"--replicates"}, true, true,
                                                  {{"--scene", "a base scene file"}});
    if (!parsed.error.empty()) return usageError(parsed.error);
    if (parsed.outDir.empty())
        return usageError("calibrate needs --out <fitted scene.json>: where to write the scene");
    const auto loaded = loadForRun(parsed.experimentPath);
    if (!loaded) return kBadInput;
    const ExperimentSpec& spec = *loaded;
    SceneFitSettings settings;
    if (parsed.seeds.count("--replicates")) {
        const auto n = parsed.seeds.at("--replicates");
        if (n < 5 || n > 1000) return usageError("--replicates takes 5 to 1000 recordings");
        settings.bootstrapReplicates = static_cast<int>(n);
    }
    std::string recording = parsed.recordingPath;
    if (fs::is_directory(recording))
        recording = (fs::path(recording) / "data" / "taps.csv").string();
    settings.recording = recording;
    const fs::path out(parsed.outDir);
    const std::string stem = (out.parent_path() / out.stem()).string();
    const std::string reportPath = stem + ".calibration.json";
    const std::string simulatedPath = stem + ".simulated_taps.csv";
    try {
        SceneSpec base = spec.scene;
        if (!parsed.text("--scene").empty()) {
            base = loadScene(parsed.text("--scene"));
            simulatedRigs().checkEffects(base);
        }
        std::string cutOff;
        const auto taps =
            readTapCsv(recording, spec.classes, &cutOff, checkedRecordingBounds(recording));
        for (const std::string& path : {parsed.outDir, reportPath, simulatedPath}) {
            if (fs::is_directory(path))
                throw InputError(path, "", "this is a folder; --out names the fitted scene's file");
            if (fs::exists(path) && !parsed.replace)
                throw InputError(path, "",
                                 "already exists; choose another --out, or give --replace");
        }
        if (const std::string why = unwritable({parsed.outDir, reportPath, simulatedPath});
            !why.empty()) {
            std::fprintf(stderr, "error: %s\nNothing was fitted.\n", why.c_str());
            return kRunFailed;
        }
        if (!cutOff.empty())
            std::printf("the recording was cut short: %s; left out\n", cutOff.c_str());
        std::vector<TapRecord> records;
        records.reserve(taps.size());
        for (const auto& t : taps) records.push_back(t.record);
        const SceneFit fit = fitScene(base, records, settings);
        const Figure6Comparison figure6 = compareFigure6(spec, taps, fit);
        writeFittedScene(parsed.outDir, simulatedPath, recording, reportPath, base, fit, spec,
                         figure6.firstSimulated);
        writeJsonAtomically(
            reportPath, calibrationReport(recording, base, fit, settings, figure6, simulatedPath));
        std::printf("%s: %d taps, %ld samples over nothing; fitted from %s\n", recording.c_str(),
                    fit.taps, fit.nothingSamples,
                    base.source.empty() ? "the experiment's scene" : base.source.c_str());
        printEstimates(fit);
        printGoodness(fit, figure6);
        const bool drawn = parsed.figures && drawCalibrationFigure(argc, argv, fit, figure6, stem);
        std::printf(
            "wrote %s, %s and %s (analyse it for its Figure 6)%s\n", parsed.outDir.c_str(),
            reportPath.c_str(), simulatedPath.c_str(),
            !drawn ? "" : (", and the figure " + (stem + ".calibration.{png,pdf,svg}")).c_str());
        return kOk;
    } catch (const InputError& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return kBadInput;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "calibrate failed: %s\n", e.what());
        return kRunFailed;
    }
}

}  // namespace activetouch::cli
