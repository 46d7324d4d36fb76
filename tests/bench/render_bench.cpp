// Speed of pictures: one 1024x768 shaded, 2x-supersampled frame, PNG encoding, and a 60-frame
// turntable with encoding overlapped as `actuator render` does it.
//   build/tests/render_bench --benchmark_repetitions=5
#include <benchmark/benchmark.h>

#include <future>
#include <numbers>

#include "render/mesh_renderer.h"
#include "sim/solver.h"
#include "sim/surface.h"

namespace {

struct Fixture {
    sim::SimResult result = sim::Evaluate(sim::SineShape{4.1, 0.5, std::numbers::pi - 0.5}, sim::DefaultMeshDef(), sim::DefaultSimParams());
    std::unique_ptr<render::MeshRenderer> renderer;
    Fixture() {
        std::string error;
        renderer = render::MeshRenderer::Create(render::DefaultRenderDef(), &error);
        if (!renderer) std::abort();
    }
    render::Scene Turntable(int frame, int frames) const {
        render::Scene scene;
        scene.surface = std::make_shared<const sim::Surface>(sim::HelixSurface(sim::DefaultMeshDef()));
        scene.title = "sine A = 4.1";
        scene.lines = {"fitness 0.5818"};
        scene.panels = {{result.final, result.initial, "turntable", 360.0 * frame / frames}};
        scene.framing = render::FrameMeshes({&result.final});
        return scene;
    }
};

Fixture& Shared() {
    static Fixture fixture;
    return fixture;
}

void BM_RenderFrame(benchmark::State& state) {
    Fixture& f = Shared();
    for (auto _ : state) benchmark::DoNotOptimize(f.renderer->Render(f.Turntable(0, 1)).rgba.data());
}

void BM_EncodePng(benchmark::State& state) {
    Fixture& f = Shared();
    const render::Image image = f.renderer->Render(f.Turntable(0, 1));
    for (auto _ : state) benchmark::DoNotOptimize(render::EncodePng(image, static_cast<int>(state.range(0))).size());
}

void BM_RenderAndEncodeFrame(benchmark::State& state) {
    Fixture& f = Shared();
    for (auto _ : state) benchmark::DoNotOptimize(render::EncodePng(f.renderer->Render(f.Turntable(0, 1)), 1).size());
}

void BM_Turntable60(benchmark::State& state) {
    Fixture& f = Shared();
    for (auto _ : state) {
        std::future<size_t> pending;
        for (int k = 0; k < 60; ++k) {
            render::Image image = f.renderer->Render(f.Turntable(k, 60));
            if (pending.valid()) benchmark::DoNotOptimize(pending.get());
            pending = std::async(std::launch::async, [image = std::move(image)] { return render::EncodePng(image, 1).size(); });
        }
        benchmark::DoNotOptimize(pending.get());
    }
    state.counters["frames/s"] = benchmark::Counter(60, benchmark::Counter::kIsIterationInvariantRate);
}

}  // namespace

BENCHMARK(BM_RenderFrame)->Unit(benchmark::kMillisecond)->UseRealTime();  // llvmpipe works on its own threads
BENCHMARK(BM_EncodePng)->Arg(1)->Arg(6)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RenderAndEncodeFrame)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Turntable60)->Unit(benchmark::kMillisecond)->Iterations(3)->UseRealTime();

BENCHMARK_MAIN();
