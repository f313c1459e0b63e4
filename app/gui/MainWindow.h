#pragma once
// The workbench window (docs/window.md): tabs for the live view, training and validation, contour
// following and recognition; docks for the scene, the devices and the log; runs with progress,
// cancel and a clear final state; every plot exportable. Layout and settings persist.
#include <QMainWindow>
#include <memory>
#include <optional>

#include "app/gui/DeviceSession.h"
#include "app/gui/LiveFeed.h"
#include "app/gui/RunController.h"
#include "core/experiment/Experiment.h"

class QAction;
class QComboBox;
class QMenu;
class QToolBar;
class QLabel;
class QPlainTextEdit;
class QProgressBar;
class QSettings;
class QTabWidget;

namespace activetouch {

class CalibrationDialog;
class DevicesPanel;
class FollowingTab;
class LiveView;
class PlotPanel;
class RecognitionTab;
class SweepsTab;
class ValidationTab;
class ProtocolPanel;
class ScenePanel;
class SeedsTab;
class ComparisonTab;

class MainWindow : public QMainWindow {
    Q_OBJECT
public:
    explicit MainWindow(QWidget* parent = nullptr);
    ~MainWindow() override;

    /// Loads an experiment file; on a bad file shows the problem and keeps the current session.
    bool openExperiment(const QString& path);
    /// Writes the experiment as shown (the scene panel's scene inline) to `path`.
    bool saveExperiment(const QString& path);
    /// The experiment a run would use now: the loaded one with the scene and protocol panels
    /// applied, read with the same checks as a file. Throws InputError naming the panel and its
    /// field if what the panels show cannot run.
    ExperimentSpec experimentAsShown() const;
    bool startRun(RunController::What what);
    /// Runs the experiment as shown once per seed from `first` to `last` on the simulated rig
    /// (the "Rates over seeds" tab), writing into a new folder under the output base.
    bool startSeeds(std::uint64_t first, std::uint64_t last);
    /// Runs `seed` of the last seeds run (its experiment and scene, whatever the panels show
    /// since) as a whole run on the simulated rig: the very run that seed's row stands for, with
    /// every artefact, shown in the contour following tab. Without a seeds run, the experiment
    /// as shown.
    bool startSeedRun(std::uint64_t seed);
    /// Runs the experiment as shown (A) and the experiment file `otherPath` (B) on the seeds
    /// `first` to `last` and compares them trial by trial (the "Compare" tab), writing into a new
    /// folder under the output base. A file that cannot be read, or that shares no trial with A,
    /// is refused with the reason before any run.
    bool startComparison(const QString& otherPath, std::uint64_t first, std::uint64_t last);
    /// What *Compare with...* does once B is chosen: asks first ("compareQuestion": both
    /// experiments, the seeds, how many whole runs that is and how many at a time), then
    /// startComparison on Yes. False, with nothing run, on No.
    bool confirmComparison(const QString& otherPath, std::uint64_t first, std::uint64_t last);
    /// Runs `seed` of the last comparison in both its experiments (as they were compared,
    /// whatever the panels show since) and shows the trial `mode`/`label`/`trial` of each under
    /// the comparison's table. False if there has been no comparison or a run is going.
    bool startTrialPair(std::uint64_t seed, FollowingMode mode, const QString& label, int trial);
    /// Trains and validates the experiment as shown on the training and test taps recorded in
    /// `path` (a run's data/taps.csv), taking no tap; a recording that cannot be read or
    /// validated is refused with the reason and the session kept.
    bool analyseRecording(const QString& path);
    /// Replays the run recorded in the folder `runDir` (its data/taps.csv and
    /// data/following_taps.csv) with the experiment as shown: trains and validates on the
    /// recorded taps, then runs every trial on its recorded taps, which it retraces as long as it
    /// decides as the recorded run did. A recording that cannot be read or lacks a trial is
    /// refused with the reason and the session kept.
    bool replayRun(const QString& runDir);
    /// Opens the Calibrate dialog on the taps recorded in `path` (a taps.csv), fitting the scene
    /// of the experiment as shown; nullptr (and the reason said) if no experiment can run.
    CalibrationDialog* calibrateRecording(const QString& path);
    void cancelRun();
    /// Writes every figure of the last run into `dir`/figures; returns the files.
    QStringList exportAllFigures(const QString& dir);
    /// Where this session writes its runs (not kept as the preference).
    void setOutputBase(const QString& dir);
    const QString& outputBase() const { return outputBase_; }
    /// The results folder preference: kept across sessions, and where runs go from now on.
    void setResultsFolder(const QString& dir);
    const QString& resultsFolder() const { return resultsFolder_; }
    /// <documents>/ActiveTouch/results: the preference's default.
    static QString defaultResultsFolder();
    /// Opens the folder runs go to with the desktop's file manager (made if need be).
    bool openResultsFolder();
    /// Opens a file dropped on the window by what it is: an experiment, a rig file, a tap
    /// recording (analysed) or a run's folder (replayed).
    bool openDropped(const QString& path);
    /// Whether the scene or protocol panel shows what the experiment file does not say.
    bool hasUnsavedEdits() const;
    /// The experiments opened last, newest first.
    QStringList recentExperiments() const;
    /// Shows every dock and the tool bar where they were at first start, fitted to the screen.
    void resetLayout();
    void setPace(Pace pace);

    const QString& experimentPath() const { return experimentPath_; }
    std::shared_ptr<const RunResult> lastRun() const { return last_; }
    QString lastRunDirectory() const { return lastOutDir_; }
    QString lastSeedsDirectory() const { return lastSeedsDir_; }
    QString lastComparisonDirectory() const { return lastComparisonDir_; }
    bool running() const { return runs_.running(); }
    QProgressBar* progressBar() const { return progress_; }
    ScenePanel* scenePanel() const { return scene_; }
    ProtocolPanel* protocolPanel() const { return protocol_; }
    LiveView* liveView() const { return live_; }
    FollowingTab* followingTab() const { return following_; }
    SeedsTab* seedsTab() const { return seeds_; }
    ComparisonTab* comparisonTab() const { return comparison_; }
    QTabWidget* tabs() const { return tabs_; }
    /// Every plot in the window, for export.
    QList<PlotPanel*> plotPanels() const;

signals:
    void errorShown(const QString& message);
    void runEnded(bool completed);

protected:
    void closeEvent(QCloseEvent* event) override;
    void dragEnterEvent(QDragEnterEvent* event) override;
    void dropEvent(QDropEvent* event) override;

private:
    /// Cancels a run in flight and interrupts the devices under it, waiting briefly for it.
    void stopRunNow();
    void showError(const QString& message);
    /// experimentAsShown(), also giving the experiment file's document as the panels show it
    /// (what Save as writes) when `document` is given.
    ExperimentSpec experimentAsShown(Json* document) const;
    /// The experiment as shown, if one is open and it can run; otherwise says why.
    std::optional<ExperimentSpec> experimentToRun();
    /// Analyses the recorded taps in the file `path`, or (`replay`) replays the run recorded in
    /// the folder `path`; what cannot be read or run is refused with the reason.
    bool startOnRecording(const QString& path, bool replay);
    /// Whether `runs` runs of `spec` may be written into `dir`: a plan beyond the bounds and a
    /// folder that holds a run each need the user's yes.
    bool mayWriteRun(const ExperimentSpec& spec, double runs, const QString& dir);
    /// Starts `spec` into a new folder named after `stem`, on `connected` or the simulated rig.
    bool launch(const ExperimentSpec& spec, RunController::What what, const QString& stem,
                std::shared_ptr<const ConnectedRig> connected,
                std::shared_ptr<const RecordedRun> recorded = {});
    /// A new folder under the output base for a run: <stem>-<date and time>.
    QString newRunDirectory(const QString& stem) const;
    // The constructor's parts: the tabs, the docks, the run tool bar and the status bar, and the
    // run controller's signals.
    void buildTabs();
    void buildDocks();
    void buildToolBar(const QSettings& settings);
    void buildStatusBar();
    void buildMenus();
    void buildFileMenu();  // the menu bar's parts (MainWindowMenuBar.cpp)
    void buildRunMenu();
    void buildViewMenu();
    void buildHelpMenu();
    void connectRuns();
    // The menus' parts (MainWindowMenus.cpp).
    void fillRecentMenu();
    void rememberRecent(const QString& path);
    void chooseExperiment();
    void chooseSaveAs();
    void saveExperimentInPlace();
    void chooseExportFolder();
    void showPreferences();
    void showResultsFolder();
    void openDocumentation();
    void showAbout();
    /// Sizes the window to the screen it is on (first start and Reset the layout).
    void fitToScreen();
    /// The experiment file's document as the panels show it (throws on a value no file holds).
    Json documentAsShown() const;
    void updateModified();
    /// Before another experiment replaces this one: asks to save unsaved edits; false to stay.
    bool maySwitchExperiment();
    enum class DroppedKind { Experiment, Rig, Recording, RunFolder, Unknown };
    static DroppedKind kindOfDropped(const QString& path);
    void log(const QString& text);
    void showRun(std::shared_ptr<const RunResult> result, const QString& dir);
    void showSeeds(std::shared_ptr<const SeedRates> rates, const QString& dir, bool cancelled);
    void showComparison(std::shared_ptr<const PairedComparison> comparison, const QString& dir,
                        bool cancelled);
    /// Draws a trial pair in the Compare tab and writes its table and figure into `dir`.
    void showTrialPair(const std::shared_ptr<const TrialPairRun>& pair, const QString& dir);
    void updateActions();
    /// The progress bar counts the seeds first..last, from none.
    void resetProgressToSeeds(std::uint64_t first, std::uint64_t last);

    LiveFeed feed_;
    RunController runs_;
    DeviceThread devices_;
    ExperimentSpec spec_;
    Json experimentJson_;
    QString experimentPath_;
    QString outputBase_;
    QString resultsFolder_;
    Json savedDocument_;       ///< documentAsShown() as last opened or saved
    QByteArray defaultState_;  ///< the docks and tool bar at first start
    std::shared_ptr<const RunResult> last_;
    QString lastOutDir_;
    QString lastSeedsDir_;
    QString lastComparisonDir_;
    std::optional<ExperimentSpec> seedsSpec_;  ///< what the last seeds run ran
    /// What the last comparison compared: A and B.
    std::optional<std::pair<ExperimentSpec, ExperimentSpec>> compared_;
    bool countingSeeds_ = false;  ///< the run going counts seeds, not taps

    QTabWidget* tabs_;
    class HelpBrowser* help_ = nullptr;  ///< made when first asked for
    LiveView* live_;
    ValidationTab* validation_;
    FollowingTab* following_;
    RecognitionTab* recognition_;
    SweepsTab* sweeps_;
    SeedsTab* seeds_;
    ComparisonTab* comparison_;
    ScenePanel* scene_;
    ProtocolPanel* protocol_;
    DevicesPanel* devicesPanel_;
    QPlainTextEdit* log_;
    QProgressBar* progress_;
    QLabel* status_;
    QComboBox* pace_;
    QLabel* resultsLabel_ = nullptr;
    QToolBar* runBar_;
    QMenu* recentMenu_;
    QAction *runAll_, *runTraining_, *runFollowing_, *analyse_, *replay_, *cancel_, *exportAll_;
    QAction* calibrate_ = nullptr;
    QAction *save_, *exportAllMenu_, *runSeeds_, *runCompare_, *pauseLive_;
};

}  // namespace activetouch
