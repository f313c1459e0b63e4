#include "core/recognition/ShapeRecognition.h"

namespace activetouch {

std::vector<ShapeTemplate> shapeTemplates(const std::vector<NamedOutline>& shapes,
                                          double offset_mm, double step_mm, int bins,
                                          double sigmaBins) {
    std::vector<ShapeTemplate> templates;
    for (const NamedOutline& s : shapes) {
        bool seen = false;
        for (const auto& t : templates) seen = seen || t.shape == s.shape;
        if (seen) continue;
        ShapeTemplate t;
        t.shape = s.shape;
        t.raw = idealFollowingHistogram(*s.outline, offset_mm, step_mm, bins);
        t.smooth = smoothed(t.raw, sigmaBins);
        templates.push_back(std::move(t));
    }
    return templates;
}

}  // namespace activetouch
