// Every design, setting and result survives the Cap'n Proto schema unchanged, and a value this
// build does not know is an error rather than a silent default.
#include "formats/schema_convert.h"
#include "sim/batch.h"

#include <capnp/message.h>
#include <gtest/gtest.h>

#include <bit>
#include <numbers>

TEST(SchemaConvert, EveryShapeAndSettingRoundTrips) {
    sim::Positions mesh;
    mesh.x = {0.1, 0.2, 1e-300};
    mesh.y = {1, 2, 3};
    mesh.z = {-1, 0.5, 7};
    const std::vector<sim::Shape> shapes{sim::CylinderShape{}, sim::SineShape{4.1, 0.5, std::numbers::pi - 0.5}, sim::AbsSineShape{3, 0, 4 * std::numbers::pi},
                                         sim::BSplineShape{sim::SplineRegion::Entire, {{1, 2, 3, 4}, {5, 6, 7, 8, 9}}},
                                         sim::FreeXYShape{{0.1, 0.2}, {0.3, 0.4}}, sim::MeshShape{mesh}};
    sim::SimParams params;
    params.iterations = 1234;
    params.load = sim::Load::None;
    params.springConstant = 0.123;
    params.pressureScale = 0.0042;
    params.pullForce = 0.9;
    params.stepScale = 0.06;
    params.divergenceLimit = 55;
    params.precision = sim::Precision::Double;
    for (const auto& shape : shapes) {
        capnp::MallocMessageBuilder message;
        const sim::EvalJob job{shape, sim::ModelKind::Thesis, sim::ThesisDef{sim::MeshDef{12, 7}, params}};
        app::SetJob(message.initRoot<app::schema::EvalRequest>(), job);
        const sim::EvalJob back = app::GetJob(message.getRoot<app::schema::EvalRequest>().asReader());
        EXPECT_EQ(back.shape, shape) << sim::ShapeName(shape);
        EXPECT_EQ(back.Thesis().mesh.resolution, 12);
        EXPECT_EQ(back.Thesis().mesh.turns, 7);
        EXPECT_EQ(back.Thesis().params.iterations, 1234);
        EXPECT_EQ(back.Thesis().params.load, sim::Load::None);
        EXPECT_EQ(back.Thesis().params.springConstant, 0.123);
        EXPECT_EQ(back.Thesis().params.pressureScale, 0.0042);
        EXPECT_EQ(back.Thesis().params.pullForce, 0.9);
        EXPECT_EQ(back.Thesis().params.stepScale, 0.06);
        EXPECT_EQ(back.Thesis().params.divergenceLimit, 55);
        EXPECT_EQ(back.Thesis().params.precision, sim::Precision::Double);
    }
}

TEST(SchemaConvert, ResultsAndStatusesRoundTrip) {
    for (const auto& [status, name] : sim::EnumNames<sim::Status>::table) {
        capnp::MallocMessageBuilder message;
        sim::SimResult r;
        r.status = status;
        r.fitness = 0.25;
        r.contractionPercent = 1.5;
        r.iterationsRun = 77;
        r.elapsedMs = 3.5;
        app::SetResultNumbers(message.initRoot<app::schema::EvalResult>(), r, sim::ModelKind::Thesis);
        sim::SimResult back;
        app::GetResultNumbers(message.getRoot<app::schema::EvalResult>().asReader(), back);
        EXPECT_EQ(back.status, status) << name;
        EXPECT_EQ(back.fitness, 0.25);
        EXPECT_EQ(back.iterationsRun, 77);
    }
}

// Every field of a shell def and of a shell result, each set away from its default, comes back equal.
TEST(SchemaConvert, ShellJobsAndOutputsRoundTrip) {
    sim::EvalJob job;
    job.shape = sim::SineShape{1.3, 0.5, 2.5};
    job.SetModel(sim::ModelKind::Membrane);
    sim::ShellDef& d = job.Shell();
    d.geometry = {7.5, 90, 1.25, 24, 40, 3, 0.5, sim::EndCondition::Sliding};
    d.material = sim::MaterialPresetDef(sim::MaterialPreset::DragonSkin10);
    d.material.law = sim::MaterialLaw::Yeoh;
    d.material.muKpa = 31;
    d.material.c01Kpa = 2;
    d.material.c20Kpa = 0.5;
    d.material.c30Kpa = 0.01;
    d.material.stretchLimit = 3.5;
    d.load.kind = sim::ShellLoad::Gas;
    d.load.pressureKpa = 12.5;
    d.load.forceN = -0.25;
    d.load.volumeRatio = 1.75;
    d.load.strokePercent = 7.5;
    d.load.strokeMm = 2.5;  // the def's check refuses both at once; the record keeps what it is given
    d.ends.twist = sim::TwistEnd::Loaded;
    d.ends.torqueNMm = -3.25;
    d.load.steps = 9;
    d.load.isobaricPoints = 7;
    d.solver = {1e-9, 77, 4, false};
    capnp::MallocMessageBuilder message;
    app::SetJob(message.initRoot<app::schema::EvalRequest>(), job);
    const sim::EvalJob back = app::GetJob(message.getRoot<app::schema::EvalRequest>().asReader());
    EXPECT_EQ(back.model, sim::ModelKind::Membrane);
    EXPECT_EQ(back.shape, job.shape);
    const sim::ShellDef& b = back.Shell();
    EXPECT_EQ(std::tie(b.geometry.radiusMm, b.geometry.lengthMm, b.geometry.thicknessMm, b.geometry.ringVertices, b.geometry.rings, b.geometry.clampMm,
                       b.geometry.edgeSpacingMm, b.geometry.ends),
              std::tie(d.geometry.radiusMm, d.geometry.lengthMm, d.geometry.thicknessMm, d.geometry.ringVertices, d.geometry.rings, d.geometry.clampMm,
                       d.geometry.edgeSpacingMm, d.geometry.ends));
    EXPECT_EQ(std::tie(b.material.preset, b.material.law, b.material.muKpa, b.material.c10Kpa, b.material.c01Kpa, b.material.c20Kpa, b.material.c30Kpa,
                       b.material.tensileStrengthKpa, b.material.elongationAtBreak, b.material.stretchLimit, b.material.densityKgPerM3),
              std::tie(d.material.preset, d.material.law, d.material.muKpa, d.material.c10Kpa, d.material.c01Kpa, d.material.c20Kpa, d.material.c30Kpa,
                       d.material.tensileStrengthKpa, d.material.elongationAtBreak, d.material.stretchLimit, d.material.densityKgPerM3));
    EXPECT_EQ(std::tie(b.load.kind, b.load.pressureKpa, b.load.forceN, b.load.volumeRatio, b.load.strokePercent, b.load.strokeMm, b.ends.twist, b.ends.torqueNMm,
                       b.load.steps, b.load.isobaricPoints),
              std::tie(d.load.kind, d.load.pressureKpa, d.load.forceN, d.load.volumeRatio, d.load.strokePercent, d.load.strokeMm, d.ends.twist, d.ends.torqueNMm,
                       d.load.steps, d.load.isobaricPoints));
    EXPECT_EQ(std::tie(b.solver.tolerance, b.solver.maxIterations, b.solver.maxBisections, b.solver.selfContact),
              std::tie(d.solver.tolerance, d.solver.maxIterations, d.solver.maxBisections, d.solver.selfContact));

    sim::SimResult r;
    r.status = sim::Status::LimitPoint;
    r.fitness = NAN;
    sim::ShellOutputs& o = r.shell;
    o.curvePressureKpa = {1, 2, 3.25};
    o.curveContractionPercent = {-0.1, -0.5, -1.25};
    o.curveVolumeMm3 = {100, 120, 150};
    o.targetPressureKpa = 3.25;
    o.limitPressureKpa = 3.5;
    o.blockingForceN = -0.125;
    o.axialStiffnessNPerMm = 0.0625;
    o.restVolumeMm3 = 90;
    o.volumeMm3 = 150;
    o.maxStretch = 1.75;
    o.maxStressKpa = 40;
    o.stretchLimit = 5.5;
    o.tensileStrengthKpa = 1379;
    o.displacementMm = 0.75;
    o.newtonIterations = 31;
    o.factorizations = 33;
    o.twistDeg = 12.5;
    o.twistPerLengthDegPerMm = 0.125;
    o.torqueNMm = -2.5;
    o.strokeForceN = 0.375;
    o.curveForceN = {0, 0.5, 0.75};
    o.curveTwistDeg = {1, 2, 4};
    o.isobaricContractionPercent = {0, 2.5, 5};
    o.isobaricForceN = {1.5, NAN, 0};
    o.workPerStrokeMj = 4.25;
    o.workPerGramMjPerG = 0.875;
    capnp::MallocMessageBuilder resultMessage;
    app::SetResultNumbers(resultMessage.initRoot<app::schema::EvalResult>(), r, job.model);
    sim::SimResult got;
    app::GetResultNumbers(resultMessage.getRoot<app::schema::EvalResult>().asReader(), got);
    const sim::ShellOutputs& g = got.shell;
    EXPECT_EQ(got.status, sim::Status::LimitPoint);
    EXPECT_EQ(g.curvePressureKpa, o.curvePressureKpa);
    EXPECT_EQ(g.curveContractionPercent, o.curveContractionPercent);
    EXPECT_EQ(g.curveVolumeMm3, o.curveVolumeMm3);
    EXPECT_EQ(g.curveForceN, o.curveForceN);
    EXPECT_EQ(g.curveTwistDeg, o.curveTwistDeg);
    EXPECT_EQ(g.isobaricContractionPercent, o.isobaricContractionPercent);
    ASSERT_EQ(g.isobaricForceN.size(), 3u);
    EXPECT_EQ(g.isobaricForceN[0], 1.5);
    EXPECT_TRUE(std::isnan(g.isobaricForceN[1])) << "a failed point stays failed";
    EXPECT_EQ(std::tie(g.workPerStrokeMj, g.workPerGramMjPerG), std::tie(o.workPerStrokeMj, o.workPerGramMjPerG));
    EXPECT_EQ(std::tie(g.twistDeg, g.twistPerLengthDegPerMm, g.torqueNMm, g.strokeForceN),
              std::tie(o.twistDeg, o.twistPerLengthDegPerMm, o.torqueNMm, o.strokeForceN));
    EXPECT_EQ(std::tie(g.targetPressureKpa, g.limitPressureKpa, g.blockingForceN, g.axialStiffnessNPerMm, g.restVolumeMm3, g.volumeMm3, g.maxStretch,
                       g.maxStressKpa, g.stretchLimit, g.tensileStrengthKpa, g.displacementMm, g.newtonIterations, g.factorizations),
              std::tie(o.targetPressureKpa, o.limitPressureKpa, o.blockingForceN, o.axialStiffnessNPerMm, o.restVolumeMm3, o.volumeMm3, o.maxStretch,
                       o.maxStressKpa, o.stretchLimit, o.tensileStrengthKpa, o.displacementMm, o.newtonIterations, o.factorizations));
}

TEST(SchemaConvert, AThesisRecordReadsAsTheThesisModel) {
    // Records written before the shell models have no model field: it reads as 0, thesis.
    capnp::MallocMessageBuilder message;
    const sim::EvalJob job{sim::CylinderShape{}, sim::ModelKind::Thesis, sim::ThesisDef{sim::MeshDef{12, 7}, sim::DefaultSimParams()}};
    app::SetJob(message.initRoot<app::schema::Evaluation>(), job);
    EXPECT_EQ(message.getRoot<app::schema::Evaluation>().asReader().getModel(), app::schema::ModelKind::THESIS);
    EXPECT_FALSE(message.getRoot<app::schema::Evaluation>().asReader().hasShell());
    EXPECT_EQ(app::GetJob(message.getRoot<app::schema::Evaluation>().asReader()).model, sim::ModelKind::Thesis);
}

// Records written before the top clamp could turn have no twist: they read as held, as they were
// evaluated (a re-simulation gives their numbers again), while a new job's default is free.
TEST(SchemaConvert, AShellRecordFromBeforeTheTwistReadsAsHeld) {
    capnp::MallocMessageBuilder message;
    sim::EvalJob job;
    job.SetModel(sim::ModelKind::Shell);
    ASSERT_EQ(job.Shell().ends.twist, sim::TwistEnd::Free);
    app::SetJob(message.initRoot<app::schema::EvalRequest>(), job);
    EXPECT_EQ(app::GetJob(message.getRoot<app::schema::EvalRequest>().asReader()).Shell().ends.twist, sim::TwistEnd::Free);
    message.getRoot<app::schema::EvalRequest>().getShell().disownTwist();  // as an older build wrote it
    EXPECT_EQ(app::GetJob(message.getRoot<app::schema::EvalRequest>().asReader()).Shell().ends.twist, sim::TwistEnd::Held);
}

TEST(SchemaConvert, AnUnknownMaterialNameIsAnError) {
    capnp::MallocMessageBuilder message;
    sim::EvalJob job;
    job.SetModel(sim::ModelKind::Shell);
    app::SetJob(message.initRoot<app::schema::EvalRequest>(), job);
    message.getRoot<app::schema::EvalRequest>().getShell().setPreset("unobtainium");
    EXPECT_THROW(app::GetJob(message.getRoot<app::schema::EvalRequest>().asReader()), std::runtime_error);
}

TEST(SchemaConvert, AnUnknownEnumValueIsAnError) {
    capnp::MallocMessageBuilder message;
    auto params = message.initRoot<app::schema::SimParams>();
    params.setLoad(static_cast<app::schema::Load>(9));
    EXPECT_THROW(app::GetParams(params.asReader()), std::runtime_error);
}

TEST(SchemaConvert, JobsAndResultsAsBytesRoundTripExactlyAndGarbageIsRefused) {
    sim::EvalJob job;
    job.shape = sim::BSplineShape{sim::SplineRegion::Entire, {{1, 3, 5, 2, 0}, {8, 0, 4, 4, 4}}};
    job.Thesis().params = sim::DefaultSimParams();
    job.Thesis().params.iterations = 300;
    job.Thesis().mesh = sim::MeshDef{12, 9};
    const sim::EvalJob back = app::JobFromBytes(app::JobBytes(job));
    EXPECT_EQ(app::JobBytes(back), app::JobBytes(job));
    EXPECT_EQ(std::get<sim::BSplineShape>(back.shape), std::get<sim::BSplineShape>(job.shape));
    EXPECT_EQ(back.Thesis().params.iterations, 300);
    EXPECT_EQ(back.Thesis().mesh.resolution, 12);

    const sim::SimResult result = sim::Evaluate(job);
    const sim::SimResult again = app::ResultFromBytes(app::ResultBytes(result, job.model));
    EXPECT_EQ(again.status, result.status);
    EXPECT_EQ(std::bit_cast<std::uint64_t>(again.fitness), std::bit_cast<std::uint64_t>(result.fitness));
    EXPECT_EQ(again.final.x, result.final.x);
    EXPECT_EQ(again.initial.z, result.initial.z);

    for (const std::string& bad : {std::string(), std::string("1234567"), std::string(16, '\xff'), app::JobBytes(job).substr(0, 16)})
        EXPECT_THROW(app::JobFromBytes(bad), std::runtime_error) << bad.size() << " bytes";
    EXPECT_THROW(app::ResultFromBytes(std::string(24, '\0') + "garbage!"), std::runtime_error);
}

// Records written before clamps were in millimetres held them by ring count: they read back as the
// same length (three clamp rings at 59 rings of a 150 mm tube: two spacings, 5.17 mm), so an old
// archive's designs are the same problem they were.
TEST(SchemaConvert, ARecordWithClampRingsReadsAsTheSameLengthInMillimetres) {
    sim::ShellDef d;
    d.geometry.rings = 59;
    capnp::MallocMessageBuilder message;
    auto builder = message.initRoot<app::schema::ShellDef>();
    app::SetShellDef(builder, d);
    builder.setClampMm(0);
    builder.setClampRings(3);
    builder.setEdgeSpacingMm(0);  // records before it had evenly spaced rings
    const sim::ShellDef back = app::GetShellDef(builder.asReader());
    EXPECT_NEAR(back.geometry.clampMm, 2 * 150.0 / 58, 1e-12);
    EXPECT_EQ(sim::ClampRingCount(back.geometry), 3);
    builder.setClampMm(7.5);  // a record with the length keeps it
    EXPECT_EQ(app::GetShellDef(builder.asReader()).geometry.clampMm, 7.5);
}
