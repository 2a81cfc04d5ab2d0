// Camera rays (docs/scene-format.md, "Camera rays") against values computed by hand.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.h"
#include "scene/camera.h"
#include "scene_test_util.h"

namespace vkray {
namespace {

constexpr double kTol = 1e-15;

void expectDir(const glm::dvec3& got, const glm::dvec3& unnormalised) {
    const glm::dvec3 want = unnormalised / std::sqrt(glm::dot(unnormalised, unnormalised));
    EXPECT_NEAR(got.x, want.x, kTol);
    EXPECT_NEAR(got.y, want.y, kTol);
    EXPECT_NEAR(got.z, want.z, kTol);
}

Camera cameraAt(glm::vec3 eye, glm::vec3 center, glm::vec3 up, float fovy) {
    Camera c;
    c.eye = eye;
    c.center = center;
    c.up = up;
    c.fovyDegrees = fovy;
    return c;
}

// 2x2, fovy 90 (tanX = tanY = 1), looking down -z: pixel centres at a, b = +-1/2.
TEST(CameraRays, TwoByTwoLookingDownZ) {
    const CameraFrame f = makeCameraFrame(cameraAt({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 90.0f), 2, 2);
    EXPECT_EQ(f.w, glm::dvec3(0, 0, 1));
    EXPECT_EQ(f.u, glm::dvec3(1, 0, 0));
    EXPECT_EQ(f.v, glm::dvec3(0, 1, 0));
    expectDir(primaryDirection(f, 0, 0), {-0.5, 0.5, -1});  // top left
    expectDir(primaryDirection(f, 1, 0), {0.5, 0.5, -1});   // top right
    expectDir(primaryDirection(f, 0, 1), {-0.5, -0.5, -1});
    expectDir(primaryDirection(f, 1, 1), {0.5, -0.5, -1});
}

// An up vector that is not orthogonal to the view direction is orthogonalised, not used as is.
TEST(CameraRays, UpIsOrthogonalised) {
    const CameraFrame f = makeCameraFrame(cameraAt({0, 0, 0}, {0, 0, -1}, {0, 5, 1}, 90.0f), 2, 2);
    EXPECT_NEAR(f.u.x, 1.0, kTol);
    EXPECT_NEAR(f.v.y, 1.0, kTol);
    expectDir(primaryDirection(f, 0, 0), {-0.5, 0.5, -1});
}

// 4x3, fovy 90: tanX = 4/3, so a = (4/3)((i + 1/2) - 2)/2 in {-1, -1/3, 1/3, 1} and
// b = (3/2 - (j + 1/2))/(3/2) in {2/3, 0, -2/3}. Looking down +x from (1, 2, 3): w = -x, u = +z,
// v = +y, so a direction is (1, b, a) before normalisation.
TEST(CameraRays, FourByThreeLookingDownX) {
    const CameraFrame f = makeCameraFrame(cameraAt({1, 2, 3}, {4, 2, 3}, {0, 1, 0}, 90.0f), 4, 3);
    EXPECT_EQ(f.w, glm::dvec3(-1, 0, 0));
    EXPECT_EQ(f.u, glm::dvec3(0, 0, 1));
    EXPECT_EQ(f.v, glm::dvec3(0, 1, 0));
    EXPECT_NEAR(f.tanX, 4.0 / 3.0, kTol);
    expectDir(primaryDirection(f, 0, 0), {1, 2.0 / 3.0, -1});
    expectDir(primaryDirection(f, 3, 1), {1, 0, 1});
    expectDir(primaryDirection(f, 1, 2), {1, -2.0 / 3.0, -1.0 / 3.0});
    expectDir(primaryDirection(f, 2, 0), {1, 2.0 / 3.0, 1.0 / 3.0});
}

// With an odd size the centre pixel's a and b are exactly 0: the direction is -w, bit for bit.
TEST(CameraRays, CentrePixelOfOddSizeIsMinusW) {
    const CameraFrame f = makeCameraFrame(cameraAt({0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 45.0f), 5, 3);
    EXPECT_EQ(primaryDirection(f, 2, 1), -f.w);
    const CameraFrame g = makeCameraFrame(cameraAt({1, 2, 3}, {4, 2, 3}, {0, 1, 0}, 30.0f), 3, 7);
    EXPECT_EQ(primaryDirection(g, 1, 3), -g.w);
    // Oblique view: -w up to the rounding of renormalising an already unit vector.
    const CameraFrame h = makeCameraFrame(cameraAt({1, 1, 1}, {0, 0, 0}, {0, 1, 0}, 60.0f), 3, 3);
    expectDir(primaryDirection(h, 1, 1), {-1, -1, -1});
}

TEST(CameraRays, DegenerateCameraIsAnError) {
    EXPECT_THROW(makeCameraFrame(cameraAt({0, 0, 0}, {0, 0, 0}, {0, 1, 0}, 45.0f), 2, 2), Error);
    EXPECT_THROW(makeCameraFrame(cameraAt({0, 0, 0}, {0, 1, 0}, {0, 1, 0}, 45.0f), 2, 2), Error);
    EXPECT_THROW(makeCameraFrame(cameraAt({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 180.0f), 2, 2), Error);
    EXPECT_THROW(makeCameraFrame(cameraAt({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 45.0f), 0, 2), Error);
}

// --view: the scene's camera, a close-up of the triangles' bounds, or an explicit eye and centre.
Scene unitCubeCorners() {
    Scene s;
    s.camera = cameraAt({0, 0, 10}, {0, 0, 0}, {0, 1, 0}, 60.0f);
    s.triangles.push_back(Triangle{{-1, -1, -1}, {1, 1, 1}, {1, -1, 1}, 0});
    return s;
}

TEST(ViewCamera, SceneKeepsTheCamera) {
    const Scene s = unitCubeCorners();
    const Camera c = viewCamera(s, "scene");
    EXPECT_EQ(c.eye, s.camera.eye);
    EXPECT_EQ(c.center, s.camera.center);
}

TEST(ViewCamera, CloseLooksAtTheBoundsFromTheScenesDirection) {
    const Scene s = unitCubeCorners();
    const Camera c = viewCamera(s, "close");
    EXPECT_EQ(c.center, glm::vec3(0, 0, 0));
    EXPECT_EQ(c.fovyDegrees, 60.0f);
    // Half-diagonal sqrt(3); the field of view spans half of it: d = (sqrt(3)/2) / tan(30 deg) = 1.5,
    // below the half-diagonal, so the eye stays that far out, on the scene camera's side.
    EXPECT_NEAR(c.eye.x, 0.0f, 1e-6f);
    EXPECT_NEAR(c.eye.y, 0.0f, 1e-6f);
    EXPECT_NEAR(c.eye.z, std::sqrt(3.0f), 1e-5f);
}

TEST(ViewCamera, ExplicitEyeCentreAndFovy) {
    const Scene s = unitCubeCorners();
    const Camera c = viewCamera(s, "1,2,3,0,0.5,-1e1,30");
    EXPECT_EQ(c.eye, glm::vec3(1, 2, 3));
    EXPECT_EQ(c.center, glm::vec3(0, 0.5f, -10));
    EXPECT_EQ(c.fovyDegrees, 30.0f);
    EXPECT_EQ(c.up, s.camera.up);
    EXPECT_EQ(viewCamera(s, "1,2,3,0,0,0").fovyDegrees, 60.0f);
}

TEST(ViewCamera, TheWholeCameraLine) {
    const Scene s = unitCubeCorners();
    const Camera c = viewCamera(s, "1,2,3,0,0.5,-10,1,0,0,45");
    EXPECT_EQ(c.eye, glm::vec3(1, 2, 3));
    EXPECT_EQ(c.center, glm::vec3(0, 0.5f, -10));
    EXPECT_EQ(c.up, glm::vec3(1, 0, 0));
    EXPECT_EQ(c.fovyDegrees, 45.0f);
    // As one quoted argument with the scene file's spaces, pbrt and CSE167 style.
    const Camera spaced = viewCamera(s, " 1 2 3  0 0.5 -10\t1 0 0 45");
    EXPECT_EQ(spaced.eye, c.eye);
    EXPECT_EQ(spaced.center, c.center);
    EXPECT_EQ(spaced.up, c.up);
    EXPECT_EQ(spaced.fovyDegrees, c.fovyDegrees);
    EXPECT_THROW(viewCamera(s, "0,0,5,0,0,0,0,0,1,45"), Error);  // up along the view direction
    EXPECT_THROW(viewCamera(s, "1 2 3 0 0.5 -10 1 0 0 45 # x"), Error);
}

// --view fit: the whole of the triangles' bounds in the image, every corner of the box inside it,
// from the scene camera's direction with its up and fovy, for landscape and portrait images and
// boxes of any proportions.
TEST(ViewCamera, FitSeesTheWholeBoundingBox) {
    const glm::vec3 boxes[][2] = {{{-1, -1, -1}, {1, 1, 1}},
                                  {{10, 0, -3}, {60, 0.5f, -2}},      // long and flat, off the origin
                                  {{0, 0, 0}, {0.01f, 5, 0.01f}},     // a tall thin pole
                                  {{-1e4f, -2, 3}, {1e4f, 2, 4}}};    // very wide
    const Camera views[] = {cameraAt({0, 0, 10}, {0, 0, 0}, {0, 1, 0}, 60.0f),
                            cameraAt({5, 4, -3}, {1, 0, 2}, {0, 1, 0}, 25.0f),
                            cameraAt({0, 9, 0.1f}, {0, 0, 0}, {0, 0, -1}, 90.0f)};
    const std::pair<int, int> sizes[] = {{640, 480}, {100, 400}, {256, 1}, {1, 256}};
    for (const auto& [lo, hi] : boxes)
        for (const Camera& view : views)
            for (const auto& [w, h] : sizes) {
                SCOPED_TRACE(::testing::Message() << "box " << lo.x << ".." << hi.x << ", fovy " << view.fovyDegrees
                                                  << ", " << w << "x" << h);
                Scene s;
                s.width = w;
                s.height = h;
                s.camera = view;
                s.triangles.push_back(Triangle{lo, hi, {lo.x, hi.y, lo.z}, 0});
                s.triangles.push_back(Triangle{{hi.x, lo.y, hi.z}, {hi.x, hi.y, lo.z}, {lo.x, lo.y, hi.z}, 0});
                const Camera fit = viewCamera(s, "fit");
                EXPECT_EQ(fit.fovyDegrees, view.fovyDegrees);
                EXPECT_EQ(fit.up, view.up);
                const glm::dvec3 was = glm::normalize(glm::dvec3(view.eye - view.center));
                const glm::dvec3 is = glm::normalize(glm::dvec3(fit.eye - fit.center));
                EXPECT_NEAR(glm::dot(was, is), 1.0, 1e-6) << "the view direction changed";
                s.camera = fit;
                test::expectFramed(s, test::triangleBox(s));
            }
}

// Fitted, the box fills the narrower field: its sphere touches the cone within the margin.
TEST(ViewCamera, FitIsNotFarther) {
    Scene s = unitCubeCorners();  // half-diagonal sqrt(3), centre 0
    s.width = 640;
    s.height = 480;
    const Camera fit = viewCamera(s, "fit");
    EXPECT_EQ(fit.center, glm::vec3(0, 0, 0));
    EXPECT_NEAR(fit.eye.z, 1.05 * std::sqrt(3.0) / std::sin(glm::radians(30.0)), 1e-4);
    s.width = 240;  // portrait: the horizontal field is the narrower one
    const double halfX = std::atan(std::tan(glm::radians(30.0)) * 240.0 / 480.0);
    EXPECT_NEAR(viewCamera(s, "fit").eye.z, 1.05 * std::sqrt(3.0) / std::sin(halfX), 1e-4);
}

TEST(ViewCamera, BadTextIsAnErrorNamingTheOption) {
    const Scene s = unitCubeCorners();
    for (const char* bad : {"", "near", "1,2,3", "1,2,3,4,5", "1,2,3,4,5,6,7,8", "1,2,3,4,5,6,7,8,9", "1,2,x,4,5,6", "1,2,3,4,5,6,",
                            "1,2,3,4,5,nan", "1,2,3,1,2,3", "0,5,0,0,0,0", "1,2,3,4,5,6,180"}) {
        try {
            viewCamera(s, bad);
            ADD_FAILURE() << "accepted '" << bad << "'";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("--view '" + std::string(bad) + "'"), std::string::npos) << e.what();
        }
    }
}

// --spp's pattern: sample 0 is the pixel centre (so --spp 1 is the centre ray), every sample lies
// in the pixel, and any prefix covers it evenly: of n samples every cell of a k x k grid holds
// between half and one and a half times its n / k^2, and the first 4 fill a 2x2 grid one each.
TEST(Camera, PixelSamplesStartAtTheCentreAndSpreadEvenly) {
    EXPECT_EQ(pixelSampleOffset(0), glm::vec2(0.5f, 0.5f));
    const auto counts = [](int n, int grid) {
        std::vector<int> cells(size_t(grid * grid), 0);
        for (int s = 0; s < n; ++s) {
            const glm::vec2 p = pixelSampleOffset(s);
            EXPECT_GE(p.x, 0.0f);
            EXPECT_LT(p.x, 1.0f);
            EXPECT_GE(p.y, 0.0f);
            EXPECT_LT(p.y, 1.0f);
            ++cells[size_t(int(p.y * float(grid)) * grid + int(p.x * float(grid)))];
        }
        return cells;
    };
    for (int c : counts(64, 4)) {
        EXPECT_GE(c, 2);
        EXPECT_LE(c, 6);
    }
    for (int c : counts(16, 2)) {
        EXPECT_GE(c, 3);
        EXPECT_LE(c, 5);
    }
    for (int c : counts(4, 2)) EXPECT_EQ(c, 1);
    for (int c : counts(256, 8)) {
        EXPECT_GE(c, 2);
        EXPECT_LE(c, 6);
    }
}

}  // namespace
}  // namespace vkray
