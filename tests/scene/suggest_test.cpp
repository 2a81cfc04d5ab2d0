// core/suggest.h, which the scene parser's "did you mean" uses (tested here, beside its user).
#include <string_view>
#include <vector>

#include <gtest/gtest.h>

#include "core/suggest.h"

namespace vkray {
namespace {

TEST(Suggest, EditDistanceCountsInsertionsDeletionsSubstitutionsAndSwaps) {
    EXPECT_EQ(editDistance("sphere", "sphere"), 0u);
    EXPECT_EQ(editDistance("sphre", "sphere"), 1u);     // one left out
    EXPECT_EQ(editDistance("spherre", "sphere"), 1u);   // one too many
    EXPECT_EQ(editDistance("shinyness", "shininess"), 1u);
    EXPECT_EQ(editDistance("ambeint", "ambient"), 1u);  // two neighbours swapped
    EXPECT_EQ(editDistance("Vertex", "vertex"), 0u);    // case is not an edit
    EXPECT_EQ(editDistance("", "abc"), 3u);
    EXPECT_EQ(editDistance("kitten", "sitting"), 3u);
}

TEST(Suggest, ClosestNameOnlyWhenCloseEnough) {
    const std::vector<std::string_view> names = {"sphere", "size", "vertex", "diffuse", "directional"};
    EXPECT_EQ(closestName("sphre", names), "sphere");
    EXPECT_EQ(closestName("vertx", names), "vertex");
    EXPECT_EQ(closestName("difuse", names), "diffuse");
    EXPECT_EQ(closestName("siz", names), "size");
    EXPECT_FALSE(closestName("foo", names));      // 3 edits from anything
    EXPECT_FALSE(closestName("xy", names));       // a short word gets at most one edit
    EXPECT_FALSE(closestName("camera", names));
}

}  // namespace
}  // namespace vkray
