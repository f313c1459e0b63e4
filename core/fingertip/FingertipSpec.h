#pragma once
// The fingertip as data: taxel positions on a rounded body, the body's size, how it is mounted,
// and how indentation becomes counts. Loaded from resources/fingertip/*.json.
#include <array>
#include <string>
#include <vector>

namespace activetouch {

struct TaxelPosition {
    double x = 0.0;  ///< along the finger axis toward the tip, mm (root frame of the fingertip)
    double y = 0.0;  ///< toward the pad, mm
    double z = 0.0;  ///< lateral, mm
};

struct FingertipSpec {
    std::string name;
    std::vector<TaxelPosition> taxels;  ///< published layout (docs/protocols.md §4)
    // Body: a cylinder of radius `radius` closed by a half-ellipsoid cap from `capStart` to
    // `tipEnd` along the axis. Taxels are placed on this surface at their published axial position
    // and angle around the axis.
    double radius = 6.5;
    double capStart = 12.0;
    double tipEnd = 24.5;
    double mountTiltDeg = 20.0;        ///< finger axis below the horizontal, pad facing down
    double mountHeadingDeg = 90.0;     ///< direction the finger points in the stage plane
    double receptiveFieldSigma = 1.3;  ///< taxel receptive field on the contact plane, mm
    double countsPerMm = 100.0;        ///< counts per mm of mean indentation over a receptive field
    double gridStep = 0.5;             ///< contact-plane discretisation, mm
    double maxIndentation = 6.0;       ///< deepest indentation the model resolves, mm
};

}  // namespace activetouch
