// test_sizes: no production file (core/, devices/, app/; .cpp and .h) over 500 lines and no
// function in one over 80 (docs/design.md §1). Names every file and function past its bound.
//   check_sizes <repository>    checks the tree; exit 1 naming what is over
//   check_sizes --self-test     shows that it finds a long file and a long function
//
// A function is found as a brace block opened where only namespaces, classes and linkage blocks
// enclose it, after a head with a parameter list and no '=' outside parentheses (so aggregate
// initialisers and lambdas assigned to variables are not functions). Comments, string and
// character literals (raw strings too) are skipped. Its length is the lines from its first line
// (the head's) to its closing brace.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

constexpr int kMaxFileLines = 500;
constexpr int kMaxFunctionLines = 80;

struct Finding {
    std::string where;  ///< "file:line"
    std::string what;
};

/// `text` with comments and literals blanked (newlines kept, so lines still count).
std::string code(const std::string& text) {
    std::string out = text;
    std::size_t i = 0;
    auto blank = [&](std::size_t from, std::size_t to) {
        for (std::size_t k = from; k < to && k < out.size(); ++k)
            if (out[k] != '\n') out[k] = ' ';
    };
    while (i < text.size()) {
        if (text.compare(i, 2, "//") == 0) {
            const std::size_t end = text.find('\n', i);
            blank(i, end == std::string::npos ? text.size() : end);
            i = end == std::string::npos ? text.size() : end;
        } else if (text.compare(i, 2, "/*") == 0) {
            const std::size_t end = text.find("*/", i + 2);
            const std::size_t stop = end == std::string::npos ? text.size() : end + 2;
            blank(i, stop);
            i = stop;
        } else if (text[i] == 'R' && i + 1 < text.size() && text[i + 1] == '"') {
            const std::size_t paren = text.find('(', i + 2);
            const std::string delimiter = ")" + text.substr(i + 2, paren - i - 2) + "\"";
            const std::size_t end = text.find(delimiter, paren);
            const std::size_t stop =
                end == std::string::npos ? text.size() : end + delimiter.size();
            blank(i + 1, stop);
            i = stop;
        } else if (text[i] == '"' ||
                   (text[i] == '\'' &&
                    !(i > 0 && std::isxdigit(static_cast<unsigned char>(text[i - 1]))))) {
            const char quote = text[i];
            std::size_t k = i + 1;
            while (k < text.size() && text[k] != quote && text[k] != '\n')
                k += text[k] == '\\' ? 2 : 1;
            blank(i + 1, k);
            i = k + 1;
        } else {
            ++i;
        }
    }
    return out;
}

/// The identifier before the head's parameter list: "MainWindow::openExperiment".
std::string nameOf(const std::string& head) {
    static const std::regex name(R"(([~A-Za-z_][A-Za-z_0-9:~]*(?:operator\s*\S+?)?)\s*\()");
    std::smatch m;
    if (std::regex_search(head, m, name)) return m[1];
    return "(a function)";
}

bool isContainerHead(const std::string& head) {
    static const std::regex container(R"(\b(namespace|class|struct|union|enum|extern)\b)");
    return std::regex_search(head, container) && head.find('(') == std::string::npos;
}

bool isFunctionHead(const std::string& head) {
    if (head.find(')') == std::string::npos) return false;
    int depth = 0;
    for (std::size_t i = 0; i < head.size(); ++i) {
        const char c = head[i];
        if (c == '(') ++depth;
        if (c == ')') --depth;
        if (c == '=' && depth == 0 && head.rfind("operator", i) == std::string::npos) return false;
    }
    return true;
}

void checkFileLength(const std::string& file, const std::string& text, std::vector<Finding>& out) {
    const int lines = static_cast<int>(std::count(text.begin(), text.end(), '\n')) +
                      (text.empty() || text.back() == '\n' ? 0 : 1);
    if (lines > kMaxFileLines)
        out.push_back({file,
                       std::to_string(lines) + " lines, over " + std::to_string(kMaxFileLines) +
                           ": split it where its responsibilities divide"});
}

/// Functions over kMaxFunctionLines in `text` (preprocessor lines already blanked).
void checkFunctions(const std::string& file, const std::string& text, std::vector<Finding>& out) {
    const std::string c = code(text);
    enum Kind { Container, Function, Other };
    struct Scope {
        Kind kind;
        int firstLine;
        std::string name;
    };
    std::vector<Scope> stack;
    std::string head;
    int line = 1, headLine = 1;
    bool headStarted = false;
    for (char ch : c) {
        if (ch == '\n') ++line;
        if (ch == '{') {
            const bool atTop = std::all_of(stack.begin(), stack.end(),
                                           [](const Scope& s) { return s.kind == Container; });
            Kind kind = Other;
            if (atTop && isContainerHead(head))
                kind = Container;
            else if (atTop && isFunctionHead(head))
                kind = Function;
            stack.push_back({kind, headStarted ? headLine : line, nameOf(head)});
            head.clear();
            headStarted = false;
        } else if (ch == '}') {
            if (!stack.empty()) {
                const Scope s = stack.back();
                stack.pop_back();
                const int length = line - s.firstLine + 1;
                if (s.kind == Function && length > kMaxFunctionLines)
                    out.push_back({file + ":" + std::to_string(s.firstLine),
                                   s.name + " is " + std::to_string(length) + " lines, over " +
                                       std::to_string(kMaxFunctionLines) +
                                       ": split it into named steps"});
            }
            head.clear();
            headStarted = false;
        } else if (ch == ';') {
            head.clear();
            headStarted = false;
        } else {
            if (!headStarted && !std::isspace(static_cast<unsigned char>(ch))) {
                headStarted = true;
                headLine = line;
            }
            if (headStarted) head += ch == '\n' ? ' ' : ch;
        }
    }
}

/// Preprocessor lines blanked: their text is no head of anything.
std::string withoutDirectives(const std::string& text) {
    std::istringstream in(text);
    std::string out, l;
    bool continued = false;
    while (std::getline(in, l)) {
        const auto first = l.find_first_not_of(" \t");
        const bool directive = continued || (first != std::string::npos && l[first] == '#');
        continued = directive && !l.empty() && l.back() == '\\';
        out += (directive ? std::string() : l) + "\n";
    }
    return out;
}

std::vector<Finding> checkTree(const fs::path& top) {
    std::vector<Finding> findings;
    for (const char* layer : {"core", "devices", "app"}) {
        std::vector<fs::path> files;
        for (const auto& e : fs::recursive_directory_iterator(top / layer)) {
            const std::string ext = e.path().extension().string();
            if (e.is_regular_file() && (ext == ".cpp" || ext == ".h")) files.push_back(e.path());
        }
        std::sort(files.begin(), files.end());
        for (const fs::path& f : files) {
            std::ifstream in(f, std::ios::binary);
            const std::string text((std::istreambuf_iterator<char>(in)), {});
            const std::string name = fs::relative(f, top).generic_string();
            checkFileLength(name, text, findings);
            checkFunctions(name, withoutDirectives(text), findings);
        }
    }
    return findings;
}

int selfTest() {
    std::string longFunction = "namespace a {\nint f(int x) {\n";
    for (int i = 0; i < 85; ++i) longFunction += "    x += " + std::to_string(i) + ";\n";
    longFunction += "    return x;\n}\nconst int kTable[] = {\n1,\n2};\n}\n";
    std::string shortOnes =
        "struct S {\n  int g() const { return 1; }\n};\nauto h = [](int y) {\n  return y;\n};\n"
        "const char* t = \"{{{\";  // {\n";
    std::string longFile;
    for (int i = 0; i < 501; ++i) longFile += "// line\n";
    std::vector<Finding> found;
    checkFunctions("long_function.cpp", withoutDirectives(longFunction), found);
    checkFunctions("short.cpp", withoutDirectives(shortOnes), found);
    checkFileLength("short.cpp", shortOnes, found);
    checkFileLength("long_file.cpp", longFile, found);
    const bool ok = found.size() == 2 && found[0].where == "long_function.cpp:2" &&
                    found[0].what.rfind("f is 88 lines", 0) == 0 &&
                    found[1].where == "long_file.cpp";
    for (const Finding& x : found) std::printf("%s: %s\n", x.where.c_str(), x.what.c_str());
    std::printf(ok ? "self-test: the check finds a long function and a long file, and nothing "
                     "else\n"
                   : "self-test FAILED: the check does not find what it should\n");
    return ok ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc == 2 && std::string(argv[1]) == "--self-test") return selfTest();
    if (argc != 2) {
        std::fprintf(stderr, "usage: check_sizes <repository> | --self-test\n");
        return 2;
    }
    const std::vector<Finding> findings = checkTree(argv[1]);
    for (const Finding& x : findings) std::printf("%s: %s\n", x.where.c_str(), x.what.c_str());
    std::printf("%zu production files or functions over their bounds (%d lines a file, %d a "
                "function)\n",
                findings.size(), kMaxFileLines, kMaxFunctionLines);
    return findings.empty() ? 0 : 1;
}
