// Cost of sending one evaluation over the wire: encoding a response (result plus the initial and
// final 30x30 meshes at full precision) into bytes, and decoding it back.
//   build/tests/wire_bench
#include <benchmark/benchmark.h>
#include <capnp/message.h>
#include <capnp/serialize.h>

#include "schema_convert.h"

namespace {

const sim::SimResult& Sample() {
    static const sim::SimResult result = [] {
        sim::SimParams params = sim::DefaultSimParams();
        params.iterations = 100;
        return sim::Evaluate(sim::SineShape{4.1, 0.5, 2.64}, sim::DefaultMeshDef(), params);
    }();
    return result;
}

kj::Array<capnp::word> Encode(const sim::SimResult& r) {
    capnp::MallocMessageBuilder message;
    auto response = message.initRoot<app::schema::EvalResponse>();
    response.initResult().setFitness(r.fitness);
    app::SetExactMesh(response.initInitial(), r.initial);
    app::SetExactMesh(response.initFinal(), r.final);
    return capnp::messageToFlatArray(message);
}

void BM_EncodeResponse(benchmark::State& state) {
    for (auto _ : state) benchmark::DoNotOptimize(Encode(Sample()).size());
    state.counters["bytes"] = static_cast<double>(Encode(Sample()).asBytes().size());
}

void BM_DecodeResponse(benchmark::State& state) {
    const auto words = Encode(Sample());
    for (auto _ : state) {
        capnp::FlatArrayMessageReader reader(words);
        auto response = reader.getRoot<app::schema::EvalResponse>();
        benchmark::DoNotOptimize(app::GetExactMesh(response.getFinal()).x.data());
        benchmark::DoNotOptimize(app::GetExactMesh(response.getInitial()).x.data());
    }
}

}  // namespace

BENCHMARK(BM_EncodeResponse)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_DecodeResponse)->Unit(benchmark::kMicrosecond);
BENCHMARK_MAIN();
