#include "sim/mesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

TEST(Mesh, ThirtyByThirtyHasOneSpringPerNeighbourPair) {
    // docs/models/thesis.md's rule, (i, i+1), (i, i+R), (i, i+R-1), (i, i+R+1) for every pair inside the mesh, gives
    // 899 + 870 + 871 + 869 = 3509. (docs/models/thesis.md's prose says 3508; its rule and its known values hold.)
    EXPECT_EQ(sim::SpringCount(sim::DefaultMeshDef()), 899 + 870 + 871 + 869);
    EXPECT_EQ(sim::VertexCount(sim::DefaultMeshDef()), 900);
}

TEST(Mesh, HelixRisesOneTurnPerResolutionVertices) {
    const sim::MeshDef def{30, 30};
    const sim::Positions p = sim::BaseHelix(def);
    ASSERT_EQ(p.Size(), 900);
    EXPECT_DOUBLE_EQ(p.z[0], 1.0 / 30);
    EXPECT_DOUBLE_EQ(p.z[899], 30.0);
    // Vertex i+R sits straight above vertex i, one unit higher.
    for (int i : {0, 17, 450, 868}) {
        EXPECT_NEAR(p.x[i + 30], p.x[i], 1e-12);
        EXPECT_NEAR(p.y[i + 30], p.y[i], 1e-12);
        EXPECT_NEAR(p.z[i + 30] - p.z[i], 1.0, 1e-12);
        EXPECT_NEAR(std::hypot(p.x[i], p.y[i]), 1.0, 1e-12);
    }
    // Vertex 0 at angle 0: (sin 0, cos 0) = (0, 1).
    EXPECT_NEAR(p.x[0], 0.0, 1e-15);
    EXPECT_NEAR(p.y[0], 1.0, 1e-15);
}

TEST(Mesh, ClampsHoldTwoTurnsAtEachEnd) {
    const sim::MeshDef def{30, 30};
    EXPECT_TRUE(sim::IsClamped(def, 0));
    EXPECT_TRUE(sim::IsClamped(def, 59));
    EXPECT_FALSE(sim::IsClamped(def, 60));
    EXPECT_FALSE(sim::IsClamped(def, 839));
    EXPECT_TRUE(sim::IsClamped(def, 840));
}

TEST(Mesh, TrianglesCoverEveryQuadOnce) {
    const sim::MeshDef def{30, 30};
    const auto triangles = sim::Triangles(def);
    EXPECT_EQ(triangles.size(), 2u * (900 - 31));
    EXPECT_EQ(triangles[0], (std::array<int, 3>{0, 1, 31}));
    EXPECT_EQ(triangles[1], (std::array<int, 3>{0, 31, 30}));
}
