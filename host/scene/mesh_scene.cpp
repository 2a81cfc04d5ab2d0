#include "scene/mesh_scene.h"

#include "scene/camera.h"
#include "scene/mesh_file.h"
#include "scene/scene_builder.h"

namespace vkray {
namespace {

// The lights of a mesh scene, from the fitted camera's frame: directions towards each light.
void addLights(Scene& scene) {
    const CameraFrame f = makeCameraFrame(scene.camera, 1, 1);
    const auto light = [&](const glm::dvec3& towards, float intensity) {
        Light l;
        l.type = Light::Type::Directional;
        l.vector = glm::vec3(glm::normalize(towards));
        l.color = glm::vec3(intensity);
        scene.lights.push_back(l);
    };
    light(f.w + 0.8 * f.v - 0.6 * f.u, 0.85f);  // key: above the camera, to its left
    light(f.w - 0.2 * f.v + 0.9 * f.u, 0.3f);   // fill: from its right, a little below
}

}  // namespace

Scene loadMeshScene(const std::filesystem::path& file, const ParseOptions& options) {
    Scene scene;
    SceneBuilder out(scene, options.maxTriangles, options.memoryProblem);
    const MeshRequest request{file,           file.string(), FileLoc{file.string()}, Transform(),
                              kMeshDefaultMaterial, options.readFile ? options.readFile : fileSystemReader(), options.warn};
    if (options.progress) options.progress("mesh " + file.filename().string());
    loadMeshFile(request, out);
    out.finish();
    scene.sourceFile = file;
    Camera view;
    view.eye = kMeshViewDirection;
    view.center = glm::vec3(0.0f);
    view.up = glm::vec3(0.0f, 1.0f, 0.0f);
    view.fovyDegrees = 40.0f;
    scene.camera = fitCamera(scene, view);
    scene.hasCamera = true;
    addLights(scene);
    return scene;
}

}  // namespace vkray
