#include <filesystem>
#include <map>

#include "core/run/OutputFiles.h"
#include "core/run/RunArtefacts.h"

namespace activetouch {
namespace fs = std::filesystem;

namespace {

void writeClassRegions(const RunResult& r, const fs::path& data) {
    const ClassSet& cs = r.classes;
    OutputFile f((data / "class_regions.csv").string());
    f.print("class,orientation_deg,orientation,position,offset_mm,region\n");
    for (int c = 0; c < cs.classCount(); ++c)
        f.print("%d,%g,%s,%d,%g,%s\n", c, cs.orientationDegOf(c),
                ClassSet::orientationName(cs.orientationDegOf(c)).c_str(), cs.positionOf(c),
                cs.offsetOf(cs.positionOf(c)), regionName(cs.regionOf(c)));
    f.close();
}

void writeValidationTables(const RunResult& r, const fs::path& data) {
    const ClassSet& cs = r.classes;
    {
        OutputFile f((data / "validation_by_class.csv").string());
        f.print(
            "orientation_deg,orientation,position,region,test_taps,angle_error_deg,"
            "position_error_mm,correct_fraction\n");
        for (const auto& e : r.validation.byClass) {
            const double deg = cs.orientationsDeg[static_cast<std::size_t>(e.orientationIndex)];
            f.print("%g,%s,%d,%s,%d,%.10g,%.10g,%.10g\n", deg,
                    ClassSet::orientationName(deg).c_str(), e.position, regionName(e.region),
                    e.taps, e.angleError_deg, e.positionError_mm, e.correctFraction);
        }
        f.close();
    }

    {
        OutputFile f((data / "validation_by_position.csv").string());
        f.print(
            "position,offset_mm,angle_error_deg_mean,angle_error_deg_std,position_error_"
            "mm_mean,position_error_mm_std,in_valid_range\n");
        for (int p = 1; p <= cs.positions; ++p) {
            const auto i = static_cast<std::size_t>(p - 1);
            f.print(
                "%d,%g,%.10g,%.10g,%.10g,%.10g,%d\n", p, cs.offsetOf(p), r.validation.angleMean[i],
                r.validation.angleStd[i], r.validation.positionMean[i], r.validation.positionStd[i],
                p >= r.validation.validRange.first && p <= r.validation.validRange.last ? 1 : 0);
        }
        f.close();
    }

    {
        OutputFile f((data / "test_percepts.csv").string());
        f.print(
            "set,true_class,true_orientation_deg,true_position,true_offset_mm,perceived_"
            "class,shape_class,perceived_orientation_deg,perceived_position,posterior\n");
        std::size_t i = 0;
        for (const auto& t : r.taps) {
            if (r.spec.training.isTrainingSet(t.dataSet)) continue;
            const Percept& p = r.validation.percepts[i++];
            f.print("%d,%d,%g,%d,%.10g,%d,%s,%g,%d,%.10g\n", t.dataSet, t.cls,
                    cs.orientationDegOf(t.cls), cs.positionOf(t.cls), t.trueOffset_mm, p.cls,
                    p.shapeClass().c_str(), p.orientationDeg, p.position, p.posterior);
        }
        f.close();
    }
}

void writeFollowingTables(const RunResult& r, const fs::path& data) {
    {
        OutputFile f((data / "following_trials.csv").string());
        f.print(
            "shape,mode,trial,completed,end,taps,robot_time_s,coverage,mean_contour_"
            "distance_mm,max_contour_distance_mm,progress_mm,start_x_mm,start_y_mm,"
            "furthest_progress_mm,furthest_x_mm,furthest_y_mm,furthest_place,corner_x_mm,"
            "corner_y_mm,past_corner_mm,convex_corners_rounded,concave_corners_rounded\n");
        for (const auto& t : r.trials) {
            const ContourPlace& at = t.result.furthest;
            f.print("%s,%s,%d,%d,%s,%zu,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%s,",
                    t.label.c_str(), modeName(t.result.mode), t.trial, t.result.completed() ? 1 : 0,
                    trialEndName(t.result.end), t.result.taps.size(), t.result.robotTime_s,
                    t.result.coverage, t.result.meanContourDistance_mm,
                    t.result.maxContourDistance_mm, t.result.progress_mm, t.start.x, t.start.y,
                    t.result.furthestProgress_mm, at.point.x, at.point.y, placeKindName(at.kind));
            if (at.kind == PlaceKind::AwayFromCorners)
                f.print(",,");
            else
                f.print("%.6g,%.6g,%.6g", at.corner.x, at.corner.y, at.pastCorner_mm);
            f.print(",%d,%d\n", t.result.cornersRounded.convex, t.result.cornersRounded.concave);
        }
        f.close();
    }
    {
        OutputFile f((data / "following_paths.csv").string());
        f.print("shape,mode,trial,%s\n", kTrialTapColumns);
        for (const auto& t : r.trials)
            printTrialTaps(
                f, t.label + "," + modeName(t.result.mode) + "," + std::to_string(t.trial) + ",",
                t);
        f.close();
    }
    {
        OutputFile f((data / "outlines.csv").string());
        f.print("shape,vertex,x_mm,y_mm\n");
        std::map<std::string, bool> written;
        for (const auto& t : r.trials) {
            if (written[t.label]) continue;
            written[t.label] = true;
            for (std::size_t v = 0; v < t.outline.size(); ++v)
                f.print("%s,%zu,%.10g,%.10g\n", t.label.c_str(), v, t.outline.vertex(v).x,
                        t.outline.vertex(v).y);
        }
        f.close();
    }
}

void writeRecognitionTables(const RunResult& r, const fs::path& data) {
    {
        OutputFile f((data / "recognition.csv").string());
        f.print("shape,trial,predicted,predicted_smoothed");
        for (const auto& t : r.templates) f.print(",distance_%s", t.shape.c_str());
        for (const auto& t : r.templates) f.print(",smoothed_distance_%s", t.shape.c_str());
        f.put('\n');
        for (const auto& t : r.trials) {
            if (!t.recognised) continue;
            f.print("%s,%d,%s,%s", t.label.c_str(), t.trial, t.recognition.predicted.c_str(),
                    t.recognition.predictedSmoothed.c_str());
            for (const auto& tp : r.templates)
                f.print(",%.10g", t.recognition.distances.at(tp.shape));
            for (const auto& tp : r.templates)
                f.print(",%.10g", t.recognition.smoothedDistances.at(tp.shape));
            f.put('\n');
        }
        f.close();
    }
    {
        OutputFile f((data / "path_histograms.csv").string());
        f.print("kind,shape,trial,smoothed,ix,iy,value\n");
        auto dump = [&](const char* kind, const std::string& shape, int trial, bool smooth,
                        const PathHistogram& h) {
            for (int iy = 0; iy < h.bins; ++iy)
                for (int ix = 0; ix < h.bins; ++ix)
                    f.print("%s,%s,%d,%d,%d,%d,%.10g\n", kind, shape.c_str(), trial, smooth ? 1 : 0,
                            ix, iy, h.at(ix, iy));
        };
        for (const auto& t : r.templates) {
            dump("template", t.shape, 0, false, t.raw);
            dump("template", t.shape, 0, true, t.smooth);
        }
        for (const auto& t : r.trials)
            if (t.recognised) {
                dump("path", t.label, t.trial, false, t.recognition.raw);
                dump("path", t.label, t.trial, true, t.recognition.smooth);
            }
        f.close();
    }
}

void writeSweepTables(const SweepResults& sw, const fs::path& data) {
    if (!sw.perception.empty()) {
        {
            OutputFile f((data / "sweep_perception.csv").string());
            f.print(
                "belief_threshold,decisions,mean_taps_per_decision,taps_low,taps_high,"
                "mean_robot_time_s,robot_time_low_s,robot_time_high_s,edge_angle_error_deg,"
                "angle_low_deg,angle_high_deg,position_error_mm,position_low_mm,"
                "position_high_mm,correct_fraction,correct_low,correct_high,"
                "plane_perceived_as_plane,air_perceived_as_air\n");
            for (const auto& row : sw.perception)
                f.print(
                    "%.15g,%d,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,"
                    "%.6g,%.6g,%.6g,%.6g\n",
                    row.threshold, row.decisions, row.meanTaps, row.taps.low, row.taps.high,
                    row.meanRobotTime_s, row.robotTime_s.low, row.robotTime_s.high,
                    row.angleError_deg, row.angle_deg.low, row.angle_deg.high, row.positionError_mm,
                    row.position_mm.low, row.position_mm.high, row.correctFraction, row.correct.low,
                    row.correct.high, row.planeRecognised, row.airRecognised);
            f.close();
        }
    }
    if (!sw.following.empty()) {
        {
            OutputFile f((data / "sweep_following.csv").string());
            f.print(
                "mode,follow_step_mm,reposition_step_mm,belief_threshold,trials,completed,"
                "completion_rate,mean_contour_distance_mm,"
                "mean_taps,mean_robot_time_s,robot_time_per_completion_s,paper_setting\n");
            for (const auto& row : sw.following)
                f.print("%s,%g,%g,%.15g,%d,%d,%.6g,%.6g,%.6g,%.6g,%.6g,%d\n", modeName(row.mode),
                        row.followStep_mm, row.repositionStep_mm, row.beliefThreshold, row.trials,
                        row.completed, double(row.completed) / row.trials,
                        row.meanContourDistance_mm, row.meanTaps, row.meanRobotTime_s,
                        row.robotTimePerCompletion_s, row.paperSetting ? 1 : 0);
            f.close();
        }
    }
    if (!sw.compute.empty()) {
        {
            OutputFile f((data / "sweep_compute.csv").string());
            f.print(
                "bins,samples_per_tap,angle_error_deg,position_error_mm,microseconds_per_"
                "decision,paper_setting\n");
            for (const auto& row : sw.compute)
                f.print("%d,%d,%.6g,%.6g,%.6g,%d\n", row.bins, row.samples, row.angleError_deg,
                        row.positionError_mm, row.microsecondsPerDecision,
                        row.paperSetting ? 1 : 0);
            f.close();
        }
    }
}

void writeConfusion(const RunResult& r, const fs::path& data) {
    const ClassSet& cs = r.classes;
    OutputFile f((data / "confusion.csv").string());
    f.print("true_class");
    for (int c = 0; c < cs.classCount(); ++c) f.print(",perceived_%d", c);
    f.put('\n');
    for (int a = 0; a < cs.classCount(); ++a) {
        f.print("%d", a);
        for (int b = 0; b < cs.classCount(); ++b)
            f.print(",%d",
                    r.validation.confusion[static_cast<std::size_t>(a * cs.classCount() + b)]);
        f.put('\n');
    }
    f.close();
}

}  // namespace

void printTrialTaps(OutputFile& f, const std::string& prefix, const TrialRun& t) {
    int i = 0;
    for (const auto& tap : t.result.taps) {
        const Vec2 m = tap.decision.move();
        f.print("%s%d,%.10g,%.10g,%s,%g,%d,%s,%.10g,%.10g,%.10g,%.10g\n", prefix.c_str(), i++,
                tap.record.pose.x, tap.record.pose.y, tap.percept.shapeClass().c_str(),
                tap.percept.orientationDeg, tap.percept.position, ruleFor(tap.decision.rule).name,
                m.x, m.y, tap.progress_mm, tap.contourDistance_mm);
    }
}

void writeRunTables(const RunResult& r, const std::string& outDir) {
    const fs::path data = fs::path(outDir) / "data";
    ensureOutputDirectory(data.string());
    writeClassRegions(r, data);
    if (!r.validation.byClass.empty()) writeValidationTables(r, data);
    if (!r.trials.empty()) writeFollowingTables(r, data);
    if (!r.templates.empty()) writeRecognitionTables(r, data);
    writeSweepTables(r.sweeps, data);
    if (!r.validation.confusion.empty()) writeConfusion(r, data);
}

}  // namespace activetouch
