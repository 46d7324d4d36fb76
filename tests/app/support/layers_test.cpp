// The architecture as the tree shows it (docs/architecture.md): sim includes nothing of render or
// app, render nothing of app, and inside app each folder includes only folders below it in the
// order commands -> report -> experiments -> {pictures, evaluation, options} -> {materials, fields} -> formats -> support.
// No folder holds more than about 20 source files.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>

namespace fs = std::filesystem;

namespace {

const fs::path kRoot = fs::path(ACTUATOR_ASSETS_DIR).parent_path();

// Every #include "..." of the C++ files under `dir`, as (file, included path).
std::vector<std::pair<fs::path, std::string>> Includes(const fs::path& dir) {
    std::vector<std::pair<fs::path, std::string>> found;
    const std::regex include(R"re(^\s*#include\s+"([^"]+)")re");
    for (const auto& e : fs::recursive_directory_iterator(dir)) {
        const auto ext = e.path().extension();
        if (ext != ".cpp" && ext != ".h" && ext != ".inc") continue;
        std::ifstream in(e.path());
        for (std::string line; std::getline(in, line);) {
            std::smatch m;
            if (std::regex_search(line, m, include)) found.push_back({e.path(), m[1]});
        }
    }
    return found;
}

}  // namespace

TEST(Layers, LibrariesIncludeOnlyDownward) {
    for (const auto& [file, included] : Includes(kRoot / "sim")) {
        EXPECT_NE(included.rfind("render/", 0), 0u) << file << " includes " << included;
        for (const char* app : {"commands/", "report/", "experiments/", "pictures/", "evaluation/", "options/", "materials/", "fields/", "formats/", "support/"})
            EXPECT_NE(included.rfind(app, 0), 0u) << file << " includes " << included;
    }
    for (const auto& [file, included] : Includes(kRoot / "render"))
        for (const char* app : {"commands/", "report/", "experiments/", "pictures/", "evaluation/", "options/", "materials/", "fields/", "formats/", "support/"})
            EXPECT_NE(included.rfind(app, 0), 0u) << file << " includes " << included;
}

TEST(Layers, AppFoldersIncludeOnlyFoldersBelowThem) {
    const std::map<std::string, int> order{{"commands", 0},   {"report", 1},  {"experiments", 2}, {"pictures", 3}, {"evaluation", 3},
                                           {"options", 3},    {"materials", 4}, {"fields", 4},    {"formats", 5},   {"support", 6}};
    std::set<std::pair<std::string, std::string>> pairs;
    for (const auto& [folder, level] : order) {
        ASSERT_TRUE(fs::is_directory(kRoot / "app" / "src" / folder)) << folder;
        for (const auto& [file, included] : Includes(kRoot / "app" / "src" / folder)) {
            const std::string target = included.substr(0, included.find('/'));
            if (!order.count(target) || target == folder) continue;
            pairs.insert({folder, target});
            EXPECT_GE(order.at(target), level) << fs::relative(file, kRoot) << " includes " << included << ", a folder above it";
        }
    }
    for (const auto& [a, b] : pairs) EXPECT_FALSE(pairs.count({b, a})) << a << " and " << b << " include each other";
}

TEST(Layers, NoFolderHoldsMoreThanAboutTwentySourceFiles) {
    for (const char* top : {"app/src", "sim/src", "sim/include/sim", "render/src", "tests"}) {
        for (const auto& e : fs::recursive_directory_iterator(kRoot / top)) {
            if (!e.is_directory() && fs::path(top) != "app/src") continue;
            const fs::path dir = e.is_directory() ? e.path() : kRoot / top;
            int files = 0;
            for (const auto& f : fs::directory_iterator(dir))
                if (f.path().extension() == ".cpp" || f.path().extension() == ".h") ++files;
            EXPECT_LE(files, 22) << fs::relative(dir, kRoot) << ": about 20 at most";
        }
    }
}
