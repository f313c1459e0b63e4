#include "app/cli/CommandLine.h"

#include <QCommandLineOption>
#include <QCommandLineParser>
#include <QStringList>
#include <algorithm>

namespace activetouch::cli {

namespace {

QString bare(const std::string& option) {
    return QString::fromStdString(option.substr(option.find_first_not_of('-')));
}

/// The argument as typed that named the option QCommandLineParser did not know as `name`.
std::string typedAs(const std::vector<std::string>& args, const QString& name) {
    for (const std::string& a : args) {
        if (a.size() < 2 || a[0] != '-') continue;
        const std::string word = a.substr(0, a.find('='));
        if (bare(word) == name) return word;
    }
    std::string word = "-";  // one dash: QCommandLineParser reads -word as --word
    word += name.toStdString();
    return word;
}

}  // namespace

bool CommandLine::has(const std::string& flag) const {
    return std::find(flags.begin(), flags.end(), flag) != flags.end();
}

std::string CommandLine::value(const std::string& option) const {
    const auto it = values.find(option);
    return it == values.end() ? std::string() : it->second;
}

CommandLine parseCommandLine(const CommandSyntax& syntax, const std::vector<std::string>& args) {
    QCommandLineParser parser;
    // "-out" is --out, not -o -u -t; a "--" ends the options.
    parser.setSingleDashWordOptionMode(QCommandLineParser::ParseAsLongOptions);
    for (const auto& [option, what] : syntax.values)
        parser.addOption(QCommandLineOption(bare(option), QString(), QString::fromStdString(what)));
    for (const std::string& flag : syntax.flags) parser.addOption(QCommandLineOption(bare(flag)));
    QStringList list{QStringLiteral("activetouch-cli")};
    for (const std::string& a : args) list << QString::fromLocal8Bit(a.c_str());

    CommandLine r;
    if (!parser.parse(list)) {
        if (const QStringList unknown = parser.unknownOptionNames(); !unknown.isEmpty()) {
            r.error = "unknown option '" + typedAs(args, unknown.front()) + "'";
        } else {
            // The one other way parsing fails: a value option last, with nothing after it.
            r.error = parser.errorText().toStdString();
            for (const auto& [option, what] : syntax.values)
                if (!args.empty() && bare(args.back().substr(0, args.back().find('='))) ==
                                         bare(option))
                    r.error = option + " needs " + what;
        }
        return r;
    }
    for (const QString& p : parser.positionalArguments())
        r.positional.push_back(p.toLocal8Bit().toStdString());
    for (const auto& [option, what] : syntax.values)
        if (parser.isSet(bare(option))) {
            r.values[option] = parser.value(bare(option)).toLocal8Bit().toStdString();
            // An empty value names nothing: never read as if the option were not given.
            if (r.values[option].empty() && r.error.empty())
                r.error = option + " was given an empty value; it needs " + what;
        }
    for (const std::string& flag : syntax.flags)
        if (parser.isSet(bare(flag))) r.flags.push_back(flag);
    return r;
}

}  // namespace activetouch::cli
