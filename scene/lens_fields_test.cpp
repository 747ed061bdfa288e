// The scene format's rig.lens: what it writes reads back to the same rig bit for bit (rig
// equality keys every cache and a resumed dataset's frames), for every model, with angles whose
// degrees ↔ radians conversion is not exact both ways.
#include "lens_fields.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "errors.h"
#include "lens_camera.h"
#include "scene_loader.h"
#include "sidecar.h"

namespace omnicam {
namespace {

using nlohmann::json;

RigSpec readBack(const RigSpec& rig) { return rigFromJson(rigToJson(rig), "sidecar.json", "rig"); }

TEST(LensFields, EveryModelReadsBackBitForBit) {
  int checked = 0;
  for (const double angle : {69.0, 75.0, 85.0, 138.0, 150.0, 17.3, 99.99}) {
    const json lenses[] = {
        {{"model", "kannala_brandt"}, {"width", 320}, {"height", 240}, {"fx", 95.5}, {"fy", 96.0}, {"cx", 161.25}, {"cy", 118.0},
         {"k", {0.02, -0.005, 0.001, -0.0002}}, {"max_theta_deg", std::min(angle, 100.0)}, {"rotation_deg", {1.5, -angle / 2, angle}}},
        {{"model", "double_sphere"}, {"width", 320}, {"height", 240}, {"fx", 120}, {"fy", 121}, {"xi", -0.2}, {"alpha", 0.6}},
        {{"model", "eucm"}, {"width", 320}, {"height", 240}, {"fx", 150}, {"fy", 149}, {"alpha", 0.6}, {"beta", 1.1}},
        {{"model", "fisheye_equidistant"}, {"width", 200}, {"height", 150}, {"f_px", 40}, {"fov_deg", 2 * angle}},
        {{"model", "fisheye_equisolid"}, {"width", 160}, {"height", 160}, {"f_px", 55}, {"fov_deg", angle}},
        {{"model", "fisheye_polynomial"}, {"width", 200}, {"height", 150}, {"k", {0, 0.0125, 1.5e-5, -4e-8, 0}}, {"fov_deg", angle}},
        {{"model", "equirectangular"}, {"width", 256}, {"height", 128}, {"longitude_deg", {-angle, angle / 3}},
         {"latitude_deg", {-angle / 2, 0.1 * angle}}},
        {{"model", "pinhole"}, {"width", 320}, {"height", 240}, {"fx", 300}, {"fy", 302},
         {"distortion", {{"k1", -0.2}, {"k2", 0.05}, {"p1", 0.001}, {"p2", -0.002}, {"k3", 0.01}}}}};
    for (const json& lens : lenses) {
      const RigSpec rig = rigFromJson({{"height", 0.4}, {"lens", lens}, {"tilt_deg", {1, -2}}}, "scene.json", "rig");
      ASSERT_TRUE(std::holds_alternative<LensCameraSpec>(rig.kind));
      EXPECT_TRUE(readBack(rig) == rig) << lens.dump() << "\n -> " << rigToJson(rig).dump();
      EXPECT_TRUE(readBack(rig.resized(2 * rig.lensCamera().width)) == rig.resized(2 * rig.lensCamera().width)) << lens.dump();
      ++checked;
    }
  }
  EXPECT_EQ(checked, 56);
}

// Each model takes only its own fields, range-checked; the mirror's blocks are refused beside it.
TEST(LensFields, FieldsOfOtherModelsAndOutOfRangeValuesAreRefused) {
  const json kb = {{"model", "kannala_brandt"}, {"width", 64}, {"height", 48}, {"fx", 20}, {"fy", 20}};
  const auto problem = [](const json& rig) {
    try {
      (void)rigFromJson(rig, "scene.json", "rig");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(problem({{"lens", kb}, {"image", {{"size", 64}}}}).find("rig.image: a lens camera"), std::string::npos);
  json foreign = kb;
  foreign["f_px"] = 3;
  EXPECT_NE(problem({{"lens", foreign}}).find("rig.lens.f_px: unknown field"), std::string::npos);
  // A pinhole's fx on a one-focal model points at f_px, not at the nearest spelling (cx).
  const json fisheye = {{"model", "fisheye_equidistant"}, {"width", 64}, {"height", 64}, {"fx", 20}};
  EXPECT_NE(problem({{"lens", fisheye}}).find("rig.lens.fx: unknown field (this model has one focal length: f_px)"),
            std::string::npos) << problem({{"lens", fisheye}});
  json fy = kb;
  fy["fy"] = -1;
  EXPECT_NE(problem({{"lens", fy}}).find("rig.lens.fy: must be in (0, 1e+06]"), std::string::npos) << problem({{"lens", fy}});
  json pitch = kb;
  pitch["rotation_deg"] = {0, 100, 0};
  EXPECT_NE(problem({{"lens", pitch}}).find("rig.lens.rotation_deg: pitch"), std::string::npos);
  // A polynomial that leaves the field of view and comes back images some directions twice.
  const json twice = {{"model", "fisheye_polynomial"}, {"width", 200}, {"height", 200}, {"k", {0, 0.03, -2e-4, 0, 0}},
                      {"fov_deg", 100}};
  EXPECT_NE(problem({{"lens", twice}}).find("rig.lens.k: θ(r) comes back inside the field of view"), std::string::npos)
      << problem({{"lens", twice}});
  // A width that cannot keep the aspect exactly.
  const RigSpec rig = rigFromJson({{"lens", json(kb)}}, "scene.json", "rig");
  EXPECT_THROW((void)rig.resized(99), InputError);
  EXPECT_EQ(rig.resized(96).lensCamera().height, 72);
}

// Issue #45: an equidistant lens whose small circle lies mostly left of the image still images
// pixel centres along the left edge; the reader took only the principal point's pixel and a
// 64 × 64 grid and refused it.
TEST(LensFields, ASmallCircleOffTheImageIsAcceptedWhenItCoversPixelCentres) {
  const json lens = {{"model", "fisheye_equidistant"}, {"width", 4096}, {"height", 64}, {"f_px", 400}, {"fov_deg", 10},
                     {"cx", -10}, {"cy", 31.5}};
  // The circle r = f·θmax about (cx, cy), counted in closed form: 1246 pixel centres (the count).
  const double radius = 400.0 * radians(5.0);
  int covered = 0;
  for (int j = 0; j < 64; ++j)
    for (int i = 0; i < 4096; ++i) covered += std::hypot(i + 10.0, j - 31.5) <= radius;
  EXPECT_EQ(covered, 1246);
  const RigSpec rig = rigFromJson({{"lens", lens}}, "scene.json", "rig");
  ASSERT_TRUE(std::holds_alternative<LensCameraSpec>(rig.kind));
  EXPECT_TRUE(imagesSomePixel(rig.lensCamera()));
  // Moved one radius and a pixel further left, it images nothing: refused.
  json gone = lens;
  gone["cx"] = -radius - 1.0;
  EXPECT_THROW((void)rigFromJson({{"lens", gone}}, "scene.json", "rig"), InputError);
}

// imagesSomePixel's shortcut (the pixel nearest the centre and its neighbours) agrees with asking
// every pixel centre, for each model whose image is a disc (imagesADisc), over centres inside, at the edge of and off the image, and
// circles from a fraction of a pixel to the whole image — including a polynomial f-θ lens with
// k0 > 0 on an integer centre, whose own centre pixel is not imaged.
TEST(LensFields, ImagesSomePixelAgreesWithAskingEveryPixel) {
  const int width = 24, height = 16;
  const auto everyPixel = [&](const LensCameraSpec& lens) {
    RigSpec rig;
    rig.kind = lens;
    const LensCamera camera(rig);
    for (int j = 0; j < lens.height; ++j)
      for (int i = 0; i < lens.width; ++i)
        if (camera.images(Vec2(i + 0.5, j + 0.5))) return true;
    return false;
  };
  int imaged = 0, notImaged = 0;
  for (const double cx : {-24.0, -7.3, -3.0, -0.6, 0.0, 5.0, 11.5, 23.0, 23.4, 30.0, 47.9})
    for (const double cy : {-16.0, -2.5, 0.0, 7.5, 8.0, 15.2, 19.0, 32.0})
      for (const double size : {0.3, 1.0, 2.2, 4.0, 9.5, 40.0}) {
        FThetaLens equidistant;
        equidistant.f = size, equidistant.cx = cx, equidistant.cy = cy, equidistant.maxThetaRad = radians(60.0);
        FThetaLens equisolid = equidistant;
        equisolid.kind = FThetaLens::Kind::Equisolid;
        FThetaLens polynomial = equidistant;
        polynomial.kind = FThetaLens::Kind::Polynomial;
        polynomial.k = {0.3, 0.5 / size, 0.0, 0.0, 0.0};  // k0 > 0: the centre sees a cone, not imaged
        KannalaBrandt kb;
        kb.fx = size, kb.fy = 1.7 * size, kb.cx = cx, kb.cy = cy, kb.k = {0.05, 0.0, 0.0, 0.0}, kb.maxThetaRad = radians(70.0);
        DoubleSphere ds;
        ds.fx = 0.6 * size, ds.fy = 0.4 * size, ds.cx = cx, ds.cy = cy, ds.xi = -0.3, ds.alpha = 0.7;
        ExtendedUnified eucm;
        eucm.fx = size, eucm.fy = size, eucm.cx = cx, eucm.cy = cy, eucm.alpha = 0.7, eucm.beta = 1.5;
        PinholeRadTan pinhole;  // undistorted: a pinhole with distortion is searched on a grid (not exact)
        pinhole.fx = 3 * size, pinhole.fy = 2 * size, pinhole.cx = cx, pinhole.cy = cy;
        for (const LensModel& model : std::vector<LensModel>{equidistant, equisolid, polynomial, kb, ds, eucm, pinhole}) {
          const LensCameraSpec lens{model, width, height, {0.0, 0.0, 0.0}};
          const bool expected = everyPixel(lens);
          EXPECT_EQ(imagesSomePixel(lens), expected) << lensModelName(model) << " centre (" << cx << ", " << cy << ") size " << size;
          (expected ? imaged : notImaged) += 1;
        }
      }
  // Both answers were asked for many times.
  EXPECT_GT(imaged, 500);
  EXPECT_GT(notImaged, 500);
}

}  // namespace
}  // namespace omnicam
