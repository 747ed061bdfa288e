#include "povray_exporter.h"

#include "engine_capabilities.h"

#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>

#include "atomic_file.h"
#include "errors.h"
#include "number_format.h"
#include "mirror.h"
#include "mirror_surface.h"
#include "physical_camera.h"
#include "scene_translation.h"
#include "texture_image.h"
#include "triangulate.h"

namespace omnicam {

namespace {

std::string num(double v) { return roundTrip(v); }

// A world point (metres, right-handed, Z up) as a POV-Ray vector (mm, left-handed, Y up).
std::string pov(const Vec3& p) {
  const Vec3 q = p * kPovrayUnitsPerMetre;
  return "<" + num(q.x()) + ", " + num(q.z()) + ", " + num(q.y()) + ">";
}
// A direction: same axis swap, no unit scaling.
std::string povDirection(const Vec3& d) { return "<" + num(d.x()) + ", " + num(d.z()) + ", " + num(d.y()) + ">"; }
// An affine map as a POV-Ray `matrix`: the images of the local x, y and z axes and of the local
// origin in omnicam's world (the origin in metres, the axes in metres per local unit over
// `axesPerMetre`); POV-Ray's row k is the image of its axis k.
std::string povAffine(const Vec3& xAxis, const Vec3& yAxis, const Vec3& zAxis, const Vec3& origin,
                      double axesPerMetre = kPovrayUnitsPerMetre) {
  std::string out = "matrix <";
  for (const Vec3& a : {xAxis, yAxis, zAxis}) {
    const Vec3 q = a * axesPerMetre;
    out += num(q.x()) + ", " + num(q.z()) + ", " + num(q.y()) + ", ";
  }
  const Vec3 t = origin * kPovrayUnitsPerMetre;
  return out + num(t.x()) + ", " + num(t.z()) + ", " + num(t.y()) + ">";
}
// A rigid placement of an object modelled in its local frame (POV axes, mm): POV's local x, y, z
// are omnicam's x, z, y, unscaled (a local millimetre is a world one).
std::string povPlacement(const Rigid& worldFromLocal) {
  const Eigen::Matrix3d& r = worldFromLocal.linear();
  return povAffine(r.col(0), r.col(2), r.col(1), worldFromLocal.translation(), 1.0);
}
// Where a texture's UV comes from on a shape. POV-Ray 3.7 gives UV to meshes and spheres only
// (its sphere's is omnicam's: u the azimuth from +X, v from the bottom pole). A cylinder's UV is
// its pattern wrapped by a cylindrical warp about the axis, a disc's the planar image map, each
// placed in the shape's frame (perpendicularFrame, as the fast renderer's), so that every engine
// reads the same texel.
struct TexturePlacement {
  bool uvMapping = true;
  std::string frame;  // pattern modifiers after the UV repeats
};

TexturePlacement cylinderTexturePlacement(const Cylinder& c) {
  const Vec3 axis = c.top - c.base;
  const auto [e1, e2] = perpendicularFrame(axis);
  // The warp maps pattern point (x, y, z) to (azimuth from +x toward +z over 2π, y, ·).
  return {false, " warp { cylindrical } " + povAffine(c.radius * e1, axis, c.radius * e2, c.base)};
}

TexturePlacement discTexturePlacement(const Disc& d) {
  const auto [e1, e2] = perpendicularFrame(d.normal);
  // UV (0, 0)–(1, 1) is the disc's bounding square.
  const double side = 2.0 * d.radius;
  return {false, " " + povAffine(side * e1, side * e2, side * d.normal.normalized(), d.center - d.radius * (e1 + e2))};
}

std::string rgb(const Vec3f& c) { return "rgb <" + num(c.x()) + ", " + num(c.y()) + ", " + num(c.z()) + ">"; }

std::string finish(const Material& m, Shading shading) {
  if (shading == Shading::Unlit) return "finish { ambient 1 diffuse 0 specular 0 phong 0 }";
  return "finish { ambient " + num(m.ambient) + " diffuse " + num(m.diffuse) +
         " brilliance 1 specular 0 phong 0 }";
}

class SdlWriter {
 public:
  SdlWriter(const Scene& scene, Shading shading, PovrayJob& job) : scene_(scene), shading_(shading), job_(job) {
    for (size_t i = 0; i < scene.materials.size(); ++i) {
      const Material& m = scene.materials[i];
      if (!m.texture) continue;
      textureOf_[i] = job.textures.size();
      job.textures.push_back({"tex_" + std::to_string(i) + ".exr", opaqueImage(*m.texture, m.color)});
    }
  }

  std::string texture(int materialIndex, const TexturePlacement& placement = {}) const {
    const Material& m = scene_.materials[materialIndex];
    std::string pigment;
    auto t = textureOf_.find(materialIndex);
    if (t == textureOf_.end()) {
      pigment = "pigment { " + rgb(m.color) + " }";
    } else {
      pigment = std::string("pigment { ") + (placement.uvMapping ? "uv_mapping " : "") + "image_map { exr \"" +
                job_.textures[t->second].name + "\" interpolate 2 } scale <" + num(1.0 / m.textureScale.x()) +
                ", " + num(1.0 / m.textureScale.y()) + ", 1>" + placement.frame + " }";
    }
    return "texture { " + pigment + " " + finish(m, shading_) + " }";
  }

  bool textured(int materialIndex) const { return textureOf_.count(materialIndex) > 0; }

 private:
  const Scene& scene_;
  Shading shading_;
  PovrayJob& job_;
  std::map<int, size_t> textureOf_;
};

void writeMesh(std::ostringstream& out, const TriangleMesh& mesh, bool withUv, const std::string& texture) {
  out << "mesh2 {\n  vertex_vectors { " << mesh.vertices.size();
  for (const Vec3& v : mesh.vertices) out << ",\n    " << pov(v);
  out << " }\n";
  if (withUv) {
    out << "  uv_vectors { " << mesh.uvs.size();
    for (const auto& uv : mesh.uvs) out << ",\n    <" << num(uv.x()) << ", " << num(uv.y()) << ">";
    out << " }\n";
  }
  out << "  face_indices { " << mesh.triangles.size();
  for (const auto& t : mesh.triangles) out << ",\n    <" << t[0] << ", " << t[1] << ", " << t[2] << ">";
  out << " }\n  " << texture << "\n}\n";
}

}  // namespace

namespace {

// The physical camera. POV-Ray's ray for screen (x0, y0) ∈ [−½, ½]² is direction + x0·right +
// y0·up (perspective) or starts at location + x0·right + y0·up along direction (orthographic),
// y0 upward; raster u = (x0 + ½)·W and v = (½ − y0)·H reach the pinhole frame's
// ((u − ppx)/f, (v − ppy)/f, 1) (times f/H) with these vectors; a principal point off the image
// centre tilts `direction` (perspective) or moves `location` (orthographic).
std::string cameraSdl(const Pinhole& pinhole, int size, const Rigid& worldFromView) {
  const double w = size, h = size, f = pinhole.focalPx;
  const Vec2& pp = pinhole.principalPoint;
  const Eigen::Matrix3d worldFromPinhole = worldFromView.linear() * pinhole.viewpointFromPinhole;
  std::ostringstream out;
  if (pinhole.orthographic) {
    // f is pixels per metre: the view is W/f × H/f metres, centred on the image centre's ray.
    const Vec3 centre = pinhole.position + pinhole.viewpointFromPinhole * Vec3((0.5 * w - pp.x()) / f, (0.5 * h - pp.y()) / f, 0.0);
    const Vec3 right = worldFromPinhole * Vec3(w / f, 0.0, 0.0) * kPovrayUnitsPerMetre;
    const Vec3 up = worldFromPinhole * Vec3(0.0, -h / f, 0.0) * kPovrayUnitsPerMetre;
    out << "camera { orthographic\n  location " << pov(worldFromView * centre) << "\n  right " << povDirection(right)
        << "\n  up " << povDirection(up) << "\n  direction " << povDirection(worldFromPinhole * Vec3::UnitZ()) << "\n}\n";
    return out.str();
  }
  const Vec3 location = worldFromView * pinhole.position;
  const Vec3 right = worldFromPinhole * Vec3(w / h, 0.0, 0.0);
  const Vec3 up = worldFromPinhole * Vec3(0.0, -1.0, 0.0);
  const Vec3 direction = worldFromPinhole * Vec3((0.5 * w - pp.x()) / h, (0.5 * h - pp.y()) / h, f / h);
  out << "camera { perspective\n  location " << pov(location) << "\n  right " << povDirection(right)
      << "\n  up " << povDirection(up) << "\n  direction " << povDirection(direction) << "\n}\n";
  return out.str();
}

// A lens camera (rig.lens) as POV-Ray's own camera, in its definitions (POV-Ray 3.7.0.10,
// TracePixel::CreateCameraRay; docs/povray.md, "Lens cameras"): pixel (i, j) is traced at its
// centre; `fisheye` is the equidistant lens θ = ρ·angle/2 with ρ = |(x0·|right|, y0·|up|)| and
// x0, y0 ∈ [−1, 1] across the image, no ray beyond ρ = 1 (black, alpha 0); `spherical` spreads
// `angle H, V` evenly over the columns and rows about `direction`; `perspective` is the pinhole.
// Each centres its image: the lens' principal point must be the image's centre (checked by the
// engine's capabilities). `lens` is the rendered (supersampled) image's.
std::string lensCameraSdl(const LensCameraSpec& lens, const Rigid& worldFromView) {
  const Eigen::Matrix3d worldFromLens = worldFromView.linear() * viewpointFromLens(lens);
  const Vec3 right = worldFromLens.col(0), up = -worldFromLens.col(1);
  Vec3 forward = worldFromLens.col(2);
  const double w = lens.width, h = lens.height;
  std::ostringstream out;
  out << "camera { ";
  if (const auto* f = std::get_if<FThetaLens>(&lens.model)) {
    const double angle = 2.0 * f->maxThetaRad;  // the image circle's θ = angle/2 at ρ = 1
    out << "fisheye\n  angle " << num(degrees(angle)) << "\n  right " << povDirection(right * (w / (f->f * angle)))
        << "\n  up " << povDirection(up * (h / (f->f * angle)));
  } else if (const auto* e = std::get_if<Equirectangular>(&lens.model)) {
    out << "spherical\n  angle " << num(degrees(e->lonMaxRad - e->lonMinRad)) << ", "
        << num(degrees(e->latMaxRad - e->latMinRad)) << "\n  right " << povDirection(right) << "\n  up " << povDirection(up);
  } else {
    const auto& p = std::get<PinholeRadTan>(lens.model);
    out << "perspective\n  right " << povDirection(right * (w / h)) << "\n  up " << povDirection(up);
    forward = forward * (p.fx / h);
  }
  out << "\n  location " << pov(worldFromView.translation()) << "\n  direction " << povDirection(forward) << "\n}\n";
  return out.str();
}

// `clipped_by` the box from `low` to `high`, which also bounds the object.
std::string clipBoxSdl(const Vec3& low, const Vec3& high) {
  return "  clipped_by { box { <" + num(low.x()) + ", " + num(low.y()) + ", " + num(low.z()) + ">, <" + num(high.x()) + ", " +
         num(high.y()) + ", " + num(high.z()) + "> } }\n  bounded_by { clipped_by }\n";
}

// The exact mirror in its local frame (mm, POV axes: POV y = omnicam z, origin at the design
// point), clipped to the box from `low` to `high` of that frame: an open object the caller
// closes.
std::string mirrorSurfaceSdl(const MirrorRig& rig, const Vec3& low, const Vec3& high) {
  const double u = kPovrayUnitsPerMetre;
  std::ostringstream out;
  std::visit(Overloaded{
                 [&](const HyperboloidMirror& hyperboloid) {
                   // (y + c/2)²/a² − (x² + z²)/b² = 1, times a²: −(a²/b²)x² + y² − (a²/b²)z² + c·y + c²/4 − a² = 0.
                   const HyperbolicMirror mirror = hyperboloid.mirror();
                   const double a2 = mirror.a2() * u * u, b2 = mirror.b2() * u * u, c = mirror.c() * u;
                   out << "// Mirror: exact hyperboloid (k = " << num(mirror.k()) << ", c = " << num(mirror.c())
                       << " m), upper sheet from its vertex to the rim.\n"
                       << "quadric { <" << num(-a2 / b2) << ", 1, " << num(-a2 / b2) << ">, <0, 0, 0>, <0, " << num(c)
                       << ", 0>, " << num(c * c / 4.0 - a2) << "\n"
                       << clipBoxSdl(low, high);
                 },
                 [&](const ParaboloidMirror& paraboloid) {
                   // x² + z² − 2h·y = 0 about its vertex, moved h/2 down to put the focus at the
                   // origin (x² + z² − 2h·y − h² = 0). Written about the focus, POV-Ray 3.7's
                   // automatic bounds of a paraboloid forget that shift and cut the mirror off short
                   // of its rim (at r = √(2h·rim height) instead of √(2h·rim height + h²)).
                   const double h = paraboloid.h * u;
                   const Vec3 up(0.0, 0.5 * h, 0.0);
                   out << "// Mirror: exact paraboloid (h = " << num(paraboloid.h) << " m), about its vertex, then moved to its focus.\n"
                       << "quadric { <1, 0, 1>, <0, 0, 0>, <0, " << num(-2.0 * h) << ", 0>, 0\n"
                       << clipBoxSdl(low + up, high + up) << "  translate <0, " << num(-0.5 * h) << ", 0>\n";
                 },
                 [&](const SphereMirror& sphere) {
                   out << "// Mirror: sphere (radius " << num(sphere.radius) << " m) about its centre, its lower cap.\n"
                       << "sphere { <0, 0, 0>, " << num(sphere.radius * u) << "\n"
                       << clipBoxSdl(low, high);
                 },
                 [&](const ConeMirror& cone) {
                   const double rimR = cone.rimRadius * u, rimY = rimR / std::tan(radians(cone.halfAngleDeg));
                   out << "// Mirror: cone (half-angle " << num(cone.halfAngleDeg) << " deg), apex down at the origin.\n"
                       << "cone { <0, 0, 0>, 0, <0, " << num(rimY) << ", 0>, " << num(rimR) << " open\n"
                       << clipBoxSdl(low, high);
                 }},
             rig.shape);
  return out.str();
}

// The lens imaging the n×-larger image POV-Ray renders (n samples per pixel and axis); no size
// limit applies to it.
LensCameraSpec supersampled(const LensCameraSpec& lens, int n) {
  LensCameraSpec large = lens;
  large.width = lens.width * n;
  large.height = lens.height * n;
  large.model = scaledLens(lens.model, n);
  return large;
}

// The mirror as built, placed on the robot, and the black beyond its rim.
std::string mirrorSdl(const MirrorRig& rig, const Rigid& worldFromView) {
  const std::shared_ptr<const MirrorSurface> surface = mirrorSurfaceOf(rig);
  const double u = kPovrayUnitsPerMetre;
  std::ostringstream out;
  const double rimY = surface->rimZ() * u, rimR = surface->rimRadius() * u;
  const double bottomY = surface->heightAt(0.0, 0.0) * u - 0.5;
  out << mirrorSurfaceSdl(rig, Vec3(-rimR - 1.0, bottomY, -rimR - 1.0), Vec3(rimR + 1.0, rimY, rimR + 1.0))
      << "  texture { pigment { rgb 0 } finish { ambient 0 diffuse 0 specular 0 phong 0 reflection { 1 } } }\n"
      << "  no_shadow\n  " << povPlacement(worldFromView) << "\n}\n"
      << "// Beyond the rim the camera sees black (docs/conventions.md §2); invisible to everything else.\n"
      << "disc { <0, " << num(rimY) << ", 0>, y, " << num(rimR + 1000.0) << ", " << num(rimR) << "\n"
      << "  texture { pigment { rgb 0 } finish { ambient 0 diffuse 0 } } no_shadow no_reflection\n"
      << "  " << povPlacement(worldFromView) << "\n}\n\n";
  return out.str();
}

// The rig in SDL: its camera, and the mirror it looks into (none for a lens camera).
struct RigSdl {
  std::string camera, mirror;
};

RigSdl rigSdl(const RigSpec& rig, int samplesPerAxis, const Rigid& worldFromView) {
  return std::visit(Overloaded{[&](const MirrorRig& mirror) {
                                 return RigSdl{cameraSdl(pinholeOf(mirror), mirror.imageSize, worldFromView), mirrorSdl(mirror, worldFromView)};
                               },
                               [&](const LensCameraSpec& lens) {
                                 return RigSdl{lensCameraSdl(supersampled(lens, samplesPerAxis), worldFromView), ""};
                               }},
                    rig.kind);
}

}  // namespace

void checkPovrayCamera(const RigSpec& rig) { checkEngineRenders(EngineKind::Povray, rig, CameraPlacement{}); }

PovrayJob exportPovray(const Scene& worldScene, const CameraPlacement& worldPlacement, const RenderSettings& settings) {
  checkRenderSettings(settings);
  checkPlacement(worldPlacement);
  const EngineFrame frame = engineFrameNear(worldScene, {worldPlacement});
  const Scene& scene = frame.sceneOr(worldScene);
  const CameraPlacement& placement = frame.placements.front();
  const auto n = samplesPerAxis(settings.spp);
  PovrayJob job;
  job.samplesPerAxis = *n;
  job.worldOrigin = frame.worldOrigin;
  // The physical camera as built (physical_camera.h) and the mirror it looks into.
  checkPovrayCamera(settings.rig);
  job.width = settings.rig.imageWidth() * *n;
  job.height = settings.rig.imageHeight() * *n;
  // POV-Ray renders one instant: the exposure start (povray_renderer.h freezes a moving
  // placement at each instant it renders).
  const Rigid worldFromView = placement.worldFromViewpoint(settings.rig);
  checkEngineShading(EngineKind::Povray, settings.shading);
  SdlWriter writer(scene, settings.shading, job);

  std::ostringstream out;
  out << "// omnicam POV-Ray export (generated). Units: mm; axes: <X, Z, Y> of omnicam's world, its origin at\n"
      << "// omnicam's (" << num(frame.worldOrigin.x()) << ", " << num(frame.worldOrigin.y())
      << ", 0) m, the whole metre nearest the robot (POV-Ray loses precision far from its origin).\n"
      << "#version 3.7;\n"
         "global_settings { assumed_gamma 1.0 ambient_light rgb 1 max_trace_level 8 adc_bailout 0 }\n"
      << "background { " << rgb(scene.background) << " }\n\n";
  const RigSdl rig = rigSdl(settings.rig, *n, worldFromView);
  out << rig.camera << "\n";

  if (settings.shading == Shading::Lit)
    for (const PointLight& l : scene.lights) out << "light_source { " << pov(l.position) << ", " << rgb(l.intensity) << " }\n";

  out << rig.mirror;

  const double u = kPovrayUnitsPerMetre;

  for (size_t i = 0; i < scene.objects.size(); ++i) {
    const SceneObject& o = scene.objects[i];
    out << "// object " << i << "\n";
    if (auto s = std::get_if<Sphere>(&o.shape)) {
      out << "sphere { " << pov(s->center) << ", " << num(s->radius * u) << " " << writer.texture(o.material) << " }\n";
    } else if (auto cyl = std::get_if<Cylinder>(&o.shape)) {
      out << "cylinder { " << pov(cyl->base) << ", " << pov(cyl->top) << ", " << num(cyl->radius * u)
          << (cyl->caps ? "" : " open") << " " << writer.texture(o.material, cylinderTexturePlacement(*cyl)) << " }\n";
    } else if (auto d = std::get_if<Disc>(&o.shape)) {
      out << "disc { " << pov(d->center) << ", " << povDirection(d->normal) << ", " << num(d->radius * u) << ", "
          << num(d->innerRadius * u) << " " << writer.texture(o.material, discTexturePlacement(*d)) << " }\n";
    } else {
      const TriangleMesh mesh = *triangulatePlanar(o.shape);
      writeMesh(out, mesh, writer.textured(o.material), writer.texture(o.material));
    }
  }
  job.sdl = out.str();
  return job;
}

std::vector<std::string> povrayJobFiles(const PovrayJob& job) {
  std::vector<std::string> names{"scene.pov", "render.ini"};
  for (const auto& t : job.textures) names.push_back(t.name);
  return names;
}

void writePovrayJob(const PovrayJob& job, const std::string& dir, int threads, const std::optional<PovrayRegion>& region) {
  namespace fs = std::filesystem;
  // Every name first: a folder in the way of the last file leaves none written.
  std::error_code ec;
  if (fs::is_directory(dir, ec))
    for (const std::string& name : povrayJobFiles(job)) checkOutputFile((fs::path(dir) / name).string(), "POV-Ray job");
  std::vector<FileBytes> files{{(fs::path(dir) / "scene.pov").string(), {job.sdl.begin(), job.sdl.end()}}};
  for (const auto& t : job.textures) {
    const std::string path = (fs::path(dir) / t.name).string();
    files.push_back({path, encodeImage(path, t.image)});
  }
  std::ostringstream ini;
  ini << "; omnicam POV-Ray job (generated): regular grid, no anti-aliasing, no jitter.\n"
      << "Input_File_Name=scene.pov\nOutput_File_Name=render.exr\nOutput_File_Type=E\nOutput_Alpha=Off\n"
      << "Width=" << job.width << "\nHeight=" << job.height << "\n"
      << "Antialias=Off\nJitter=Off\nDisplay=Off\nPause_When_Done=Off\nVerbose=Off\nQuality=9\n"
      << "Library_Path=.\n";
  if (threads > 0) ini << "Work_Threads=" << threads << "\n";
  if (region)  // POV-Ray counts rows and columns from 1, both ends included
    ini << "Start_Row=" << region->firstRow + 1 << "\nEnd_Row=" << region->endRow << "\nStart_Column=" << region->firstColumn + 1
        << "\nEnd_Column=" << region->endColumn << "\n";
  const std::string iniText = ini.str();
  files.push_back({(fs::path(dir) / "render.ini").string(), {iniText.begin(), iniText.end()}});
  writeFilesTogether(files);  // the whole job or none of it
}

}  // namespace omnicam
