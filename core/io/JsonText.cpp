#include "core/io/JsonText.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <utility>
#include <vector>

#include "core/common/InputError.h"
#include "core/io/InputFile.h"

namespace activetouch {
namespace {

struct Place {
    std::size_t line = 1, column = 1;
    std::string text() const {
        return "line " + std::to_string(line) + ", column " + std::to_string(column);
    }
};

// One open object or list while scanning: for an object, the keys so far and where each stood,
// and whether the next string is a key; for a list, the index of the current element.
struct Frame {
    bool object = false;
    bool expectKey = true;
    std::size_t index = 0;
    std::string key;  // the current key, for the pointer
    std::map<std::string, Place> keys;
};

void appendUtf8(std::string& out, unsigned long cp) {
    if (cp < 0x80) {
        out += static_cast<char>(cp);
    } else if (cp < 0x800) {
        out += static_cast<char>(0xC0 | (cp >> 6));
        out += static_cast<char>(0x80 | (cp & 0x3F));
    } else if (cp < 0x10000) {
        out += static_cast<char>(0xE0 | (cp >> 12));
        out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
        out += static_cast<char>(0x80 | (cp & 0x3F));
    } else {
        out += static_cast<char>(0xF0 | (cp >> 18));
        out += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
        out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
        out += static_cast<char>(0x80 | (cp & 0x3F));
    }
}

std::string pointerEscaped(const std::string& key) {
    std::string out;
    for (char c : key) {
        if (c == '~')
            out += "~0";
        else if (c == '/')
            out += "~1";
        else
            out += c;
    }
    return out;
}

class Scanner {
public:
    Scanner(const std::string& text, const std::string& source) : t_(text), source_(source) {}

    void run() {
        while (i_ < t_.size()) {
            const char c = t_[i_];
            if (c == '"') {
                if (!string()) return;  // unterminated: the parser says where
                continue;
            }
            if (c == '{' || c == '[') {
                if (stack_.size() >= static_cast<std::size_t>(kMaxJsonDepth))
                    throw InputError(source_, here().text(),
                                     "objects and lists are nested more than " +
                                         std::to_string(kMaxJsonDepth) +
                                         " levels deep here; no workbench file nests that deep, "
                                         "so this is not one of its files");
                Frame f;
                f.object = c == '{';
                stack_.push_back(std::move(f));
            } else if (c == '}' || c == ']') {
                if (stack_.empty()) return;
                stack_.pop_back();
            } else if (c == ',') {
                if (!stack_.empty()) {
                    if (stack_.back().object)
                        stack_.back().expectKey = true;
                    else
                        ++stack_.back().index;
                }
            } else if (c == ':') {
                if (!stack_.empty() && stack_.back().object) stack_.back().expectKey = false;
            } else if (c == '-' || (c >= '0' && c <= '9')) {
                number();
                continue;
            }
            advance();
        }
    }

private:
    Place here() const { return place_; }

    void advance() {
        if (t_[i_] == '\n') {
            ++place_.line;
            place_.column = 1;
        } else {
            ++place_.column;
        }
        ++i_;
    }

    std::string pointer() const {
        std::string p;
        for (const Frame& f : stack_) {
            p += '/';
            p += f.object ? pointerEscaped(f.key) : std::to_string(f.index);
        }
        return p;
    }

    // Reads a string starting at the quote; false if it does not end (left to the parser).
    bool string() {
        const Place start = here();
        const bool isKey = !stack_.empty() && stack_.back().object && stack_.back().expectKey;
        advance();
        std::string value;
        while (i_ < t_.size()) {
            const char c = t_[i_];
            if (c == '"') {
                advance();
                if (isKey) key(value, start);
                return true;
            }
            if (c == '\n') return false;
            if (c == '\\') {
                if (i_ + 1 >= t_.size()) return false;
                const char e = t_[i_ + 1];
                advance();
                advance();
                if (!isKey) continue;
                switch (e) {
                    case 'b': value += '\b'; break;
                    case 'f': value += '\f'; break;
                    case 'n': value += '\n'; break;
                    case 'r': value += '\r'; break;
                    case 't': value += '\t'; break;
                    case 'u': {
                        unsigned long cp = 0;
                        if (!hex4(cp)) return false;
                        if (cp >= 0xD800 && cp < 0xDC00 && i_ + 1 < t_.size() && t_[i_] == '\\' &&
                            t_[i_ + 1] == 'u') {
                            advance();
                            advance();
                            unsigned long low = 0;
                            if (!hex4(low)) return false;
                            if (low >= 0xDC00 && low < 0xE000)
                                cp = 0x10000 + ((cp - 0xD800) << 10) + (low - 0xDC00);
                        }
                        appendUtf8(value, cp);
                        break;
                    }
                    default: value += e; break;
                }
                continue;
            }
            if (isKey) value += c;
            advance();
        }
        return false;
    }

    bool hex4(unsigned long& out) {
        if (i_ + 4 > t_.size()) return false;
        for (int k = 0; k < 4; ++k) {
            const char h = t_[i_];
            int d = -1;
            if (h >= '0' && h <= '9') d = h - '0';
            if (h >= 'a' && h <= 'f') d = h - 'a' + 10;
            if (h >= 'A' && h <= 'F') d = h - 'A' + 10;
            if (d < 0) return false;
            out = out * 16 + static_cast<unsigned long>(d);
            advance();
        }
        return true;
    }

    void key(const std::string& name, Place where) {
        Frame& f = stack_.back();
        if (const auto it = f.keys.find(name); it != f.keys.end()) {
            f.key = name;
            throw InputError(source_, where.text() + " (" + pointer() + ")",
                             "the key '" + name + "' appears twice in one object, first at " +
                                 it->second.text() +
                                 "; only one of them could take effect, so keep the one you mean");
        }
        f.keys.emplace(name, where);
        f.key = name;
    }

    void number() {
        const Place start = here();
        const std::size_t begin = i_;
        while (i_ < t_.size()) {
            const char c = t_[i_];
            if (!((c >= '0' && c <= '9') || c == '-' || c == '+' || c == '.' || c == 'e' ||
                  c == 'E'))
                break;
            advance();
        }
        const std::string token = t_.substr(begin, i_ - begin);
        if (token.size() > 400)
            throw InputError(source_, start.text(),
                             "a number " + std::to_string(token.size()) +
                                 " characters long; write it with an exponent (e.g. 1.5e3)");
        const double v = std::strtod(token.c_str(), nullptr);
        if (std::isinf(v))
            throw InputError(source_, start.text(),
                             "the number " + token +
                                 " is beyond the range of a double (about 1.8e308); no "
                                 "setting is that large, so give the value you mean");
    }

    const std::string& t_;
    const std::string& source_;
    std::size_t i_ = 0;
    Place place_;
    std::vector<Frame> stack_;
};

}  // namespace

void checkJsonText(const std::string& text, const std::string& source) {
    Scanner(text, source).run();
}

std::string readJsonFileText(const std::string& path) {
    return readBoundedFile(path, kMaxJsonFileBytes,
                           "an experiment, scene, rig or fingertip file (a few kilobytes)");
}

}  // namespace activetouch
