#include "core/records/FramesImport.h"

#include <filesystem>

#include "core/common/InputError.h"
#include "core/io/Csv.h"
#include "core/io/InputFile.h"
#include "core/io/OutputFile.h"

namespace activetouch {

namespace fs = std::filesystem;

void writeFramesImport(const std::string& folder, const FramesImport& frames,
                       const std::vector<std::string>& digests) {
    const FramesLayout& layout = frames.layout;
    int widest = 0;
    for (const auto& f : layout.fingers) widest = std::max(widest, f.taxels);
    OutputFile csv((fs::path(folder) / "frames.csv").string());
    csv.print("file,frame,time_s,finger");
    for (int k = 0; k < widest; ++k) csv.print(",taxel_%d", k);
    csv.put('\n');
    Json files = Json::array();
    const int taxels = layout.taxelCount();
    for (std::size_t i = 0; i < frames.files.size(); ++i) {
        const FramesFile& file = frames.files[i];
        const std::string name = fs::path(file.path).filename().string();
        for (int frame = 0; frame < file.frames; ++frame) {
            int offset = 0;
            for (const auto& finger : layout.fingers) {
                csv.print("%s,%d,", name.c_str(), frame);
                if (!file.times_s.empty()) csv.print("%.9g", file.times_s[std::size_t(frame)]);
                csv.print(",%s", finger.name.c_str());
                for (int k = 0; k < widest; ++k) {
                    csv.put(',');
                    if (k < finger.taxels) csv.print("%.9g", file.at(frame, offset + k, taxels));
                }
                csv.put('\n');
                offset += finger.taxels;
            }
        }
        files.push_back({{"file", name}, {"frames", file.frames}, {"sha256", digests[i]}});
    }
    csv.close();
    OutputFile json((fs::path(folder) / "frames.json").string());
    json.print("%s\n", Json{{"layout_file", frames.layout.source},
                            {"layout", frames.layoutDocument},
                            {"files", files}}
                           .dump(2)
                           .c_str());
    json.close();
}

FramesImport readFramesImport(const std::string& folder) {
    const std::string jsonPath = (fs::path(folder) / "frames.json").string();
    if (!fs::exists(jsonPath))
        throw InputError(folder, "", "holds no frames.json: give a folder import-frames wrote");
    FramesImport out;
    const Json doc = readJsonFile(jsonPath);
    const JsonFields f(doc, jsonPath, "");
    if (!f.has("layout") || !f.has("files") || !f.raw("files").is_array())
        throw InputError(jsonPath, "", "is not a frames import (it needs 'layout' and 'files')");
    out.layoutDocument = f.raw("layout");
    out.layout = parseFramesLayout(out.layoutDocument, jsonPath + " (its layout)");
    if (f.has("layout_file") && f.raw("layout_file").is_string())
        out.layout.source = f.raw("layout_file").get<std::string>();
    const int taxels = out.layout.taxelCount();
    for (const Json& file : f.raw("files")) {
        FramesFile ff;
        ff.path = JsonFields(file, jsonPath, "/files").text("file");
        ff.frames = JsonFields(file, jsonPath, "/files").integer("frames", 1, 1 << 30);
        ff.pressures.assign(std::size_t(ff.frames) * std::size_t(taxels), 0.0);
        out.files.push_back(std::move(ff));
    }
    const std::string csvPath = (fs::path(folder) / "frames.csv").string();
    std::ifstream in = openInputFile(csvPath);
    BoundedLines lines(in, csvPath, 1u << 20, "this is not a frames.csv");
    std::string line;
    lines.next(line);  // the header
    std::size_t file = 0;
    while (lines.next(line)) {
        const std::vector<std::string> row = splitCsvLine(line);
        const int n = lines.number();
        while (file < out.files.size() && row.at(0) != out.files[file].path) ++file;
        if (row.size() < 4 || file == out.files.size())
            throw InputError(csvPath, "line " + std::to_string(n),
                             "names a file frames.json does not list, or out of order");
        FramesFile& ff = out.files[file];
        const int frame = csvInteger(row[1], csvPath, n, "frame");
        if (frame < 0 || frame >= ff.frames)
            throw InputError(
                csvPath, "line " + std::to_string(n),
                "frame " + row[1] + " is past the file's " + std::to_string(ff.frames) + " frames");
        if (!row[2].empty()) {
            if (ff.times_s.size() != std::size_t(frame))
                throw InputError(csvPath, "line " + std::to_string(n), "a time stamp out of order");
            ff.times_s.push_back(csvNumber(row[2], csvPath, n, "time_s"));
        }
        int offset = 0;
        bool known = false;
        for (const auto& finger : out.layout.fingers) {
            if (finger.name == row[3]) {
                known = true;
                if (row.size() < std::size_t(4 + finger.taxels))
                    throw InputError(csvPath, "line " + std::to_string(n), "too few taxels");
                for (int k = 0; k < finger.taxels; ++k) {
                    const double v = csvNumber(row[std::size_t(4 + k)], csvPath, n, "taxel");
                    if (v < 0.0 || v > out.layout.fullScale)
                        throw InputError(csvPath, "line " + std::to_string(n),
                                         "a pressure outside 0..full scale");
                    ff.pressures[std::size_t(frame) * std::size_t(taxels) +
                                 std::size_t(offset + k)] = v;
                }
            }
            offset += finger.taxels;
        }
        if (!known)
            throw InputError(csvPath, "line " + std::to_string(n),
                             "finger '" + row[3] + "' is not in the layout");
    }
    return out;
}

}  // namespace activetouch
