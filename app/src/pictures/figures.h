// Pictures shared by the commands: titles and result lines, the before/after and turntable scenes,
// the one "inflation + stretch (+ turntable)" figure set of a design, contact sheets, thumbnails,
// and PNG files written whole or not at all.
#pragma once

#include <filesystem>
#include <future>
#include <memory>
#include <string>
#include <vector>

#include "formats/record_sink.h"
#include "render/image.h"
#include "render/mesh_renderer.h"
#include "sim/batch.h"
#include "sim/names.h"
#include "sim/casting.h"
#include "sim/solid.h"

namespace app {

std::string ShapeTitle(const sim::Shape& shape);  // "sine  A = 4.1, phase 0.5 to pi-0.5"
std::string FibreTitle(const sim::FibreDef& fibres);  // "braid +/-30 deg", "bands 20, 35 deg", "" without fibres
std::string FibreTitle(const sim::EvalJob& job);     // the job's fibres; "" for a model without any
// A job's picture title: the shape, and under the membrane and shell models the model and the fibres
// ("sine  A = 1.3, ...  -  shell model,  braid +/-35 deg").
std::string JobTitle(const sim::EvalJob& job);
// Status and the model's numbers: fitness and contraction (thesis), contraction at the pressure,
// stretch against its limit and Newton iterations (membrane, shell); and the mesh size.
std::string ResultLine(const sim::SimResult& result, const sim::EvalJob& job);
std::string FitnessCaption(const sim::SimResult& result);  // "0.582" or the status
// ResultLine, and a warning line when the mesh exploded (EscapeWarning): the lines under a
// picture's title.
std::vector<std::string> ResultLines(const sim::SimResult& result, const sim::EvalJob& job);

// What colours the deformed mesh. `Auto` is displacement under the thesis model and the largest
// principal stretch under the membrane and shell models. `Gap` (contact on): how near each vertex's
// wall is to another, beyond a wall thickness; where walls touch.
enum class Colouring { Auto, Displacement, Strain, Stretch, Stress, Gap, None };
// Empty when the colouring suits the job's model; otherwise why not.
std::string ColouringError(Colouring colouring, const sim::EvalJob& job);

// The surface a job's meshes are drawn on (shared between pictures of one mesh size).
std::shared_ptr<const sim::Surface> SharedSurface(const sim::EvalJob& job);

// The mesh before (plain material) and after (coloured), one camera and scale. Under the membrane
// and shell models, "after" is the equilibrium at the target pressure, and stretch and stress
// colourings mark the material's limits on the colour bar.
render::Scene BeforeAfterScene(const std::string& title, const sim::SimResult& result, const sim::EvalJob& job, Colouring colouring = Colouring::Auto);
// One turntable frame: the final mesh turned `angleDegrees` about its axis. The default framing (a
// cylinder about the axis) and colour scale do not change with the angle: frames hold still.
render::Scene TurntableScene(const std::string& title, const sim::SimResult& result, const sim::EvalJob& job, double angleDegrees,
                             Colouring colouring = Colouring::Auto);
// A membrane or shell result's deformed mesh at load step `step` (0 .. steps-1) coloured like
// BeforeAfterScene, on a fixed framing and scale given by the caller.
render::Scene LoadStepScene(const std::string& title, const sim::SimResult& result, const sim::EvalJob& job, int step, Colouring colouring);

// Several designs, each before and after, `pairsPerRow` pairs to a row, on one camera and one colour
// scale (the report's "best of each run" and "the thesis's specimen beside ours"). Each pair is
// captioned "<label>: before" and "after: <fitness or status>". Each is drawn with its own job (its
// shape is the rest its stretch is measured from; its fibre genes say which fibres it has); all
// share one mesh size. Precondition: pairs is not empty.
struct DesignPair {
    const sim::SimResult* result;
    const sim::EvalJob* job;  // what was evaluated
    std::string label;
};
render::Scene PairsScene(const std::string& title, const std::vector<std::string>& lines, const std::vector<DesignPair>& pairs, int pairsPerRow);
// One design before and after each of several runs of the same load (e.g. 100 and 10,000 iterations:
// the thesis's Figure 5.2), one camera and colour scale.
render::Scene StagesScene(const std::string& title, const std::vector<std::string>& lines, const std::vector<const sim::SimResult*>& stages,
                          const sim::EvalJob& job);
// The scenes above drawn at a size that gives each panel about 240 x 420 pixels.
// One camera and one colour scale over a sequence's scenes (a time-lapse), so that only the mesh
// moves; the scale reaches the largest value any scene states (its result's max stretch or stress).
void ShareFramingAndScale(std::vector<render::Scene>& scenes);
render::Image PairsImage(const render::Scene& scene);

// An exported part's solids (sim/solid.h): the parts side by side with the mold's split faces turned
// to the camera, each part its own colour; and the actuator's wall cut open along its axis, the cut
// showing its thickness.
// `firstStage`: a fibre design's first-stage mold (its shells drawn beside the second's, its layer
// beside the wall).
render::Scene ExplodedMoldScene(const sim::PartSolids& solids, const std::string& title, const sim::PartSolids* firstStage = nullptr);
// A fibre design's first-stage layer with its guide grooves, and the threads to wind in them (each
// family in its colour): the winding picture of an export.
render::Scene WindingGuidesScene(const sim::PartSolids& layer, const std::vector<sim::FibreWinding>& winding, const std::string& title);
render::Scene CutawayScene(const sim::PartSolids& solids, const std::string& title);

// Throws UsageError when no renderer can be made.
std::unique_ptr<render::MeshRenderer> MakeRenderer(int width, int height, int supersample = 2, double textScale = 0);
std::unique_ptr<render::MeshRenderer> MakeRenderer(const render::RenderDef& def);

void WritePng(const std::string& path, const render::Image& image, int compressionLevel);

// Frames go to disk on another thread while the next one renders; at most one write in flight.
class FrameWriter {
public:
    explicit FrameWriter(int pngLevel) : pngLevel_(pngLevel) {}
    ~FrameWriter();
    void Write(std::string path, render::Image image);
    void Wait();  // rethrows a write error

private:
    int pngLevel_;
    std::future<void> pending_;
};

// A design's figures: `inflation.png`-style before/after under each load, and a turntable of the
// inflated mesh when `turntableFrames` > 0; under the membrane and shell models also the
// contraction-pressure curve, `pressure_curve.png`. Names are `prefix` + "inflation.png", ...
// Returns the files written, relative to `folder`.
struct DesignFigures {
    std::string title;
    const sim::SimResult* inflated = nullptr;
    const sim::SimResult* stretched = nullptr;  // may be null (always under the membrane and shell models)
    sim::EvalJob job;                           // the inflated design's job (model, mesh, units)
    int turntableFrames = 0;
    std::string prefix;  // "" for render, "best_" for experiments
    Colouring colouring = Colouring::Auto;
};
std::vector<std::string> WriteDesignFigures(render::MeshRenderer& renderer, const std::filesystem::path& folder, const DesignFigures& figures,
                                            int figureLevel = 6, int frameLevel = 1);

// Every mesh of a sweep or a generation in one picture: inflated, one camera and colour scale, a
// caption under each. Failed evaluations show what they have, captioned with the status.
struct SheetEntry {
    const sim::SimResult* result;
    std::string caption;
};
// A sheet laid out on a 2-D sweep's axes: `columns` cells to a row, labelled along both axes.
struct SheetAxes {
    int columns = 0;  // 0: a near-square grid
    std::vector<std::string> columnLabels, rowLabels;
    std::string columnTitle, rowTitle;
};
// One camera and one colour scale for all, taken from the meshes that stay within their own size:
// a mesh that moved farther (EscapeWarning) would otherwise shrink every other cell to a speck. Such
// meshes are marked "!" and counted under the title. `renderer` is kept between calls and made
// anew only when the sheet's size changes.
void WriteContactSheet(const std::filesystem::path& path, const std::string& title, const std::vector<SheetEntry>& entries,
                       const sim::EvalJob& job, std::unique_ptr<render::MeshRenderer>& renderer, const SheetAxes& axes = {});

// Non-empty when some vertex moved farther than the mesh's own size (its rest height or diameter,
// whichever is larger): "moved 57.7 on a 30-unit mesh". Such a result is not a physical state,
// whatever its status; sheets mark it and sweeps' results.csv carry it as a warning.
std::string EscapeWarning(const sim::SimResult& result);

// Small before/after pictures of single evaluations, named by evaluation id.
class Thumbnails final : public RecordSink {
public:
    explicit Thumbnails(std::filesystem::path folder);
    void Append(const ArchiveRecord& record) override;
    // Removes the thumbnails of the records past `keep`.
    void RollBack(std::uint64_t keep, const std::vector<ArchiveRecord>& kept) override;
    static std::string Name(std::uint64_t id);  // "evaluation_000017.png"
    const std::filesystem::path& Folder() const { return folder_; }

private:
    std::filesystem::path folder_;
    std::unique_ptr<render::MeshRenderer> renderer_;
};

}  // namespace app

template <>
struct sim::EnumNames<app::Colouring> {
    static constexpr std::array<std::pair<app::Colouring, const char*>, 7> table{{{app::Colouring::Auto, "auto"},
                                                                                  {app::Colouring::Displacement, "displacement"},
                                                                                  {app::Colouring::Strain, "strain"},
                                                                                  {app::Colouring::Stretch, "stretch"},
                                                                                  {app::Colouring::Stress, "stress"},
                                                                                  {app::Colouring::Gap, "gap"},
                                                                                  {app::Colouring::None, "none"}}};
};
