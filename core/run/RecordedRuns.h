#pragma once
// A run's recording read back (docs/file-formats.md): its training and test taps to analyse again,
// and its following trials to replay as rigs, checked against the experiment before any tap.
#include <string>
#include <vector>

#include "core/experiment/Experiment.h"
#include "core/records/FollowingRecording.h"
#include "core/records/TapCsv.h"

namespace activetouch {

/// A recording read back whole: training and test taps to analyse instead of taking any, and for
/// a replay a run's trials too.
struct RecordedRun {
    std::string name;                   ///< where it came from (a file, or a run's folder)
    std::vector<CollectedTap> taps;     ///< <runDir>/data/taps.csv
    std::vector<RecordedTrial> trials;  ///< <runDir>/data/following_taps.csv; none: analyse
    int followingTaps = 0;
    /// Empty, or what a run stopped while writing cut from the end of each file.
    std::string tapsCutOff, trialsCutOff;
    /// Empty, or why the files could not be checked to come from one run (no run.json).
    std::string note;
    bool replay() const { return !trials.empty(); }
};

/// Reads the recording of the run in `runDir` for a replay. Throws InputError naming the file
/// and what to do: not a folder, no following recording, or no training taps beside it (a
/// following-only run's classifier was trained in another run's folder).
RecordedRun readRecordedRun(const std::string& runDir, const ClassSet& classes);

/// The recorded trial each of the experiment's trials replays, in the experiment's order.
/// Throws InputError naming `name` and the trial the recording lacks.
std::vector<const RecordedTrial*> replayedTrialsFor(const ExperimentSpec& spec,
                                                    const std::vector<RecordedTrial>& recorded,
                                                    const std::string& name);

/// Refuses a replay whose trials' taps have another number of taxels or samples than `first`,
/// the first training tap: InputError naming `name` and the trial.
void checkReplayedTapsMatch(const std::vector<const RecordedTrial*>& replayed, const Tap& first,
                            const std::string& name);

/// Refuses recorded taps the experiment cannot be validated on: a data set outside the
/// experiment's, a class of a training set without a tap, no test tap, or taps with another
/// number of taxels than the fingertip's. Throws InputError naming `name` and what is missing.
void checkRecordingCovers(const ExperimentSpec& spec, const std::vector<CollectedTap>& taps,
                          int taxels, const std::string& name);

}  // namespace activetouch
