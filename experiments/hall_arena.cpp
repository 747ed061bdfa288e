#include "hall_arena.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>

#include "atomic_file.h"
#include "errors.h"
#include "safe_files.h"
#include "scene_loader.h"

namespace omnicam {

namespace {


struct Wall {
  const char* name;
  Vec3 origin, edgeU, edgeV;  // texture u along edgeU (left to right seen from inside), v up
};

std::vector<Wall> hallWalls(const HallOptions& o) {
  const double L = o.halfLength, W = o.halfWidth, H = o.height;
  const Vec3 up(0, 0, H);
  return {{"south", {L, -W, 0}, {-2 * L, 0, 0}, up},
          {"north", {-L, W, 0}, {2 * L, 0, 0}, up},
          {"west", {-L, -W, 0}, {0, 2 * W, 0}, up},
          {"east", {L, W, 0}, {0, -2 * W, 0}, up}};
}

nlohmann::json vec(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace

PanoramaPhoto PanoramaPhoto::load(const std::string& path) {
  PanoramaPhoto photo;
  photo.image_ = readImage(path);
  const std::string sidecarPath = path + ".json";
  std::error_code ec;
  if (std::filesystem::is_regular_file(sidecarPath, ec)) {
    const nlohmann::json sidecar = readJsonFile(sidecarPath);
    const nlohmann::json* view = sidecar.contains("view") ? &sidecar["view"] : nullptr;
    if (!view || !view->is_object() || view->value("kind", "") != "panorama")
      throw InputError(showPath(sidecarPath) + ": view.kind: not a panorama (unwrap the omni image with --as panorama)");
    if (view->value("variant", "") != "exact")
      throw InputError(showPath(sidecarPath) + ": view.variant: must be exact (rows equal incidence-angle steps)");
    const RigSpec rig = rigFromJson(sidecar.at("rig"), sidecarPath, "rig");
    const double rimTheta = std::visit(  // from straight down
        Overloaded{[&](const MirrorRig&) { return rig.camera().rimTheta(); },
                   [&](const LensCameraSpec&) -> double {
                     throw InputError(showPath(sidecarPath) + ": rig.lens: a panorama unwrapped from a mirror camera's image is needed; "
                                      "a lens camera's own equirectangular image is not one (give it as a photo of its own)");
                   }},
        rig.kind);
    photo.topElevation_ = rimTheta - kPi / 2;
    photo.bottomElevation_ = -kPi / 2;
  } else {
    if (photo.image_.width != 2 * photo.image_.height)
      throw InputError(showPath(path) + ": an equirectangular photo must be twice as wide as high (got " +
                       std::to_string(photo.image_.width) + "x" + std::to_string(photo.image_.height) +
                       "); an unwrapped omni image needs its sidecar " + showPath(sidecarPath));
    photo.topElevation_ = kPi / 2;
    photo.bottomElevation_ = -kPi / 2;
  }
  std::vector<float> luminances;
  luminances.reserve(photo.image_.pixels.size() / 4);
  for (size_t p = 0; p < photo.image_.pixels.size(); p += 4) luminances.push_back(luminance(&photo.image_.pixels[p]));
  const size_t k = luminances.size() * 99 / 100;
  std::nth_element(luminances.begin(), luminances.begin() + k, luminances.end());
  const float high = luminances[k];
  if (high > 1.0f) photo.exposure_ = 0.85f / high;  // HDR: a fixed exposure, then clipping
  return photo;
}

Vec3f PanoramaPhoto::sample(double azimuth, double elevation) const {
  const int w = image_.width, h = image_.height;
  const double column = (kPi - azimuth) / (2 * kPi) * w - 0.5;
  const double row = (topElevation_ - elevation) / (topElevation_ - bottomElevation_) * h - 0.5;
  if (row < -0.5 || row > h - 0.5) return {0.0f, 0.0f, 0.0f};
  const double y = std::clamp(row, 0.0, h - 1.0);
  const int j0 = std::min(static_cast<int>(y), h - 1), j1 = std::min(j0 + 1, h - 1);
  const double fy = y - j0;
  const double x = column - std::floor(column / w) * w;  // wraps around the azimuth
  const int i0 = static_cast<int>(x) % w, i1 = (i0 + 1) % w;
  const double fx = x - std::floor(x);
  Vec3f out(0.0f, 0.0f, 0.0f);
  const int is[2] = {i0, i1}, js[2] = {j0, j1};
  const double wx[2] = {1 - fx, fx}, wy[2] = {1 - fy, fy};
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) {
      const float* p = image_.at(is[a], js[b]);
      const float weight = static_cast<float>(wx[a] * wy[b]);
      for (int c = 0; c < 3; ++c) out[c] += weight * p[c];
    }
  for (int c = 0; c < 3; ++c) out[c] = std::clamp(out[c] * exposure_, 0.0f, 1.0f);
  return out;
}

namespace {

// A wall's texture: the photo projected from `centre` onto it, turned by `azimuthOffset`.
ImageRGBA wallTexture(const Wall& wall, const PanoramaPhoto& photo, double azimuthOffset, const Vec3& centre,
                      double texelsPerMetre) {
  const int tw = std::max(8, static_cast<int>(std::lround(wall.edgeU.norm() * texelsPerMetre)));
  const int th = std::max(8, static_cast<int>(std::lround(wall.edgeV.norm() * texelsPerMetre)));
  ImageRGBA texture(tw, th);
  for (int j = 0; j < th; ++j)
    for (int i = 0; i < tw; ++i) {
      // Texel centres; row 0 is the top of the wall (v = 1).
      const Vec3 point = wall.origin + (i + 0.5) / tw * wall.edgeU + (1.0 - (j + 0.5) / th) * wall.edgeV;
      const Vec3 d = point - centre;
      const Vec3f colour = photo.sample(std::atan2(d.y(), d.x()) - azimuthOffset, std::atan2(d.z(), std::hypot(d.x(), d.y())));
      float* p = texture.at(i, j);
      p[0] = colour[0], p[1] = colour[1], p[2] = colour[2], p[3] = 1.0f;
    }
  return texture;
}

// Checks every output name, then makes the scene's folder and, for a `textured` hall, the
// texture folder beside it: a refused name leaves nothing behind.
void makeOutputFolders(const std::string& sceneOut, bool textured, const std::string& textureFolder,
                       const std::vector<std::pair<std::string, ImageRGBA>>& textures) {
  const std::filesystem::path scenePath(sceneOut);
  const std::string sceneFolder = scenePath.parent_path().empty() ? "." : scenePath.parent_path().string();
  std::error_code ec;
  if (std::filesystem::is_directory(sceneFolder, ec)) {
    checkOutputFile(sceneOut, "hall arena");
    // The texture folder beside the scene, not through a link planted under its name.
    if (textured && entryInside(sceneFolder, textureFolder) != EntryKind::Missing) {
      checkFoldersInside(sceneFolder, textureFolder);
      for (const auto& [file, image] : textures) checkOutputFile(file, "hall arena");
    }
  } else {
    checkOutputFolder(sceneFolder, "hall arena");
    std::filesystem::create_directories(sceneFolder, ec);
    if (ec) throw OutputError(showPath(sceneFolder) + ": cannot create folder (" + ec.message() + ")");
  }
  if (textured) makeFoldersInside(sceneFolder, textureFolder);
}

}  // namespace

std::vector<std::string> writeHallArena(const HallOptions& o, const std::string& sceneOut) {
  if (!(o.halfLength > 3.1 && o.halfWidth > 2.2 && o.height > 0.5 && o.projectionHeight > 0 &&
        o.projectionHeight < o.height && o.texelsPerMetre >= 8 && o.texelsPerMetre <= 1024 &&
        o.lampDiameter >= 0.0 && o.lampDiameter <= 2.0))
    throw InputError("hall: the walls must stand outside the carpet (x > 3.1 m, y > 2.2 m), the projection "
                     "centre inside the hall, 8-1024 texels per metre, lamps at most 2 m wide");
  std::vector<PanoramaPhoto> photos;
  for (const std::string& path : o.photos) photos.push_back(PanoramaPhoto::load(path));

  nlohmann::json scene = readJsonFile(o.fieldScene);
  const bool textured = !photos.empty();
  scene["name"] = std::string(scene.value("name", "field")) + (textured ? "-hall-textured" : "-hall");
  scene["description"] = std::string("The field inside a hall: walls ") + (textured ? "carrying planar projections of 360-degree photos" : "plain") +
                         ", a ceiling, generated by `omnicam arena hall` (experiments/hall_arena.h).";
  scene["comment"]["hall_m"] = {{"walls_x", o.halfLength}, {"walls_y", o.halfWidth}, {"height", o.height},
                                {"projection_centre_height", o.projectionHeight}};
  if (scene.contains("lights"))
    for (auto& light : scene["lights"]) light["diameter"] = o.lampDiameter;
  auto& materials = scene["materials"];
  materials["hall_floor"] = {{"color", {0.35, 0.33, 0.3}}, {"ambient", 0.3}, {"diffuse", 0.7}, {"class", "floor"}};
  materials["hall_ceiling"] = {{"color", 0.85}, {"ambient", 0.3}, {"diffuse", 0.7}, {"class", "ceiling"}};
  if (!textured) materials["hall_wall"] = {{"color", {0.75, 0.74, 0.7}}, {"ambient", 0.3}, {"diffuse", 0.7}, {"class", "wall"}};
  auto& objects = scene["objects"];
  const double L = o.halfLength, W = o.halfWidth;
  // Just below the carpet (z = 0), so the carpet and the lines keep their own colour.
  objects.push_back({{"name", "hall_floor"}, {"type", "quad"}, {"material", "hall_floor"},
                     {"origin", {-L, -W, -0.002}}, {"edge_u", {2 * L, 0, 0}}, {"edge_v", {0, 2 * W, 0}}});
  objects.push_back({{"name", "hall_ceiling"}, {"type", "quad"}, {"material", "hall_ceiling"},
                     {"origin", {-L, -W, o.height}}, {"edge_u", {2 * L, 0, 0}}, {"edge_v", {0, 2 * W, 0}}});

  // Every texture is made in memory and every output name checked before the first byte is
  // written: a refused name leaves nothing behind.
  std::vector<std::pair<std::string, ImageRGBA>> textures;
  const std::filesystem::path scenePath(sceneOut);
  const std::string textureFolder = scenePath.stem().string() + "_textures";
  std::mt19937_64 random(o.seed);
  const Vec3 centre(0, 0, o.projectionHeight);
  for (const Wall& wall : hallWalls(o)) {
    const std::string name = std::string("hall_wall_") + wall.name;
    std::string material = "hall_wall";
    if (textured) {
      size_t photoIndex = 0;
      double azimuthOffset = 0.0;
      if (o.randomPhotos) {  // bit arithmetic on the generator: the same walls with any library
        photoIndex = static_cast<size_t>(random() % photos.size());
        azimuthOffset = 2 * kPi * static_cast<double>(random() >> 11) * 0x1.0p-53;
      }
      ImageRGBA texture = wallTexture(wall, photos[photoIndex], azimuthOffset, centre, o.texelsPerMetre);
      const std::string relative = textureFolder + "/" + name + ".png";
      textures.emplace_back((scenePath.parent_path() / relative).string(), std::move(texture));
      material = name;
      materials[material] = {{"color", 1.0}, {"texture", {{"file", relative}}}, {"ambient", 0.3}, {"diffuse", 0.7},
                             {"class", "wall"}};
    }
    objects.push_back({{"name", name}, {"type", "quad"}, {"material", material}, {"origin", vec(wall.origin)},
                       {"edge_u", vec(wall.edgeU)}, {"edge_v", vec(wall.edgeV)}});
  }
  makeOutputFolders(sceneOut, textured, textureFolder, textures);
  std::vector<std::string> written;
  for (const auto& [file, image] : textures) {
    writeImageAtomic(file, image);
    written.push_back(file);
  }
  writeTextAtomically(sceneOut, scene.dump(1) + "\n");
  return written;
}

std::string writeLabHall(const std::string& fieldScene, const std::string& folder) {
  std::filesystem::create_directories(folder);
  HallOptions hall;
  hall.fieldScene = fieldScene;
  hall.photos = {kLabPhoto};
  const std::string scene = (std::filesystem::path(folder) / "hall-textured.json").string();
  writeHallArena(hall, scene);
  return scene;
}

}  // namespace omnicam
