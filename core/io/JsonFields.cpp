#include "core/io/JsonFields.h"


#include "core/common/NumberText.h"
#include "core/io/JsonText.h"

namespace activetouch {

Json parseJsonText(const std::string& text, const std::string& source) {
    checkJsonText(text, source);
    try {
        return Json::parse(text);
    } catch (const Json::parse_error& e) {
        // Convert the byte offset into line:column for people reading the file.
        std::size_t line = 1, column = 1;
        const std::size_t end = std::min<std::size_t>(e.byte > 0 ? e.byte - 1 : 0, text.size());
        for (std::size_t i = 0; i < end; ++i) {
            if (text[i] == '\n') {
                ++line;
                column = 1;
            } else {
                ++column;
            }
        }
        std::string what = e.what();
        const auto colon = what.rfind(": ");
        if (colon != std::string::npos) what = what.substr(colon + 2);
        throw InputError(source,
                         "line " + std::to_string(line) + ", column " + std::to_string(column),
                         "the file is not valid JSON (" + what + "); fix the syntax there");
    } catch (const Json::exception& e) {
        // The text check refuses what the library would refuse for size or range; anything else
        // it throws still reaches the user as a sentence about the file.
        std::string what = e.what();
        const auto bracket = what.find("] ");
        if (bracket != std::string::npos) what = what.substr(bracket + 2);
        throw InputError(source, "", "the file could not be read as JSON (" + what + ")");
    }
}

Json readJsonFile(const std::string& path) {
    return parseJsonText(readJsonFileText(path), path);
}

namespace {

// Renders `value` into `out` until `out` holds more than `budget` characters: a message needs
// the start of a value, never the whole of a large one.
void renderJson(const Json& value, std::string& out, std::size_t budget) {
    if (out.size() > budget) return;
    if (value.is_object() || value.is_array()) {
        const bool object = value.is_object();
        out += object ? '{' : '[';
        bool first = true;
        for (auto it = value.begin(); it != value.end() && out.size() <= budget; ++it) {
            if (!first) out += ", ";
            first = false;
            if (object) out += Json(it.key()).dump(-1, ' ', false, Json::error_handler_t::replace) + ": ";
            renderJson(it.value(), out, budget);
        }
        out += object ? '}' : ']';
        return;
    }
    if (value.is_string() && value.get_ref<const std::string&>().size() > budget) {
        // The cut may fall inside a character of several bytes: dumped with replacement.
        out += Json(value.get_ref<const std::string&>().substr(0, budget))
                   .dump(-1, ' ', false, Json::error_handler_t::replace);
        return;
    }
    out += value.dump(-1, ' ', false, Json::error_handler_t::replace);
}

}  // namespace

std::string describeJson(const Json& value) {
    constexpr std::size_t kShown = 60;
    std::string s;
    renderJson(value, s, kShown);
    if (s.size() > kShown) s = s.substr(0, kShown - 3) + "...";
    return s;
}

JsonFields::JsonFields(const Json& object, std::string source, std::string pointer)
    : object_(&object), source_(std::move(source)), pointer_(std::move(pointer)) {
    if (!object.is_object())
        throw InputError(source_, pointer_.empty() ? "/" : pointer_,
                         "expected a JSON object ({...}), found " + describeJson(object));
}

void JsonFields::fail(const std::string& key, const std::string& problem) const {
    throw InputError(source_, placeOf(key), problem);
}

void JsonFields::rejectUnknownKeys(const std::vector<std::string>& known) const {
    for (auto it = object_->begin(); it != object_->end(); ++it) {
        bool ok = false;
        for (const auto& k : known) ok = ok || it.key() == k;
        if (!ok) {
            std::string list;
            for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
            fail(it.key(), "unknown key '" + it.key() + "'; the keys allowed here are: " + list);
        }
    }
}

void JsonFields::rejectUnknownKeys(std::initializer_list<const char*> known) const {
    rejectUnknownKeys(std::vector<std::string>(known.begin(), known.end()));
}

static std::string rangeText(double lo, double hi) {
    return "between " + numberText(lo) + " and " + numberText(hi);
}

double JsonFields::number(const std::string& key, double lo, double hi) const {
    if (!has(key)) fail(key, "missing required number '" + key + "' (" + rangeText(lo, hi) + ")");
    const Json& v = raw(key);
    if (!v.is_number())
        fail(key, "expected a number " + rangeText(lo, hi) + ", found " + describeJson(v));
    const double d = v.get<double>();
    if (!std::isfinite(d) || d < lo || d > hi)
        fail(key, "'" + key + "' is " + describeJson(v) + ", outside the allowed range (" +
                      rangeText(lo, hi) + ")");
    return d;
}

double JsonFields::number(const std::string& key, double lo, double hi, double fallback) const {
    return has(key) ? number(key, lo, hi) : fallback;
}

int JsonFields::integer(const std::string& key, long lo, long hi) const {
    if (!has(key))
        fail(key, "missing required whole number '" + key + "' (" +
                      rangeText(double(lo), double(hi)) + ")");
    const Json& v = raw(key);
    if (!v.is_number_integer())
        fail(key, "expected a whole number " + rangeText(double(lo), double(hi)) + ", found " +
                      describeJson(v));
    // An unsigned value above `hi` may not fit a long (it would wrap), so it is compared first.
    const bool aboveAsUnsigned =
        v.is_number_unsigned() && v.get<unsigned long long>() > static_cast<unsigned long long>(hi);
    if (aboveAsUnsigned || v.get<long>() < lo || v.get<long>() > hi)
        fail(key, "'" + key + "' is " + describeJson(v) + ", outside the allowed range (" +
                      rangeText(double(lo), double(hi)) + ")");
    return static_cast<int>(v.get<long>());
}

int JsonFields::integer(const std::string& key, long lo, long hi, int fallback) const {
    return has(key) ? integer(key, lo, hi) : fallback;
}

std::string JsonFields::text(const std::string& key) const {
    if (!has(key)) fail(key, "missing required text '" + key + "'");
    const Json& v = raw(key);
    if (!v.is_string()) fail(key, "expected text in quotes, found " + describeJson(v));
    return v.get<std::string>();
}

std::string JsonFields::text(const std::string& key, const std::string& fallback) const {
    return has(key) ? text(key) : fallback;
}

bool JsonFields::flag(const std::string& key, bool fallback) const {
    if (!has(key)) return fallback;
    const Json& v = raw(key);
    if (!v.is_boolean()) fail(key, "expected true or false, found " + describeJson(v));
    return v.get<bool>();
}

Vec2 JsonFields::point(const std::string& key) const {
    if (!has(key)) fail(key, "missing required point '" + key + "' ([x, y] in mm)");
    const Json& v = raw(key);
    if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number())
        fail(key, "expected a point [x, y] in mm, found " + describeJson(v));
    const Vec2 p{v[0].get<double>(), v[1].get<double>()};
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) fail(key, "the point must be finite");
    return p;
}

Vec2 JsonFields::point(const std::string& key, Vec2 fallback) const {
    return has(key) ? point(key) : fallback;
}

std::vector<double> JsonFields::numbers(const std::string& key, double lo, double hi) const {
    if (!has(key)) fail(key, "missing required list of numbers '" + key + "'");
    const Json& v = raw(key);
    if (!v.is_array()) fail(key, "expected a list of numbers, found " + describeJson(v));
    std::vector<double> out;
    for (std::size_t i = 0; i < v.size(); ++i) {
        if (!v[i].is_number() || !std::isfinite(v[i].get<double>()) || v[i].get<double>() < lo ||
            v[i].get<double>() > hi)
            throw InputError(
                source_, placeOf(key) + "/" + std::to_string(i),
                "expected a number " + rangeText(lo, hi) + ", found " + describeJson(v[i]));
        out.push_back(v[i].get<double>());
    }
    return out;
}

JsonFields JsonFields::object(const std::string& key) const {
    if (!has(key)) fail(key, "missing required section '" + key + "'");
    return JsonFields(raw(key), source_, placeOf(key));
}

}  // namespace activetouch
