#pragma once
// A real fingertip beside simulated ones (docs/real-fingertips.md): each taxel's resting noise
// with its interval against the scenes' noise, and each taxel's resting KS distance per scene.
#include <QString>
#include <vector>

class QCustomPlot;

namespace activetouch {

struct FingertipFigureData {
    QString finger, caption;
    std::vector<double> sigma, sigmaLow, sigmaHigh;  ///< per taxel, counts
    struct Scene {
        QString name;
        double sigma = 0.0;      ///< the scene's taxel_noise, counts (0: none)
        std::vector<double> ks;  ///< per taxel
    };
    std::vector<Scene> scenes;
};

/// Builds the figure; false if there is nothing to draw.
bool buildFingertipFigure(QCustomPlot& plot, const FingertipFigureData& data);

}  // namespace activetouch
