#include "terratin/geometry/triangle_attributes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace terratin {
namespace {

// Angles come from atan2 of products of coordinate differences: a few ulps of 360 degrees.
constexpr double kAngleToleranceDeg = 1e-9;

constexpr double kDegreesPerRadian = 180.0 / std::numbers::pi;

// A counter-clockwise right triangle with legs of 10 m on the plane z = z0 + p x + q y,
// placed at UTM-like coordinates so that the large-offset case is what is tested.
struct PlaneTriangle {
    Point3 a, b, c;
};

PlaneTriangle onPlane(double p, double q, double z0 = 100.0) {
    constexpr double kX0 = 500000.0;
    constexpr double kY0 = 5000000.0;
    auto at = [&](double dx, double dy) {
        return Point3{kX0 + dx, kY0 + dy, z0 + p * dx + q * dy};
    };
    return {at(0.0, 0.0), at(10.0, 0.0), at(0.0, 10.0)};
}

TriangleAttributes attributesOf(const PlaneTriangle& t) {
    return computeTriangleAttributes(t.a, t.b, t.c);
}

TEST(TriangleAttributes, AspectIs90_WhenPlaneDipsToTheEast) {
    const auto attributes = attributesOf(onPlane(-0.5, 0.0));
    EXPECT_NEAR(attributes.aspectDeg, 90.0, kAngleToleranceDeg);
}

TEST(TriangleAttributes, AspectIs0_WhenPlaneDipsToTheNorth) {
    const auto attributes = attributesOf(onPlane(0.0, -0.5));
    EXPECT_NEAR(attributes.aspectDeg, 0.0, kAngleToleranceDeg);
}

TEST(TriangleAttributes, AspectIs180_WhenPlaneDipsToTheSouth) {
    const auto attributes = attributesOf(onPlane(0.0, 0.5));
    EXPECT_NEAR(attributes.aspectDeg, 180.0, kAngleToleranceDeg);
}

TEST(TriangleAttributes, AspectIs270_WhenPlaneDipsToTheWest) {
    const auto attributes = attributesOf(onPlane(0.5, 0.0));
    EXPECT_NEAR(attributes.aspectDeg, 270.0, kAngleToleranceDeg);
}

TEST(TriangleAttributes, AspectIs225_WhenPlaneDipsToTheSouthWest) {
    // z rises to the north-east, so water runs south-west.
    const auto attributes = attributesOf(onPlane(0.3, 0.3));
    EXPECT_NEAR(attributes.aspectDeg, 225.0, kAngleToleranceDeg);
}

TEST(TriangleAttributes, AspectIsJustBelow360_WhenDownhillIsSlightlyWestOfNorth) {
    const auto attributes = attributesOf(onPlane(1e-6, -1.0));
    EXPECT_LT(attributes.aspectDeg, 360.0);
    EXPECT_NEAR(attributes.aspectDeg, 360.0 - 1e-6 * kDegreesPerRadian, 1e-6);
}

TEST(TriangleAttributes, AspectStaysInRange_WhenDownhillIsATinyAngleWestOfNorth) {
    // -5.7e-299 degrees + 360 rounds to 360, which is outside [0, 360): it must come out as 0.
    const auto attributes =
        computeTriangleAttributes({0.0, 0.0, 0.0}, {1.0, 0.0, 1e-300}, {0.0, 1.0, -1.0});
    EXPECT_GE(attributes.aspectDeg, 0.0);
    EXPECT_LT(attributes.aspectDeg, 360.0);
    EXPECT_EQ(attributes.aspectDeg, 0.0);
}

TEST(TriangleAttributes, SlopeIs45_WhenGradientIsOne) {
    const auto attributes = attributesOf(onPlane(-1.0, 0.0));
    EXPECT_NEAR(attributes.slopeDeg, 45.0, kAngleToleranceDeg);
    EXPECT_NEAR(attributes.aspectDeg, 90.0, kAngleToleranceDeg);
}

TEST(TriangleAttributes, SlopeMatchesArctanOfGradient_WhenGradientIsOblique) {
    const double p = 0.3;
    const double q = -0.4; // |grad z| = 0.5
    const auto attributes = attributesOf(onPlane(p, q));
    EXPECT_NEAR(attributes.slopeDeg, std::atan(0.5) * kDegreesPerRadian, kAngleToleranceDeg);
    // Downhill is (-p, -q) = (-0.3, 0.4): north-west.
    EXPECT_NEAR(attributes.aspectDeg, std::atan2(-0.3, 0.4) * kDegreesPerRadian + 360.0,
                kAngleToleranceDeg);
}

TEST(TriangleAttributes, AspectIsMinusOneAndSlopeZero_WhenTriangleIsFlat) {
    const auto attributes = attributesOf(onPlane(0.0, 0.0, 1234.5));
    EXPECT_EQ(attributes.aspectDeg, -1.0);
    EXPECT_EQ(attributes.slopeDeg, 0.0);
    EXPECT_EQ(attributes.zMin, 1234.5);
    EXPECT_EQ(attributes.zMax, 1234.5);
    EXPECT_EQ(attributes.zMean, 1234.5);
}

TEST(TriangleAttributes, ResultsAreTheSame_WhenCornersAreClockwise) {
    const auto t = onPlane(0.2, -0.7);
    const auto ccw = computeTriangleAttributes(t.a, t.b, t.c);
    for (const auto& cw :
         {computeTriangleAttributes(t.a, t.c, t.b), computeTriangleAttributes(t.c, t.b, t.a),
          computeTriangleAttributes(t.b, t.a, t.c)}) {
        EXPECT_NEAR(cw.slopeDeg, ccw.slopeDeg, kAngleToleranceDeg);
        EXPECT_NEAR(cw.aspectDeg, ccw.aspectDeg, kAngleToleranceDeg);
        EXPECT_DOUBLE_EQ(cw.area2d, ccw.area2d);
        EXPECT_EQ(cw.zMin, ccw.zMin);
        EXPECT_EQ(cw.zMax, ccw.zMax);
        EXPECT_DOUBLE_EQ(cw.zMean, ccw.zMean);
    }
}

TEST(TriangleAttributes, AreaIsPlanimetric_WhenTriangleIsSteep) {
    // Legs of 10 m: the plan area is 50 m^2 however steep the plane.
    EXPECT_DOUBLE_EQ(attributesOf(onPlane(0.0, 0.0)).area2d, 50.0);
    EXPECT_DOUBLE_EQ(attributesOf(onPlane(3.0, -2.0)).area2d, 50.0);
}

TEST(TriangleAttributes, ZStatisticsAreOfTheCorners_WhenCornersDiffer) {
    const auto attributes =
        computeTriangleAttributes({0.0, 0.0, 7.0}, {4.0, 0.0, -2.0}, {0.0, 3.0, 1.0});
    EXPECT_EQ(attributes.zMin, -2.0);
    EXPECT_EQ(attributes.zMax, 7.0);
    EXPECT_DOUBLE_EQ(attributes.zMean, 2.0);
    EXPECT_DOUBLE_EQ(attributes.area2d, 6.0);
}

TEST(TriangleAttributes, SlopeZeroAspectMinusOneAreaZero_WhenCornersAreCollinearInPlan) {
    const auto attributes =
        computeTriangleAttributes({0.0, 0.0, 0.0}, {1.0, 1.0, 5.0}, {2.0, 2.0, 1.0});
    EXPECT_EQ(attributes.slopeDeg, 0.0);
    EXPECT_EQ(attributes.aspectDeg, -1.0);
    EXPECT_EQ(attributes.area2d, 0.0);
    EXPECT_EQ(attributes.zMin, 0.0);
    EXPECT_EQ(attributes.zMax, 5.0);
}

TEST(TriangleAttributes, SlopeApproaches90_WhenPlaneIsNearlyVertical) {
    const auto attributes = attributesOf(onPlane(0.0, -1e6));
    EXPECT_GT(attributes.slopeDeg, 89.99);
    EXPECT_LE(attributes.slopeDeg, 90.0);
    EXPECT_NEAR(attributes.aspectDeg, 0.0, kAngleToleranceDeg);
}

} // namespace
} // namespace terratin
