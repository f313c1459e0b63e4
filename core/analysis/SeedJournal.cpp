#include "core/analysis/SeedJournal.h"

#include <filesystem>
#include <fstream>

#include "core/analysis/OutcomeChecks.h"
#include "core/common/InputError.h"
#include "core/io/InputFile.h"
#include "core/io/JsonText.h"
#include "core/io/OutputFile.h"

namespace activetouch {
namespace fs = std::filesystem;

namespace {

Json journalHeader(const SeedShardFile& run) {
    return {{"experiment", run.experiment},
            {"fingerprint", run.fingerprint},
            {"range", {run.first, run.last}},
            {"shard", {run.shard.index, run.shard.count}}};
}

void writeLine(OutputFile& file, const Json& j) {
    file.print("%s\n", j.dump().c_str());
    file.flush();
}

/// The journal in `dir`, line by line, and its path; nothing where there is none.
std::optional<std::vector<std::string>> journalLines(const std::string& dir, std::string& path) {
    path = (fs::path(dir) / kSeedJournal).string();
    std::error_code ec;
    if (!fs::exists(path, ec)) return std::nullopt;
    std::ifstream in = openInputFile(path);
    BoundedLines lines(in, path, kMaxJsonFileBytes, "this is not a seeds journal");
    std::vector<std::string> all;
    for (std::string line; lines.next(line);) all.push_back(std::move(line));
    return all;
}

/// What the run a journal belongs to is, from its first line (the outcomes left empty).
SeedShardFile headerOf(const std::string& line, const std::string& path) {
    Json j;
    try {
        checkJsonText(line, path);
        j = Json::parse(line);
    } catch (const Json::exception&) {
        throw InputError(
            path, "line 1",
            "the journal's first line is damaged; start the run afresh with --replace");
    }
    JsonFields f(j, path, "line 1");
    SeedShardFile was;
    was.experiment = f.text("experiment");
    was.fingerprint = f.text("fingerprint");
    readShardPlace(f, &was.first, &was.last, &was.shard);
    return was;
}

/// A journal of another run than `run` is refused, naming what differs.
void checkSameRun(const SeedShardFile& was, const SeedShardFile& run, const std::string& path) {
    std::string differs;
    if (was.experiment != run.experiment || was.fingerprint != run.fingerprint)
        differs = "experiment '" + was.experiment + "' with other settings";
    else if (was.first != run.first || was.last != run.last)
        differs = "seeds " + std::to_string(was.first) + "-" + std::to_string(was.last);
    else if (was.shard.index != run.shard.index || was.shard.count != run.shard.count)
        differs =
            "shard " + std::to_string(was.shard.index) + "/" + std::to_string(was.shard.count);
    if (!differs.empty())
        throw InputError(path, "",
                         "this folder holds a run of " + differs +
                             " that was cut short, not of what was asked now; resume it with "
                             "the command that started it, or give --replace to start afresh");
}

}  // namespace

std::optional<JournalResume> readSeedJournal(const std::string& dir, const SeedShardFile& run,
                                             std::uint64_t first, std::uint64_t last) {
    std::string path;
    const auto lines = journalLines(dir, path);
    if (!lines) return std::nullopt;
    if (lines->empty())
        throw InputError(path, "", "the journal is empty; start the run afresh with --replace");
    checkSameRun(headerOf(lines->front(), path), run, path);
    JournalResume resume{{}, first, last};
    for (std::size_t i = 1; i < lines->size(); ++i) {
        const std::string place = "line " + std::to_string(i + 1);
        Json j;
        try {
            checkJsonText((*lines)[i], path + ", " + place);
            j = Json::parse((*lines)[i]);
        } catch (const std::exception&) {
            if (i + 1 == lines->size()) break;  // the line the run was writing when it was cut
            throw InputError(path, place, "damaged; start the run afresh with --replace");
        }
        SeedOutcome o = seedOutcomeFromJson(j, path, place);
        checkSeedOutcome(o, path, place);
        const std::uint64_t expected = first + resume.outcomes.size();
        if (o.seed != expected || o.seed > last)
            throw InputError(path, place,
                             "holds seed " + std::to_string(o.seed) + " where seed " +
                                 std::to_string(expected) +
                                 " comes next; start the run afresh with --replace");
        resume.outcomes.push_back(std::move(o));
    }
    return resume;
}

std::optional<CutShortShard> cutShortShard(const std::string& dir) {
    std::string path;
    const auto lines = journalLines(dir, path);
    if (!lines) return std::nullopt;
    CutShortShard c;
    if (lines->empty()) return c;
    const SeedShardFile was = headerOf(lines->front(), path);
    c.first = was.first;
    c.last = was.last;
    c.shard = was.shard;
    for (std::size_t i = 1; i < lines->size(); ++i)
        c.seedsDone += !(*lines)[i].empty() && (*lines)[i].back() == '}';
    return c;
}

SeedJournal::SeedJournal(const std::string& dir, const SeedShardFile& run,
                         const std::vector<SeedOutcome>& done)
    : file_(std::make_unique<OutputFile>((fs::path(dir) / kSeedJournal).string())) {
    writeLine(*file_, journalHeader(run));
    for (const SeedOutcome& o : done) writeLine(*file_, seedOutcomeJson(o));
}

SeedJournal::~SeedJournal() = default;

void SeedJournal::append(const SeedOutcome& o) {
    writeLine(*file_, seedOutcomeJson(o));
}

void SeedJournal::finish() {
    const std::string path = file_->path();
    file_->close();
    std::error_code ec;
    fs::remove(path, ec);
}

}  // namespace activetouch
