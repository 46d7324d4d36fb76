// Files the way the workbench treats them: inputs read with a size limit, outputs written whole or
// not at all (a short temporary beside the target, then rename), never onto something that is not
// a regular file of ours, and temporaries cleaned up when a run is interrupted.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace app {

// Inputs larger than this are refused before they are read whole (an OBJ of a 1024 x 1024 mesh is
// about 60 MB).
constexpr std::uintmax_t kMaxInputBytes = 256ull << 20;

// The whole file. Refuses a folder, a device, a missing file and a file over `maxBytes` (pipes are
// read up to the limit), naming the file. Throws UsageError.
std::string ReadInputFile(const std::string& path, std::uintmax_t maxBytes = kMaxInputBytes);

// Whitespace-separated numbers (comments after '#'): a free-xy offset file holds "dx dy" per vertex.
std::vector<double> ReadNumberFile(const std::string& path);

// Refuses, before any long work, an output path that cannot be written as a regular file: an empty
// or too long name, a folder, a symlink or device in the way, a missing or read-only folder.
void CheckOutputPath(const std::string& path, const std::string& what);

// Refuses, before any long work, an output folder that exists and is not an empty folder (its files
// would mix with the new ones): "what DIR exists and is not an empty folder; ...".
void CheckNewOrEmptyFolder(const std::string& folder, const std::string& what);

// Empty when `name` can be one folder's name inside an output folder; otherwise why not (empty, "." or
// "..", a '/' or '\\', a control character, longer than 100 bytes).
std::string FolderNameError(const std::string& name);

// Refuses an output that is also an input of the same command (it would be overwritten).
void RefuseOutputThatIsInput(const std::string& output, const std::string& outputWhat, const std::vector<std::string>& inputs);

// Writes the whole file or nothing. Throws OutputError when the storage fails (a full disk, a quota,
// a file-size limit), UsageError otherwise (with the path and the system's reason).
void WriteFileAtomically(const std::string& path, const std::string& contents);

// The files one command writes appear together or not at all. While a batch is open, every
// WriteFileAtomically (on any thread: the frame writer's too) writes its temporary and leaves the
// rename to Commit; a batch that ends without Commit (bad input found late, a full disk) removes its
// temporaries, so no output of the command appears. One batch at a time, for commands that write a
// set of files once (simulate, render, export, inspect); runs that write as they go do not use it.
class OutputBatch {
public:
    OutputBatch();
    ~OutputBatch();
    OutputBatch(const OutputBatch&) = delete;
    OutputBatch& operator=(const OutputBatch&) = delete;
    // Renames every staged file onto its target, in the order they were written.
    void Commit();
};

// Folders a command creates for its outputs, removed again when it ends with them empty (it failed
// before any file was in place), so that a refused or failed command leaves nothing behind.
class CreatedFolders {
public:
    CreatedFolders() = default;
    ~CreatedFolders();
    CreatedFolders(const CreatedFolders&) = delete;
    CreatedFolders& operator=(const CreatedFolders&) = delete;
    // Creates `folder` and its missing parents, remembering those it made. Throws UsageError
    // ("what: cannot create folder ...") when the folder cannot be made.
    void Create(const std::filesystem::path& folder, const std::string& what);

private:
    std::vector<std::filesystem::path> created_;  // parents first
};

// On SIGINT and SIGTERM: remove this process's temporaries, run the registered restore step (see
// ResultsFolder), then die of the signal as usual. Installed once by main().
void InstallInterruptCleanup();
// A step run on interruption, e.g. putting back the folder that --overwrite set aside. It must be
// async-signal-safe; `nullptr` clears it.
void SetInterruptRestore(void (*restore)());

// Removes temporaries left in `folder` by processes that no longer exist (after SIGKILL).
void RemoveStaleTemporaries(const std::filesystem::path& folder);

// Flushes and closes stdout; false when what was printed could not be written (a full disk,
// /dev/full, a closed pipe).
bool CloseStdout();

// Cleared to a stable, short name: temporaries are ".act<pid>-<n>.tmp" beside their target.
bool IsTemporaryName(const std::string& fileName);

}  // namespace app
