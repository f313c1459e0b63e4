// What effects share in reading their parameters: a list of taxels, a gain per taxel, and the
// catalogue looked up by name (Effect.h).
#include "devices/simulated/effects/Effect.h"

namespace activetouch {

std::vector<int> effectTaxelList(const JsonFields& f, int taxelCount) {
    const std::string indices = "taxel indices 0.." + std::to_string(taxelCount - 1);
    if (!f.has("taxels") || !f.raw("taxels").is_array() || f.raw("taxels").empty())
        f.fail("taxels", "this effect needs 'taxels': a non-empty list of " + indices);
    std::vector<int> list;
    for (const auto& v : f.raw("taxels")) {
        // An index is compared as a whole number of any size: a huge one must not wrap.
        const bool valid =
            v.is_number_integer() && v.get<long long>() >= 0 && v.get<long long>() < taxelCount &&
            !(v.is_number_unsigned() &&
              v.get<unsigned long long>() >= static_cast<unsigned long long>(taxelCount));
        if (!valid)
            f.fail("taxels", "taxel " + describeJson(v) + " does not exist; use " + indices);
        list.push_back(static_cast<int>(v.get<long long>()));
    }
    return list;
}

std::vector<double> effectGainList(const JsonFields& f, int taxelCount) {
    for (const char* other : {"spread", "fingertip_seed"})
        if (f.has(other))
            f.fail(other, std::string("'gains' gives every taxel's gain; leave '") + other +
                              "' out, or give 'spread' and 'fingertip_seed' without 'gains'");
    const std::vector<double> gains = f.numbers("gains", 0.05, 20.0);
    if (static_cast<int>(gains.size()) != taxelCount)
        f.fail("gains", "give one gain per taxel: " + std::to_string(taxelCount) + ", not " +
                            std::to_string(gains.size()));
    return gains;
}

const EffectDescription* findEffect(const std::string& name) {
    for (const auto& d : effectCatalogue())
        if (d.name == name) return &d;
    return nullptr;
}

}  // namespace activetouch
