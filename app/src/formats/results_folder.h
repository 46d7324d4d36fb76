// A results folder (--out DIR) owned by one run at a time. Results never mix and are never lost:
//   - a folder that already holds results is refused unless the run resumes it (--resume) or
//     starts afresh (--overwrite);
//   - --overwrite sets the old folder aside and removes it only once the new run has its first
//     complete result; a run that fails or is interrupted before that puts it back;
//   - an advisory lock (DIR/.lock, holding the owner's pid and command) refuses a second run into
//     the same folder while the first is alive;
//   - temporaries of dead processes are removed when a run opens the folder.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace app {

enum class FolderMode {
    Fresh,      // the folder must be missing or empty
    Resume,     // the folder must hold an earlier run of this command
    Overwrite,  // whatever the folder holds is replaced by this run's results
};

class ResultsFolder {
public:
    // Throws UsageError (exit 2) when the folder is locked by a live run, holds results and the mode
    // is Fresh, holds nothing to resume, or cannot be created.
    ResultsFolder(const std::filesystem::path& dir, FolderMode mode, const std::string& command);
    ~ResultsFolder();
    ResultsFolder(const ResultsFolder&) = delete;
    ResultsFolder& operator=(const ResultsFolder&) = delete;

    const std::filesystem::path& Dir() const { return dir_; }
    FolderMode Mode() const { return mode_; }

    // The run has a complete result: the folder set aside by --overwrite is no longer needed.
    void FirstResultDone();

private:
    std::filesystem::path dir_;
    FolderMode mode_;
    int lockFd_ = -1;
    std::filesystem::path setAside_;  // --overwrite: the previous results, until FirstResultDone
};

// Whether a folder holds anything but its lock file and temporaries.
bool HoldsResults(const std::filesystem::path& dir);

// What a run was started with beyond its experiments (a comparison's files, seeds and budget, the
// reproduction's folder and part), kept in a record in its folder so that --resume continues that
// run and no other: a setting given again on resume must say what the record says.
struct RunSetting {
    std::string key;             // in the record
    std::string option;          // as the user gives it, for messages ("--seeds")
    bool given = false;          // given on this command line
    nlohmann::ordered_json value;  // what this command line says (its default when not given)
};
// Fresh or overwritten runs: the settings as given. Resumed runs: the record's, after refusing
// (UsageError) a given setting that differs from it, or a folder without the record.
nlohmann::ordered_json RunRecord(const std::filesystem::path& record, FolderMode mode, const std::vector<RunSetting>& settings);

}  // namespace app
