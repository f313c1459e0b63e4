#pragma once
// A physical effect of the simulated rig beyond the ideal model (docs/simulated-rig.md). An effect
// exists only if the scene lists it: the pipeline constructs exactly the listed ones, so an
// unlisted effect costs nothing at run time. Each effect acts at one place:
//   pose      - where the stage really puts the fingertip (stage_error)
//   mechanics - how the tapper's stroke ends (contact_latency)
//   signal    - what the taxels report (everything else), in a fixed physical order:
//               link_dropout (the stream failing before anything is reported),
//               viscoelastic_memory, crosstalk, taxel_gain, saturation_recovery, dead_taxel,
//               intermittent_taxel, baseline_drift, taxel_noise, adc_quantisation.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/common/Random.h"
#include "core/fingertip/FingertipContactModel.h"
#include "core/io/JsonFields.h"
#include "core/tap/Tap.h"

namespace activetouch {

/// What a signal effect may know about the tap it shapes.
struct SignalContext {
    double startTime_s = 0.0;  ///< robot time of the tap's first sample
    double samplePeriod_s = 0.02;
    double release_s = 0.0;                 ///< time in the tap when the fingertip starts to rise
    const double* holdPressures = nullptr;  ///< ideal pressures while held (taxelCount values)
};

class Effect {
public:
    enum class Acts { Pose, Mechanics, Signal };

    virtual ~Effect() = default;
    const std::string& name() const { return name_; }
    Acts acts() const { return acts_; }
    /// Place in the signal chain (lower runs first).
    int signalOrder() const { return order_; }

    /// The pose the stage really reaches when commanded to `commanded`.
    virtual Vec2 perturbPose(Vec2 commanded) { return commanded; }
    /// Extra time the tapper keeps descending after the contact threshold is crossed, s.
    virtual double reflexLatency_s() const { return 0.0; }
    /// Shapes the tap's samples in place.
    virtual void shapeSignal(Tap&, const SignalContext&) {}

    /// How many effects named `name` have been constructed in this process.
    static int constructedCount(const std::string& name);

protected:
    Effect(std::string name, Acts acts, int order = 0);

private:
    std::string name_;
    Acts acts_;
    int order_;
};

/// One parameter of an effect, for documentation, validation and the GUI's scene panel.
struct EffectParameter {
    std::string key;
    std::string meaning;
    double lo, hi, typical;
};

struct EffectDescription {
    std::string name;
    std::string models;  ///< one sentence: what the effect models
    std::vector<EffectParameter> parameters;
    bool takesTaxelList = false;  ///< "taxels": [indices] (dead_taxel, intermittent_taxel)
    std::function<std::unique_ptr<Effect>(const JsonFields&, const FingertipContactModel&,
                                          RandomStream)>
        make;
    /// "gains": [one per taxel] may stand instead of every parameter (taxel_gain: a fingertip
    /// whose gains were measured, as calibrate writes them).
    bool takesGainList = false;
};

/// The taxel indices an effect's "taxels" lists (dead_taxel's), each within 0..taxelCount-1;
/// InputError naming the place otherwise.
std::vector<int> effectTaxelList(const JsonFields& f, int taxelCount);
/// The gains an effect's "gains" lists (taxel_gain's measured gains): one per taxel, each within
/// 0.05..20, and no other parameter beside them; InputError naming the place otherwise.
std::vector<double> effectGainList(const JsonFields& f, int taxelCount);

/// Every effect the simulated rig knows.
const std::vector<EffectDescription>& effectCatalogue();
const EffectDescription* findEffect(const std::string& name);

}  // namespace activetouch
