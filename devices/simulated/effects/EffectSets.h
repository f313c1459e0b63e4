#pragma once
// The simulated rig's effects come in sets, each registered into the catalogue by its own file:
// effects of the signal and the stream (Effects.cpp) and effects of single taxels
// (TaxelEffects.cpp). Internal to devices/simulated/effects.
#include <vector>

#include "devices/simulated/effects/Effect.h"

namespace activetouch {

/// The effects of single taxels: crosstalk, dead taxels, per-taxel gains, saturation with
/// recovery, intermittent taxels.
void addTaxelEffects(std::vector<EffectDescription>& catalogue);

}  // namespace activetouch
