#include "core/io/FollowingRecording.h"

#include "core/common/InputError.h"

namespace activetouch {

FollowingRecording::FollowingRecording(const std::string& path, int taxels) : taxels_(taxels) {
    file_ = std::fopen(path.c_str(), "w");
    if (!file_)
        throw InputError(path, "",
                         "cannot create the file; check the output folder exists and is writable");
    std::fprintf(
        file_,
        "shape,mode,trial,tap,pose_x_mm,pose_y_mm,robot_time_s,ending,contact,shape_class,"
        "orientation_deg,position,"
        "offset_mm,posterior,rule,move_x_mm,move_y_mm,progress_mm,contour_distance_mm,sample");
    for (int k = 0; k < taxels; ++k) std::fprintf(file_, ",taxel_%d", k);
    std::fputc('\n', file_);
    std::fflush(file_);
}

FollowingRecording::~FollowingRecording() {
    if (file_) std::fclose(file_);
}

void FollowingRecording::append(const std::string& label, FollowingMode mode, int trial,
                                int tapIndex, const FollowedTap& t) {
    const TapRecord& r = t.record;
    const Vec2 move = t.decision.move();
    const std::string shapeClass = t.percept.shapeClass();
    for (int s = 0; s < r.tap.sampleCount(); ++s) {
        std::fprintf(
            file_,
            "%s,%s,%d,%d,%.17g,%.17g,%.17g,%s,%d,%s,%g,%d,%g,%.10g,%s,%.17g,%.17g,%.10g,%.10g,%d",
            label.c_str(), modeName(mode), trial, tapIndex, r.pose.x, r.pose.y, r.startTime_s,
            r.ending == TapEnding::ContactReflex ? "reflex" : "stroke_limit", t.contact ? 1 : 0,
            shapeClass.c_str(), t.percept.orientationDeg, t.percept.position, t.percept.offset_mm,
            t.percept.posterior, ruleFor(t.decision.rule).name, move.x, move.y, t.progress_mm,
            t.contourDistance_mm, s);
        for (int k = 0; k < taxels_; ++k) std::fprintf(file_, ",%.17g", r.tap.at(s, k));
        std::fputc('\n', file_);
    }
    std::fflush(file_);
}

}  // namespace activetouch
