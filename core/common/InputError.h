#pragma once
// An error the user can cause and fix: a file, a setting, a value. It names the thing (`source`,
// usually a file path), the place inside it (`place`, a JSON pointer, a CSV line, a parameter),
// and the problem in a sentence that says what to do.
#include <stdexcept>
#include <string>

namespace activetouch {

/// `text` as a message quotes a value from a file: the whole of a short one, the start of a long
/// one (a path thousands of characters long is still refused in a readable sentence).
inline std::string shortened(const std::string& text, std::size_t most = 160) {
    return text.size() <= most ? text : text.substr(0, most) + "...";
}

class InputError : public std::runtime_error {
public:
    InputError(std::string source, std::string place, std::string problem)
        : std::runtime_error(compose(source, place, problem)),
          source_(std::move(source)),
          place_(std::move(place)),
          problem_(std::move(problem)) {}

    const std::string& source() const { return source_; }
    const std::string& place() const { return place_; }
    const std::string& problem() const { return problem_; }

    static std::string compose(const std::string& source, const std::string& place,
                               const std::string& problem) {
        std::string text = source.empty() ? std::string() : source;
        if (!place.empty()) text += (text.empty() ? "" : ": ") + std::string("at ") + place;
        text += (text.empty() ? "" : ": ") + problem;
        return text;
    }

private:
    std::string source_;
    std::string place_;
    std::string problem_;
};

}  // namespace activetouch
