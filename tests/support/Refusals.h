#pragma once
// What an input is refused with, for tests that check a refusal names its place and problem.
#include <QString>
#include <functional>

#include "core/common/InputError.h"

namespace activetouch::test {

/// "place | problem | whole message" of the InputError `attempt` throws; empty if it throws none.
inline QString refusalOf(const std::function<void()>& attempt) {
    try {
        attempt();
    } catch (const InputError& e) {
        return QString::fromStdString(e.place() + " | " + e.problem() + " | " + e.what());
    }
    return {};
}

}  // namespace activetouch::test
