// Every design, setting and result survives the Cap'n Proto schema unchanged, and a value this
// build does not know is an error rather than a silent default.
#include "schema_convert.h"

#include <capnp/message.h>
#include <gtest/gtest.h>

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
        const sim::EvalJob job{shape, sim::MeshDef{12, 7}, params};
        app::SetJob(message.initRoot<app::schema::EvalRequest>(), job);
        const sim::EvalJob back = app::GetJob(message.getRoot<app::schema::EvalRequest>().asReader());
        EXPECT_EQ(back.shape, shape) << sim::ShapeName(shape);
        EXPECT_EQ(back.mesh.resolution, 12);
        EXPECT_EQ(back.mesh.turns, 7);
        EXPECT_EQ(back.params.iterations, 1234);
        EXPECT_EQ(back.params.load, sim::Load::None);
        EXPECT_EQ(back.params.springConstant, 0.123);
        EXPECT_EQ(back.params.pressureScale, 0.0042);
        EXPECT_EQ(back.params.pullForce, 0.9);
        EXPECT_EQ(back.params.stepScale, 0.06);
        EXPECT_EQ(back.params.divergenceLimit, 55);
        EXPECT_EQ(back.params.precision, sim::Precision::Double);
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
        app::SetResultNumbers(message.initRoot<app::schema::EvalResult>(), r);
        sim::SimResult back;
        app::GetResultNumbers(message.getRoot<app::schema::EvalResult>().asReader(), back);
        EXPECT_EQ(back.status, status) << name;
        EXPECT_EQ(back.fitness, 0.25);
        EXPECT_EQ(back.iterationsRun, 77);
    }
}

TEST(SchemaConvert, AnUnknownEnumValueIsAnError) {
    capnp::MallocMessageBuilder message;
    auto params = message.initRoot<app::schema::SimParams>();
    params.setLoad(static_cast<app::schema::Load>(9));
    EXPECT_THROW(app::GetParams(params.asReader()), std::runtime_error);
}
