#pragma once
// The vertical axis that taps the fingertip onto the object (the paper's LEGO NXT tapper or its
// simulation). A tap lowers the fingertip, stops on the contact-threshold reflex or the stroke
// limit, holds for the contact time and returns to the retract height, recording the fingertip's
// frames over the tap window.
#include "core/tap/Tap.h"

namespace activetouch {

class Tapper {
public:
    virtual ~Tapper() = default;

    /// Performs one tap at the current stage position and returns it, with its timing and how it
    /// ended. Throws RigError if the device fails; the tapper is then left retracted or stopped.
    virtual TapRecord tap() = 0;
};

}  // namespace activetouch
