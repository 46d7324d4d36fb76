// One search run's designs, each evaluated once through the recorder: the simulation is
// deterministic, so asking again changes speed only. A design is known by its key (its text, fibre
// genes included) and may carry a second evaluation recorded right after it (the thesis's stretch
// test, or the inflation to twice the target). Results are kept without their meshes; the meshes of
// the designs a contact sheet shows are kept from this session or read back from the archive.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "evaluation/recorder.h"

namespace app {

class DesignCache {
public:
    struct Request {
        std::string key;
        sim::EvalJob job;
        std::optional<sim::EvalJob> second{};  // evaluated right after `job`, tagged "<label><secondLabel>"
        std::string secondLabel{};
    };
    struct Design {
        std::uint64_t id = 0;                   // the first evaluation's id in the archive
        sim::SimResult result;                  // without meshes
        std::optional<sim::SimResult> second;   // without meshes
    };
    // `keyOf` names a stored record's design; `isSecond` says whether a stored record is a second
    // evaluation. With `keepMeshes`, this session's meshes are kept for MeshesOf (contact sheets).
    DesignCache(Recorder& recorder, int run, std::function<std::string(const sim::EvalJob&)> keyOf,
                std::function<bool(const sim::EvalJob&)> isSecond, bool keepMeshes);

    // After a resume: what this run had evaluated up to its checkpoint (records of other runs and
    // other roles are left alone).
    void Restore(const std::vector<ArchiveRecord>& records);
    // The generation the next evaluations are tagged with.
    void SetGeneration(int generation) { generation_ = generation; }

    // Evaluates the requests whose key is new (the same new key twice in one batch once), in order,
    // and returns every request's design.
    std::vector<const Design*> Evaluate(const std::vector<Request>& requests);

    const Design& Of(const std::string& key) const { return designs_.at(key); }

    // The full results (meshes included) of these designs, in order; the kept meshes are then
    // trimmed to them.
    std::vector<const sim::SimResult*> MeshesOf(const std::vector<std::string>& keys);

private:
    Recorder& recorder_;
    int run_;
    int generation_ = 0;
    std::function<std::string(const sim::EvalJob&)> keyOf_;
    std::function<bool(const sim::EvalJob&)> isSecond_;
    bool keepMeshes_;
    std::unordered_map<std::string, Design> designs_;
    std::unordered_map<std::string, sim::SimResult> meshes_;
};

}  // namespace app
