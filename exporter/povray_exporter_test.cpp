// The exported SDL is parsed back and the optics re-derived from it alone.
#include "povray_exporter.h"

#include <gtest/gtest.h>

#include <charconv>
#include <filesystem>
#include <fstream>
#include <locale>
#include <regex>

#include "errors.h"
#include "scene_loader.h"
#include "placement.h"

namespace omnicam {
namespace {

const std::string kScene = OMNICAM_SOURCE_DIR "/scenes/robocup2006.json";

std::vector<double> numbersIn(const std::string& text) {
  std::vector<double> out;
  static const std::regex number(R"([-+]?[0-9]*\.?[0-9]+(?:[eE][-+]?[0-9]+)?)");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), number); it != std::sregex_iterator(); ++it) {
    const std::string s = it->str();
    double v = 0.0;
    const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    EXPECT_TRUE(ec == std::errc() && ptr == s.data() + s.size()) << s;
    out.push_back(v);
  }
  return out;
}

std::string block(const std::string& sdl, const std::string& start, const std::string& end) {
  const size_t a = sdl.find(start);
  EXPECT_NE(a, std::string::npos) << start;
  return sdl.substr(a + start.size(), sdl.find(end, a) - a - start.size());
}

// POV-Ray vector (mm, <X, Z, Y>) → omnicam world (m).
Vec3 worldOf(const std::vector<double>& v, size_t at, double scale = 1.0 / kPovrayUnitsPerMetre) {
  return Vec3(v[at], v[at + 2], v[at + 1]) * scale;
}

TEST(PovrayExport, ParsedMirrorAndCameraReproduceTheModel) {
  const Scene scene = loadScene(kScene);
  RenderSettings settings;
  settings.rig = scene.rig;
  const RobotPose pose{1.1, -0.4, 57.0};
  const PovrayJob job = exportPovray(scene, pose, settings);
  const std::string& sdl = job.sdl;
  // The SDL's origin is the whole metre nearest the robot, named in its first comment.
  EXPECT_EQ(job.worldOrigin, Vec3(1.0, 0.0, 0.0));
  EXPECT_NE(sdl.find("its origin at\n// omnicam's (1, 0, 0) m"), std::string::npos) << sdl.substr(0, 300);

  // Quadric: A x² + B y² + C z² + H y + J = 0 in the mirror's local frame, then translated.
  const auto q = numbersIn(block(sdl, "quadric {", "clipped_by"));
  ASSERT_EQ(q.size(), 10u);
  // Placed by a matrix: rows are POV's local axes in the world (POV axes), then the translation.
  const auto placement = numbersIn(block(sdl, "no_shadow\n  matrix <", ">"));
  ASSERT_EQ(placement.size(), 12u);
  const Vec3 viewpointWorld = worldOf(placement, 9) + job.worldOrigin;
  EXPECT_NEAR((viewpointWorld - Vec3(1.1, -0.4, 0.4)).norm(), 0.0, 1e-12);
  // A level rig turns its mirror about the vertical only, by the robot's yaw.
  const double yaw = radians(57.0);
  EXPECT_NEAR((Vec3(placement[0], placement[1], placement[2]) - Vec3(std::cos(yaw), 0.0, std::sin(yaw))).norm(), 0.0, 1e-15);
  EXPECT_NEAR((Vec3(placement[3], placement[4], placement[5]) - Vec3(0.0, 1.0, 0.0)).norm(), 0.0, 1e-15);
  const Vec3 localAxes[3] = {Vec3(placement[0], placement[1], placement[2]), Vec3(placement[3], placement[4], placement[5]),
                             Vec3(placement[6], placement[7], placement[8])};

  // Clip box: only the upper sheet between the vertex and the rim is the mirror.
  const auto box = numbersIn(block(sdl, "clipped_by { box {", "} }"));
  ASSERT_EQ(box.size(), 6u);
  const double clipBottomZ = viewpointWorld.z() + box[1] / kPovrayUnitsPerMetre;
  const auto c = numbersIn(block(sdl, "camera { perspective", "}"));
  ASSERT_EQ(c.size(), 12u);
  const Vec3 location = worldOf(c, 0) + job.worldOrigin;
  const Vec3 right = worldOf(c, 3, 1.0), up = worldOf(c, 6, 1.0), direction = worldOf(c, 9, 1.0);

  // Trace the parsed camera through the parsed quadric; the reflected ray, reversed, must be
  // our model's ray for that pixel (world frame).
  const OmniCamera cam = settings.rig.camera();
  const Rigid wfc = CameraPlacement(pose).worldFromCamera(settings.rig);
  auto implicit = [&](const Vec3& world) {  // in mm, local POV axes
    const Vec3 l = (world - viewpointWorld) * kPovrayUnitsPerMetre;
    const Vec3 pov(l.x(), l.z(), l.y());
    const double x = pov.dot(localAxes[0]), y = pov.dot(localAxes[1]), z = pov.dot(localAxes[2]);
    return q[0] * x * x + q[1] * y * y + q[2] * z * z + q[7] * y + q[9];
  };
  int checked = 0;
  for (int j = 20; j < 340; j += 37)
    for (int i = 20; i < 340; i += 41) {
      const Vec2 p(i + 0.5, j + 0.5);
      if (!cam.insideRim(p)) continue;
      const Vec3 d = (direction + (p.x() / 360.0 - 0.5) * right + (0.5 - p.y() / 360.0) * up).normalized();
      // Bisect the sign change of the implicit function inside the clip box (the lower sheet,
      // between the pinhole and the box, is clipped away as in POV-Ray).
      double lo = (clipBottomZ - location.z()) / d.z(), hi = lo + 0.05;
      const double f0 = implicit(location + lo * d);
      ASSERT_LT(f0, 0.0);
      ASSERT_GT(implicit(location + hi * d), 0.0);
      for (int k = 0; k < 200; ++k) {
        const double mid = 0.5 * (lo + hi);
        if ((implicit(location + mid * d) > 0) == (f0 > 0)) lo = mid;
        else hi = mid;
      }
      const Vec3 hit = location + hi * d;
      const Vec3 model = wfc.linear() * cam.cameraFromRaster(p);
      // The world ray seen at this pixel travels toward F' and meets the mirror at `hit`.
      EXPECT_LT(((hit - viewpointWorld).normalized() - model).norm(), 1e-7) << i << "," << j;
      ++checked;
    }
  EXPECT_GT(checked, 30);
}

// A tilted rig's mirror is turned with it: the matrix rows are the rig's axes Rz(yaw)·Rx(roll)·
// Ry(pitch) (worked out by hand here), in POV's <x, z, y>, and the translation is F' in mm.
TEST(PovrayExport, ATiltedRigTurnsItsMirrorWithIt) {
  const Scene scene = loadScene(kScene);
  RenderSettings settings;
  settings.rig = scene.rig;
  settings.rig.tiltDeg = {4.0, -3.0};
  const RobotPose pose{0.3, 0.2, -70.0};
  const auto m = numbersIn(block(exportPovray(scene, pose, settings).sdl, "no_shadow\n  matrix <", ">"));
  ASSERT_EQ(m.size(), 12u);
  const double cr = std::cos(radians(4.0)), sr = std::sin(radians(4.0)), cp = std::cos(radians(-3.0)),
               sp = std::sin(radians(-3.0)), cy = std::cos(radians(-70.0)), sy = std::sin(radians(-70.0));
  // Rx·Ry columns: x̂ → (cp, sr·sp, −cr·sp), ŷ → (0, cr, sr), ẑ → (sp, −sr·cp, cr·cp); then Rz.
  const auto turned = [&](const Vec3& v) { return Vec3(cy * v.x() - sy * v.y(), sy * v.x() + cy * v.y(), v.z()); };
  const Vec3 x = turned({cp, sr * sp, -cr * sp}), y = turned({0.0, cr, sr}), z = turned({sp, -sr * cp, cr * cp});
  const auto pov = [](const Vec3& v) { return Vec3(v.x(), v.z(), v.y()); };
  const Vec3 rows[3] = {pov(x), pov(z), pov(y)};  // POV's local x, y, z = omnicam's x, z, y
  for (int r = 0; r < 3; ++r)
    EXPECT_NEAR((Vec3(m[3 * r], m[3 * r + 1], m[3 * r + 2]) - rows[r]).norm(), 0.0, 1e-15) << "row " << r;
  const Vec3 viewpoint = Vec3(0.3, 0.2, 0.0) + settings.rig.height * z;
  EXPECT_NEAR((worldOf(m, 9) - viewpoint).norm(), 0.0, 1e-12);
}

TEST(PovrayExport, MeshesCarryTheSameTrianglesAndNumbersRoundTrip) {
  const Scene scene = loadScene(kScene);
  RenderSettings settings;
  settings.rig = scene.rig;
  const PovrayJob job = exportPovray(scene, scene.startPose, settings);
  size_t meshes = 0, at = 0;
  while ((at = job.sdl.find("mesh2 {", at)) != std::string::npos) ++meshes, ++at;
  size_t planar = 0;
  for (const auto& o : scene.objects) planar += !std::holds_alternative<Cylinder>(o.shape) && !std::holds_alternative<Disc>(o.shape) && !std::holds_alternative<Sphere>(o.shape);
  EXPECT_EQ(meshes, planar);
  // Every number in the file parses completely (no locale commas, no truncation).
  EXPECT_GT(numbersIn(job.sdl).size(), 1000u);
}

TEST(PovrayExport, OutputDoesNotDependOnTheGlobalLocale) {
  struct CommaDecimal : std::numpunct<char> {
    char do_decimal_point() const override { return ','; }
    char do_thousands_sep() const override { return '.'; }
    std::string do_grouping() const override { return "\3"; }
  };
  const Scene scene = loadScene(kScene);
  RenderSettings settings;
  settings.rig = scene.rig;
  const std::string before = exportPovray(scene, scene.startPose, settings).sdl;
  const std::locale previous = std::locale::global(std::locale(std::locale::classic(), new CommaDecimal));
  const std::string during = exportPovray(scene, scene.startPose, settings).sdl;
  std::locale::global(previous);
  EXPECT_EQ(before, during);
}

TEST(PovrayExport, UserStringsNeverReachTheSdl) {
  const auto dir = std::filesystem::temp_directory_path() / ("omnicam_sdl_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  ImageRGBA tex(2, 2);
  for (float& v : tex.pixels) v = 0.5f;
  const std::string evilTexture = "we\"ird #system(rm).png";
  writeImageAtomic((dir / evilTexture).string(), tex);
  std::ofstream(dir / "s.json") << R"json({"format": "omnicam-scene/1", "name": "x\"\n#system(\"rm -rf /\")",
    "materials": {"m\"#declare": {"texture": {"file": "we\"ird #system(rm).png"}}},
    "objects": [{"name": "obj\" #system(\"id\")", "type": "quad", "material": "m\"#declare",
                 "origin": [0, 0, 0], "edge_u": [1, 0, 0], "edge_v": [0, 1, 0]}]})json";
  const Scene scene = loadScene((dir / "s.json").string());
  RenderSettings settings;
  const PovrayJob job = exportPovray(scene, {}, settings);
  EXPECT_EQ(job.sdl.find("#system"), std::string::npos);
  // Neither the texture's file name nor the object's name is written: textures go by their index.
  EXPECT_EQ(job.sdl.find("ird #"), std::string::npos);
  EXPECT_EQ(job.sdl.find("obj\""), std::string::npos);
  EXPECT_EQ(job.sdl.find("#declare"), std::string::npos);
  ASSERT_EQ(job.textures.size(), 1u);
  EXPECT_EQ(job.textures[0].name, "tex_0.exr");
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace omnicam
