#include "experiments/experiment_library.h"

#include <algorithm>

#include "support/errors.h"

namespace app {

namespace fs = std::filesystem;

std::vector<fs::path> ExperimentFolders() {
    std::vector<fs::path> folders;
    for (const fs::path folder : {fs::path(ACTUATOR_ASSETS_DIR) / "experiments", fs::path(ACTUATOR_INSTALLED_ASSETS_DIR) / "experiments"}) {
        std::error_code ec;
        if (fs::is_directory(folder, ec) && std::find(folders.begin(), folders.end(), folder) == folders.end()) folders.push_back(folder);
    }
    return folders;
}

fs::path FindExperimentFile(const std::string& given) {
    std::error_code ec;
    if (given.empty()) throw UsageError("no experiment file given");
    if (fs::exists(given, ec)) return given;  // a folder or device is refused by the reader, with its reason
    const fs::path asGiven(given);
    const bool isName = !asGiven.has_parent_path();
    std::vector<fs::path> found;
    const std::vector<fs::path> folders = ExperimentFolders();
    if (isName) {
        const std::string file = asGiven.extension() == ".json" ? given : given + ".json";
        for (const fs::path& folder : folders) {
            for (fs::recursive_directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec))
                if (it->is_regular_file(ec) && it->path().filename() == file) found.push_back(it->path());
            if (!found.empty()) break;  // the source tree's copy over an installed one
        }
    }
    if (found.size() == 1) return found.front();
    std::sort(found.begin(), found.end());
    if (found.size() > 1) {
        std::string list;
        for (const fs::path& f : found) list += (list.empty() ? "" : ", ") + f.string();
        throw UsageError("the experiment name " + Quote(given) + " matches more than one file (" + list + "): give its path");
    }
    std::string where = "looked for " + fs::absolute(asGiven, ec).lexically_normal().string();
    if (isName) {
        where += folders.empty() ? "; no shipped experiments are on this machine" : " and for a shipped experiment of that name in ";
        for (size_t k = 0; k < folders.size(); ++k) where += (k ? " and " : "") + folders[k].string();
    }
    throw UsageError("cannot open the experiment " + Quote(given) + ": " + where);
}

}  // namespace app
