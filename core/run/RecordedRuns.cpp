#include "core/run/RecordedRuns.h"

#include <filesystem>

#include "core/common/InputError.h"
#include "core/run/RunFolder.h"

namespace activetouch {
namespace fs = std::filesystem;

RecordedRun readRecordedRun(const std::string& runDir, const ClassSet& classes) {
    std::error_code ec;  // a path the system cannot look up is not a run's folder
    if (!fs::is_directory(runDir, ec))
        throw InputError(runDir, "",
                         "not a folder; give the folder a run wrote (it holds data/taps.csv and "
                         "data/following_taps.csv)");
    const fs::path data = fs::path(runDir) / "data";
    const std::string following = (data / "following_taps.csv").string(),
                      taps = (data / "taps.csv").string();
    if (!fs::exists(following, ec))
        throw InputError(following, "",
                         "the run recorded no contour following, so there is nothing to replay; "
                         "re-analyse its training taps instead (analyse)");
    if (!fs::exists(taps, ec))
        throw InputError(taps, "",
                         "no training taps beside the following recording: this run followed "
                         "with a classifier trained in an earlier run; copy that run's "
                         "data/taps.csv here to replay both");
    RecordedRun run;
    run.name = runDir;
    // Both files must be the one run's: a folder that mixes runs is refused, naming the file.
    const RecordingBounds bounds = checkedRecordingBounds(taps, &run.note);
    checkedRecordingBounds(following);
    run.taps = readTapCsv(taps, classes, &run.tapsCutOff, bounds);
    FollowingRecordingContents contents;
    run.trials = readFollowingRecording(following, &contents, bounds);
    run.followingTaps = contents.taps;
    run.trialsCutOff = contents.cutOff;
    return run;
}

std::vector<const RecordedTrial*> replayedTrialsFor(const ExperimentSpec& spec,
                                                    const std::vector<RecordedTrial>& recorded,
                                                    const std::string& name) {
    std::vector<const RecordedTrial*> replayed;
    std::map<std::string, int> counters;  // trials so far per (label, mode), as runTrials counts
    for (const TrialSpec& ts : spec.trials)
        for (int repeat = 0; repeat < ts.repeats; ++repeat) {
            const int trial = ++counters[ts.label + "/" + modeName(ts.mode)];
            // A trial named after its library shape also matches a recording that spelt the
            // name in another letter case ("c" for "C").
            const bool shapeLabel = ts.label == ts.object.shape;
            const auto it = std::find_if(recorded.begin(), recorded.end(), [&](const auto& r) {
                const bool sameLabel =
                    r.label == ts.label || (shapeLabel && libraryShapeName(r.label) == ts.label);
                return sameLabel && r.mode == ts.mode && r.trial == trial;
            });
            if (it == recorded.end())
                throw InputError(name, "",
                                 "the recording holds no " + std::string(modeName(ts.mode)) + " " +
                                     ts.label + " trial " + std::to_string(trial) +
                                     " (the experiment's " + ts.place +
                                     "); replay it with the experiment the run was made with, or "
                                     "leave that trial out of the experiment");
            replayed.push_back(&*it);
        }
    return replayed;
}


void checkRecordingCovers(const ExperimentSpec& spec, const std::vector<CollectedTap>& taps,
                          int taxels, const std::string& name) {
    const ClassSet& classes = spec.classes;
    const int sets = spec.training.dataSets;
    std::vector<std::vector<int>> count(static_cast<std::size_t>(sets) + 1,
                                        std::vector<int>(classes.classCount(), 0));
    bool anyTest = false;
    for (const CollectedTap& t : taps) {
        if (t.dataSet < 1 || t.dataSet > sets)
            throw InputError(name, "column set",
                             "data set " + std::to_string(t.dataSet) +
                                 " is not one of the experiment's data sets 1.." +
                                 std::to_string(sets) +
                                 "; use the experiment the taps were "
                                 "recorded with, or set training.data_sets");
        if (t.record.tap.taxels != taxels)
            throw InputError(name, "taxel columns",
                             "the taps have " + std::to_string(t.record.tap.taxels) +
                                 " taxels and the experiment's fingertip " +
                                 std::to_string(taxels) +
                                 "; use the fingertip description the taps were recorded with");
        ++count[static_cast<std::size_t>(t.dataSet)][static_cast<std::size_t>(t.cls)];
        anyTest = anyTest || !spec.training.isTrainingSet(t.dataSet);
    }
    for (int set : spec.training.trainingSets)
        for (int c = 0; c < classes.classCount(); ++c)
            if (count[static_cast<std::size_t>(set)][static_cast<std::size_t>(c)] == 0)
                throw InputError(
                    name, "data set " + std::to_string(set),
                    "training set " + std::to_string(set) + " has no tap of class " +
                        std::to_string(c) + " (" +
                        ClassSet::orientationName(classes.orientationDegOf(c)) +
                        " edge, position " + std::to_string(classes.positionOf(c)) +
                        "); every class needs a training tap: record it, or train on other sets "
                        "(training.training_sets)");
    if (!anyTest)
        throw InputError(name, "column set",
                         "every tap belongs to a training set, so nothing is left to validate on; "
                         "record test sets, or train on fewer sets (training.training_sets)");
}

void checkReplayedTapsMatch(const std::vector<const RecordedTrial*>& replayed, const Tap& first,
                            const std::string& name) {
    for (const RecordedTrial* t : replayed)
        for (const TapRecord& r : t->taps)
            if (r.tap.taxels != first.taxels || r.tap.sampleCount() != first.sampleCount())
                throw InputError(
                    name,
                    std::string(modeName(t->mode)) + " " + t->label + " trial " +
                        std::to_string(t->trial),
                    "its taps have " + std::to_string(r.tap.taxels) + " taxels and " +
                        std::to_string(r.tap.sampleCount()) + " samples, the training and test taps " +
                        std::to_string(first.taxels) + " and " + std::to_string(first.sampleCount()) +
                        "; replay a run whose recordings were taken with one fingertip and tap "
                        "window");
}

}  // namespace activetouch
