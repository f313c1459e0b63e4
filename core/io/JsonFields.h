#pragma once
// Reading settings out of JSON with errors that name the file, the place (a JSON pointer) and
// what to do. Unknown keys are errors too: a misspelt parameter must not be silently ignored.
#include <cmath>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/common/InputError.h"
#include "core/geometry/Vec2.h"

namespace activetouch {

using Json = nlohmann::json;

/// Parses JSON text; a syntax error becomes an InputError with line and column.
Json parseJsonText(const std::string& text, const std::string& source);

/// Reads and parses a JSON file; a missing or unreadable file is an InputError.
Json readJsonFile(const std::string& path);

class JsonFields {
public:
    /// `object` must be a JSON object (else InputError at `pointer`).
    JsonFields(const Json& object, std::string source, std::string pointer);

    const std::string& source() const { return source_; }
    const std::string& pointer() const { return pointer_; }
    std::string placeOf(const std::string& key) const { return pointer_ + "/" + key; }
    bool has(const std::string& key) const { return object_->contains(key); }
    const Json& raw(const std::string& key) const { return object_->at(key); }

    /// Fails on any key not in `known`, naming it and listing the known ones.
    void rejectUnknownKeys(std::initializer_list<const char*> known) const;
    void rejectUnknownKeys(const std::vector<std::string>& known) const;

    double number(const std::string& key, double lo, double hi) const;  ///< required, in [lo, hi]
    double number(const std::string& key, double lo, double hi, double fallback) const;
    int integer(const std::string& key, long lo, long hi) const;
    int integer(const std::string& key, long lo, long hi, int fallback) const;
    std::string text(const std::string& key) const;
    std::string text(const std::string& key, const std::string& fallback) const;
    bool flag(const std::string& key, bool fallback) const;
    Vec2 point(const std::string& key) const;
    Vec2 point(const std::string& key, Vec2 fallback) const;
    std::vector<double> numbers(const std::string& key, double lo, double hi) const;
    JsonFields object(const std::string& key) const;

    [[noreturn]] void fail(const std::string& key, const std::string& problem) const;

private:
    const Json* object_;
    std::string source_;
    std::string pointer_;
};

/// A short rendering of a JSON value for error messages.
std::string describeJson(const Json& value);

}  // namespace activetouch
