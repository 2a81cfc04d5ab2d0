// markParetoFront: a point is on the front when no other point is at least as fast and at least as
// accurate and better in one of the two.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bench/report.h"

using namespace vkray::bench;

namespace {

ErrorPoint point(const std::string& label, double buildMs, double traceMs, double rmse) {
    ErrorPoint p;
    p.label = label;
    p.buildMs = buildMs;
    p.traceMs = traceMs;
    p.error.rmse = rmse;
    p.pareto = !p.pareto;  // whatever it was, markParetoFront must set it
    return p;
}

std::vector<bool> marks(const std::vector<ErrorPoint>& points) {
    std::vector<bool> out;
    for (const ErrorPoint& p : points) out.push_back(p.pareto);
    return out;
}

}  // namespace

TEST(ParetoFront, ADominatedPointIsOffTheFront) {
    std::vector<ErrorPoint> points = {point("slow and worse", 4, 6, 0.10), point("fast and better", 2, 3, 0.05)};
    markParetoFront(points);
    EXPECT_EQ(marks(points), (std::vector<bool>{false, true}));
}

TEST(ParetoFront, TradeOffsAreAllOnTheFront) {
    std::vector<ErrorPoint> points = {point("fast, rough", 0.5, 0.5, 0.5), point("middle", 5, 5, 0.01),
                                      point("slow, exact", 50, 50, 0.0), point("dominated", 6, 6, 0.02)};
    markParetoFront(points);
    EXPECT_EQ(marks(points), (std::vector<bool>{true, true, true, false}));
}

// Equal time: only the more accurate one stays; equal error: only the faster one. Totals count,
// not how they split between build and trace.
TEST(ParetoFront, TiesInOneFigureAreBrokenByTheOther) {
    std::vector<ErrorPoint> points = {point("a", 4, 6, 0.1), point("same total, worse", 7, 3, 0.2),
                                      point("same error, slower", 8, 8, 0.1)};
    markParetoFront(points);
    EXPECT_EQ(marks(points), (std::vector<bool>{true, false, false}));
}

TEST(ParetoFront, DuplicatesStayTogether) {
    std::vector<ErrorPoint> points = {point("twin 1", 1, 2, 0.03), point("twin 2", 1, 2, 0.03),
                                      point("worse", 1, 2, 0.04)};
    markParetoFront(points);
    EXPECT_EQ(marks(points), (std::vector<bool>{true, true, false}));
}

TEST(ParetoFront, IdenticalImagesBeatAnyErrorAtTheSameTime) {
    std::vector<ErrorPoint> points = {point("exact", 3, 3, 0.0), point("inexact", 3, 3, 1e-6),
                                      point("exact but slower", 3, 4, 0.0)};
    markParetoFront(points);
    EXPECT_EQ(marks(points), (std::vector<bool>{true, false, false}));
}

TEST(ParetoFront, EmptyAndSinglePoint) {
    std::vector<ErrorPoint> none;
    markParetoFront(none);
    EXPECT_TRUE(none.empty());
    std::vector<ErrorPoint> one = {point("alone", 1, 1, 0.5)};
    markParetoFront(one);
    EXPECT_TRUE(one[0].pareto);
}
