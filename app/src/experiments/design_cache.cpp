#include "experiments/design_cache.h"

#include <fmt/format.h>

#include <algorithm>

namespace app {
namespace {

sim::SimResult WithoutMeshes(sim::SimResult r) {
    r.initial = {};
    r.final = {};
    r.shell.steps.clear();
    return r;
}

}  // namespace

DesignCache::DesignCache(Recorder& recorder, int run, std::function<std::string(const sim::EvalJob&)> keyOf,
                         std::function<bool(const sim::EvalJob&)> isSecond, bool keepMeshes)
    : recorder_(recorder), run_(run), keyOf_(std::move(keyOf)), isSecond_(std::move(isSecond)), keepMeshes_(keepMeshes) {}

void DesignCache::Restore(const std::vector<ArchiveRecord>& records) {
    for (const ArchiveRecord& r : records) {
        if (r.role != Role::Individual || r.run != run_) continue;
        const std::string key = keyOf_(r.job);
        if (isSecond_(r.job)) {
            designs_[key].second = WithoutMeshes(r.result);
            continue;
        }
        Design& d = designs_[key];
        d.id = r.id;
        d.result = WithoutMeshes(r.result);
    }
}

std::vector<const DesignCache::Design*> DesignCache::Evaluate(const std::vector<Request>& requests) {
    std::vector<sim::EvalJob> jobs;
    std::vector<EvaluationTag> tags;
    std::vector<std::string> jobKeys;
    std::vector<bool> seconds;
    const std::string label = fmt::format("run {} generation {}", run_, generation_);
    for (const Request& request : requests) {
        if (designs_.count(request.key) || std::find(jobKeys.begin(), jobKeys.end(), request.key) != jobKeys.end()) continue;
        jobs.push_back(request.job);
        tags.push_back({Role::Individual, run_, generation_, label});
        jobKeys.push_back(request.key);
        seconds.push_back(false);
        if (!request.second) continue;
        jobs.push_back(*request.second);
        tags.push_back({Role::Individual, run_, generation_, label + request.secondLabel});
        jobKeys.push_back(request.key);
        seconds.push_back(true);
    }
    recorder_.Evaluate(jobs, tags, [&](std::uint64_t id, size_t k, sim::SimResult&& r) {
        Design& d = designs_[jobKeys[k]];
        if (seconds[k]) {
            d.second = WithoutMeshes(std::move(r));
            return;
        }
        d.id = id;
        if (!keepMeshes_) {
            d.result = WithoutMeshes(std::move(r));
            return;
        }
        // The meshes moved aside while the rest is copied: a result's meshes are most of its size.
        sim::Positions initial = std::move(r.initial), last = std::move(r.final);
        auto steps = std::move(r.shell.steps);
        d.result = WithoutMeshes(r);
        r.initial = std::move(initial);
        r.final = std::move(last);
        r.shell.steps = std::move(steps);
        meshes_[jobKeys[k]] = std::move(r);
    });
    std::vector<const Design*> out;
    for (const Request& request : requests) out.push_back(&designs_.at(request.key));
    return out;
}

std::vector<const sim::SimResult*> DesignCache::MeshesOf(const std::vector<std::string>& keys) {
    std::vector<std::uint64_t> missing;
    for (const std::string& key : keys)
        if (!meshes_.count(key)) missing.push_back(designs_.at(key).id);
    for (ArchiveRecord& r : recorder_.ReadBack(missing)) meshes_[keyOf_(r.job)] = std::move(r.result);
    std::unordered_map<std::string, sim::SimResult> kept;
    for (const std::string& key : keys)
        if (!kept.count(key)) kept.emplace(key, std::move(meshes_.at(key)));
    meshes_ = std::move(kept);
    std::vector<const sim::SimResult*> out;
    for (const std::string& key : keys) out.push_back(&meshes_.at(key));
    return out;
}

}  // namespace app
