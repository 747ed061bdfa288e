// Recording-camera specs: distributions drawn as stated, deterministic per frame, presets within
// their ranges, stages held neutral, and strict reading with one clear line per mistake.
#include "recording_camera_spec.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>

#include "errors.h"

namespace omnicam {
namespace {

RecordingCameraSpec specOf(const std::string& text) { return recordingCameraSpecFromJson(nlohmann::json::parse(text), "spec.json"); }

std::string errorOf(const std::string& text) {
  try {
    specOf(text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(RecordingCameraSpec, DistributionsAreDrawnAsStated) {
  const RecordingCameraSpec spec = specOf(R"({"exposure_ev": {"uniform": [-1, 0.5]}, "full_well_electrons": {"log_uniform": [100, 10000]},
    "bayer": {"choice": ["rggb", "gbrg"]}, "jpeg_quality": {"uniform": [60, 90]}, "read_noise": 0.01, "seed": 3})");
  ASSERT_TRUE(spec.randomised());
  const int n = 4000;
  double exposureSum = 0, logWellSum = 0;
  std::map<BayerPattern, int> patterns;
  for (int k = 0; k < n; ++k) {
    const RecordingCamera c = spec.draw(static_cast<uint64_t>(k));
    ASSERT_GE(c.exposureEv, -1.0);
    ASSERT_LE(c.exposureEv, 0.5);
    ASSERT_GE(c.fullWellElectrons, 100.0);
    ASSERT_LE(c.fullWellElectrons, 10000.0);
    ASSERT_TRUE(c.jpegQuality >= 60 && c.jpegQuality <= 90);
    ASSERT_EQ(c.readNoise, 0.01);
    exposureSum += c.exposureEv;
    logWellSum += std::log10(c.fullWellElectrons);
    ++patterns[c.bayer];
  }
  // Means of uniform draws: σ/√n = 0.43/63 ≈ 0.007 for the exposure, 0.58/63 for log10 of the well.
  EXPECT_NEAR(exposureSum / n, -0.25, 0.03);
  EXPECT_NEAR(logWellSum / n, 3.0, 0.04);
  EXPECT_EQ(patterns.size(), 2u);
  EXPECT_NEAR(patterns[BayerPattern::RGGB], n / 2, 150);
  // The same index draws the same camera; another index another; the seed matters.
  EXPECT_EQ(spec.draw(17).exposureEv, spec.draw(17).exposureEv);
  EXPECT_NE(spec.draw(17).exposureEv, spec.draw(18).exposureEv);
  RecordingCameraSpec other = spec;
  other.seed = 4;
  EXPECT_NE(other.draw(17).exposureEv, spec.draw(17).exposureEv);
  // A parameter added to the spec leaves the others' draws as they were.
  RecordingCameraSpec more = spec;
  more.draws["vignetting"] = ParameterDraw{ParameterDraw::Kind::Uniform, 0.0, 0.5, {}};
  EXPECT_EQ(more.draw(17).exposureEv, spec.draw(17).exposureEv);
  EXPECT_EQ(more.draw(17).fullWellElectrons, spec.draw(17).fullWellElectrons);
}

TEST(RecordingCameraSpec, IntegersAreDrawnEvenlyAndChoicesOfIntegersKeepTheirValues) {
  // jpeg_quality uniform over [60, 62]: 60, 61 and 62 a third each; a choice of 0 and 95 gives both.
  const RecordingCameraSpec uniform = specOf(R"({"jpeg_quality": {"uniform": [60, 62]}})");
  const RecordingCameraSpec choice = specOf(R"({"jpeg_quality": {"choice": [0, 95]}})");
  std::map<int, int> drawn, chosen;
  for (uint64_t k = 0; k < 3000; ++k) ++drawn[uniform.draw(k).jpegQuality], ++chosen[choice.draw(k).jpegQuality];
  ASSERT_EQ(drawn.size(), 3u);
  for (const auto& [quality, count] : drawn) EXPECT_NEAR(count, 1000, 90) << quality;  // 3.5 σ of a binomial
  ASSERT_EQ(chosen.size(), 2u);
  EXPECT_NEAR(chosen[95], 1500, 100);
  // The machine-vision preset's JPEG: none or 95.
  std::map<int, int> machine;
  for (uint64_t k = 0; k < 200; ++k) ++machine[recordingPreset("machine_vision").draw(k).jpegQuality];
  EXPECT_EQ(machine.size(), 2u);
  EXPECT_TRUE(machine.count(0) && machine.count(95));
}

TEST(RecordingCameraSpec, PresetsDrawWithinTheirRangesAndOverridesWin) {
  for (const std::string& name : recordingPresetNames()) {
    const RecordingCameraSpec preset = recordingPreset(name);
    EXPECT_TRUE(preset.randomised()) << name;
    for (uint64_t k = 0; k < 200; ++k) {
      const RecordingCamera c = preset.draw(k);
      EXPECT_NE(c.bayer, BayerPattern::None) << name;
      EXPECT_GT(c.fullWellElectrons, 900.0) << name;
      EXPECT_LE(std::abs(c.exposureEv), 1.0) << name;
    }
  }
  const RecordingCameraSpec phone = specOf(R"({"preset": "phone", "jpeg_quality": 50})");
  for (uint64_t k = 0; k < 50; ++k) {
    EXPECT_EQ(phone.draw(k).jpegQuality, 50);
    EXPECT_EQ(phone.draw(k).tone, ToneCurve::Filmic);
  }
  // A choice of presets draws each of them.
  const RecordingCameraSpec mixed = specOf(R"({"preset": {"choice": ["webcam", "phone"]}})");
  int filmic = 0;
  for (uint64_t k = 0; k < 400; ++k) filmic += mixed.draw(k).tone == ToneCurve::Filmic;
  EXPECT_NEAR(filmic, 200, 40);
  EXPECT_EQ(specOf(R"("webcam")"), specOf(R"({"preset": "webcam"})"));
  // The drawn values read back as a fixed camera, exactly.
  const RecordingCamera drawn = mixed.draw(11);
  const RecordingCamera back = recordingCameraFromJson(nlohmann::json::parse(recordingCameraToJson(drawn).dump()), "manifest.json");
  EXPECT_EQ(recordingCameraToJson(back), recordingCameraToJson(drawn));
  // The spec reads back from what omnicam writes of it.
  EXPECT_EQ(recordingCameraSpecFromJson(recordingCameraSpecToJson(mixed), "x"), mixed);
}

TEST(RecordingCameraSpec, AStageHeldNeutralDoesNothing) {
  RecordingCamera everything = recordingPreset("phone").draw(3);
  everything.chromaticAberration = 0.01;
  RecordingCamera neutral = everything;
  for (const std::string& stage : recordingStages()) neutral = withStageNeutral(neutral, stage);
  EXPECT_EQ(recordingCameraToJson(neutral).dump(), [&] {
    RecordingCamera c;
    c.seed = everything.seed;
    return recordingCameraToJson(c).dump();
  }());
  const RecordingCamera noBlur = withStageNeutral(everything, "blur");
  EXPECT_EQ(noBlur.blurRadiusPx, 0.0);
  EXPECT_EQ(noBlur.jpegQuality, everything.jpegQuality);
}

// Which of a camera's values no camera of a spec has: beyond every preset's range, unlike its
// fixed values and choices, the spec's own draws winning over its presets'.
TEST(RecordingCameraSpec, TheParametersBeyondASpecAreThoseNoDrawCanGive) {
  const RecordingCameraSpec mix = specOf(R"({"preset": {"choice": ["webcam", "machine_vision", "phone"]}})");
  for (uint64_t k = 0; k < 100; ++k) EXPECT_EQ(parametersBeyond(mix, mix.draw(k)), std::vector<std::string>{}) << k;
  // The examples' noisy test camera: less full well, more read and row noise than any preset's.
  const RecordingCamera noisy = specOf(R"({"exposure_ev": -0.5, "white_balance": [0.85, 1, 1.2], "vignetting": 0.25,
      "bayer": "grbg", "demosaic": "bilinear", "full_well_electrons": 700, "read_noise": 0.015, "row_noise": 0.004,
      "jpeg_quality": 75})").draw(0);
  EXPECT_EQ(parametersBeyond(mix, noisy), (std::vector<std::string>{"full_well_electrons", "read_noise", "row_noise"}));
  // At a range's ends (webcam's read noise 0.012, machine vision's full well 30000) it is within.
  RecordingCamera atEnds = noisy;
  atEnds.fullWellElectrons = 30000, atEnds.readNoise = 0.012, atEnds.rowNoise = 0.003;
  EXPECT_EQ(parametersBeyond(mix, atEnds), std::vector<std::string>{});
  // Every preset mosaics: a camera without a mosaic is beyond them (and its demosaic, unused, is not).
  RecordingCamera noMosaic = atEnds;
  noMosaic.bayer = BayerPattern::None;
  EXPECT_EQ(parametersBeyond(mix, noMosaic), std::vector<std::string>{"bayer"});
  // The spec's own draw wins: exposure held to ±0.1 EV puts −0.5 EV beyond it; without machine
  // vision a full well of 30000 e⁻ is beyond too.
  const RecordingCameraSpec narrow = specOf(R"({"preset": {"choice": ["webcam", "phone"]}, "exposure_ev": {"uniform": [-0.1, 0.1]}})");
  EXPECT_EQ(parametersBeyond(narrow, atEnds), (std::vector<std::string>{"exposure_ev", "full_well_electrons"}));
  // Without a preset each parameter not given is its neutral value.
  const RecordingCameraSpec plain = specOf(R"({"jpeg_quality": {"choice": [80, 90]}})");
  RecordingCamera jpeg;
  jpeg.jpegQuality = 90;
  EXPECT_EQ(parametersBeyond(plain, jpeg), std::vector<std::string>{});
  jpeg.jpegQuality = 85, jpeg.vignetting = 0.1;
  EXPECT_EQ(parametersBeyond(plain, jpeg), (std::vector<std::string>{"vignetting", "jpeg_quality"}));
  // What the report names beside the ablation: the stage of each such parameter.
  EXPECT_EQ(recordingStageOf("full_well_electrons"), "noise");
  EXPECT_EQ(recordingStageOf("white_balance[2]"), "white_balance");
  EXPECT_EQ(recordingStageOf("demosaic"), "bayer");
  EXPECT_EQ(recordingStageOf("no_such_parameter"), "");
}

// A drawn camera (a sidecar's or a manifest's, every field given, those its choices leave unused
// included) reads back as the same camera.
TEST(RecordingCameraSpec, ADrawnCameraReadsBackAsItself) {
  for (const char* preset : {"webcam", "machine_vision", "phone"}) {
    const RecordingCamera drawn = specOf(std::string("{\"preset\": \"") + preset + "\"}").draw(3);
    EXPECT_EQ(recordingCameraToJson(recordingCameraFromJson(recordingCameraToJson(drawn), "manifest.json")), recordingCameraToJson(drawn))
        << preset;
    EXPECT_EQ(errorOf(recordingCameraToJson(drawn).dump()), "(accepted)") << preset;  // as --recording FILE, recording=
    // It says which preset it came from, and keeps saying so when given back.
    EXPECT_EQ(recordingCameraToJson(drawn).at("drawn_from_preset"), preset);
    EXPECT_EQ(specOf(recordingCameraToJson(drawn).dump()).draw(7).drawnFromPreset, preset);
  }
  // Of a mix, each frame's own preset: the one whose ranges its values were drawn from.
  const RecordingCameraSpec mix = specOf(R"({"preset": {"choice": ["webcam", "machine_vision", "phone"]}, "seed": 4})");
  std::set<std::string> seen;
  for (uint64_t frame = 0; frame < 40; ++frame) {
    const RecordingCamera camera = mix.draw(frame);
    seen.insert(camera.drawnFromPreset);
    EXPECT_EQ(camera.tone == ToneCurve::Filmic, camera.drawnFromPreset == "phone") << frame;  // only the phone's curve is filmic
  }
  EXPECT_EQ(seen, (std::set<std::string>{"webcam", "machine_vision", "phone"}));
  EXPECT_EQ(RecordingCameraSpec{}.draw(0).drawnFromPreset, "");
  EXPECT_EQ(recordingCameraToJson(RecordingCamera::webcam()).count("drawn_from_preset"), 0u);
}

TEST(RecordingCameraSpec, BadInputGetsOneLineNamingTheField) {
  EXPECT_EQ(errorOf(R"({"iso": 100})").rfind("spec.json: recording.iso: unknown field", 0), 0u);
  EXPECT_EQ(errorOf(R"({"exposure_ev": {"gaussian": [0, 1]}})"),
            "spec.json: recording.exposure_ev: unknown distribution \"gaussian\" (uniform, log_uniform, choice)");
  EXPECT_EQ(errorOf(R"({"exposure_ev": {"uniform": [1, -1]}})"), "spec.json: recording.exposure_ev.uniform: lo > hi (1 > -1)");
  EXPECT_EQ(errorOf(R"({"vignetting": {"uniform": [0, 1.5]}})"),
            "spec.json: recording.vignetting.uniform[1]: must be a number in [0, 1] (got 1.5)");
  EXPECT_EQ(errorOf(R"({"full_well_electrons": {"log_uniform": [0, 100]}})"),
            "spec.json: recording.full_well_electrons.log_uniform: log_uniform needs lo > 0 (got 0)");
  EXPECT_EQ(errorOf(R"({"bayer": "rgbg"})"), "spec.json: recording.bayer: must be one of none, rggb, bggr, grbg, gbrg (got \"rgbg\") (did you mean rggb?)");
  EXPECT_EQ(errorOf(R"({"bayer": {"choice": ["rggb", "xyz"]}})"),
            "spec.json: recording.bayer.choice[1]: must be one of none, rggb, bggr, grbg, gbrg (got \"xyz\")");
  EXPECT_EQ(errorOf(R"({"bayer": {"uniform": [0, 1]}})"), "spec.json: recording.bayer.uniform: a word is drawn with {\"choice\": [...]}");
  EXPECT_EQ(errorOf(R"({"preset": "dslr"})"),
            "spec.json: recording.preset: must be one of webcam, machine_vision, phone (got \"dslr\")");
  EXPECT_EQ(errorOf(R"({"preset": "webcm"})"),
            "spec.json: recording.preset: must be one of webcam, machine_vision, phone (got \"webcm\") (did you mean webcam?)");
  EXPECT_EQ(errorOf(R"({"exposure_ev": {"uniform": [-1, 1, 2]}})"), "spec.json: recording.exposure_ev.uniform: must be [lo, hi] (got an array of 3)");
  EXPECT_EQ(errorOf(R"("dslr")"), "spec.json: recording: unknown preset \"dslr\" (webcam, machine_vision, phone; or a camera of its own: an object of the stages' fields, docs/experiments.md)");
  EXPECT_EQ(errorOf(R"("webcm")"), "spec.json: recording: unknown preset \"webcm\" (did you mean webcam?) (webcam, machine_vision, phone; or a camera of its own: an object of the stages' fields, docs/experiments.md)");
  EXPECT_EQ(errorOf(R"({"jpeg_quality": 80.5})"), "spec.json: recording.jpeg_quality: must be an integer in [0, 100] (0: no JPEG) (got 80.5)");
  // An integer's range has integer ends ([60.2, 60.8] drew 60, outside it), and no log-uniform draw.
  EXPECT_EQ(errorOf(R"({"jpeg_quality": {"uniform": [60.2, 60.8]}})"),
            "spec.json: recording.jpeg_quality.uniform[0]: must be an integer in [0, 100] (got 60.2)");
  EXPECT_EQ(errorOf(R"({"jpeg_quality": {"log_uniform": [10, 90]}})"),
            "spec.json: recording.jpeg_quality.log_uniform: an integer is drawn with {\"uniform\": [lo, hi]} or {\"choice\": [...]}");
  EXPECT_EQ(errorOf(R"({"white_balance": [1, 0, 1]})"), "spec.json: recording.white_balance[1]: must be a number in (0, 10] (got 0)");
  EXPECT_EQ(errorOf(R"({"white_balance": 1})"),
            "spec.json: recording.white_balance: must be [r, g, b], each a gain in (0, 10] or a distribution (got 1)");
  EXPECT_EQ(errorOf(R"({"exposure_ev": {"uniform": [0, 1], "choice": [1]}})").rfind("spec.json: recording.exposure_ev: a distribution is one of", 0), 0u);
  EXPECT_EQ(errorOf(R"({"gamma": {"choice": []}})"), "spec.json: recording.gamma.choice: must be a list of 1 to 64 values (got an array of 0)");
  EXPECT_EQ(errorOf(R"({"seed": -1})"), "spec.json: recording.seed: must be an integer in [0, 2^64 - 1] (got -1)");
  EXPECT_EQ(errorOf(R"({"read_noise": "0.1"})"), "spec.json: recording.read_noise: must be a number in [0, 1] (got \"0.1\")");
  // A setting that would do nothing in every frame: its stage's switch is never on, by the spec's
  // own value, by every preset it may draw, or by default. One that acts in some frame is kept.
  EXPECT_EQ(errorOf(R"({"preset": "phone", "gamma": 2})"),
            "spec.json: recording.gamma: does nothing unless tone_curve is gamma, and it is filmic (the preset's) here: "
            "give \"tone_curve\": \"gamma\", or leave gamma out");
  EXPECT_EQ(errorOf(R"({"contrast": 1.2, "tone_curve": {"choice": ["srgb", "gamma"]}})"),
            "spec.json: recording.contrast: does nothing unless tone_curve is filmic, and it is srgb or gamma here: "
            "give \"tone_curve\": \"filmic\", or leave contrast out");
  EXPECT_EQ(errorOf(R"({"demosaic": "vng"})"),
            "spec.json: recording.demosaic: does nothing unless bayer is a pattern, and it is none (its default) here: "
            "give a bayer pattern, or leave demosaic out");
  EXPECT_EQ(errorOf(R"({"preset": {"choice": ["machine_vision", "webcam"]}, "contrast": 1.2})"),
            "spec.json: recording.contrast: does nothing unless tone_curve is filmic, and it is srgb or gamma (the presets') here: "
            "give \"tone_curve\": \"filmic\", or leave contrast out");
  // A kernel without a blur, told by the radius's range: its ends (a range [0, r] blurs in some
  // frame). Its default, gaussian, is kept: drawn cameras written before 2026-12-02 held it.
  EXPECT_EQ(errorOf(R"({"blur_kernel": "disc"})"),
            "spec.json: recording.blur_kernel: does nothing unless blur_radius_px > 0, and it is 0 (its default) here: "
            "give a blur_radius_px, or leave blur_kernel out");
  EXPECT_EQ(errorOf(R"({"blur_kernel": "disc", "blur_radius_px": {"choice": [0]}})"),
            "spec.json: recording.blur_kernel: does nothing unless blur_radius_px > 0, and it is 0 here: "
            "give a blur_radius_px, or leave blur_kernel out");
  EXPECT_EQ(errorOf(R"({"blur_kernel": "disc", "blur_radius_px": {"uniform": [0, 0]}})"),
            "spec.json: recording.blur_kernel: does nothing unless blur_radius_px > 0, and it is 0 here: "
            "give a blur_radius_px, or leave blur_kernel out");
  EXPECT_EQ(errorOf(R"({"blur_kernel": "disc", "blur_radius_px": {"uniform": [0, 2]}})"), "(accepted)");
  EXPECT_EQ(errorOf(R"({"blur_kernel": "gaussian", "blur_radius_px": 0, "exposure_ev": 0.3})"), "(accepted)");
  EXPECT_EQ(errorOf(R"({"blur_kernel": "disc", "blur_radius_px": {"choice": [0, 2]}})"), "(accepted)");
  EXPECT_EQ(errorOf(R"({"preset": "webcam", "blur_kernel": "disc"})"), "(accepted)");  // the webcam blurs up to 1.2 px
  EXPECT_EQ(errorOf(R"({"preset": "webcam", "gamma": 2})"), "(accepted)");  // the webcam draws gamma or srgb
  EXPECT_EQ(errorOf(R"({"preset": {"choice": ["webcam", "phone"]}, "contrast": 1.2})"), "(accepted)");
  EXPECT_EQ(errorOf(R"({"preset": "phone", "tone_curve": "gamma", "gamma": 2})"), "(accepted)");
  EXPECT_EQ(errorOf(R"({"preset": "webcam", "drawn_from_preset": "webcam"})"),
            "spec.json: recording.drawn_from_preset: says which preset a drawn camera came from: not beside preset, which draws one");
  EXPECT_EQ(errorOf(R"({"exposure_ev": 0.1, "drawn_from_preset": "phnoe"})"),
            "spec.json: recording.drawn_from_preset: must be one of webcam, machine_vision, phone (got \"phnoe\") (did you mean phone?)");
  // A single camera (a manifest's drawn values) refuses ranges.
  EXPECT_THROW(recordingCameraFromJson(nlohmann::json::parse(R"({"exposure_ev": {"uniform": [0, 1]}})"), "m.json"), InputError);
  EXPECT_THROW(recordingCameraFromJson(nlohmann::json::parse(R"("webcam")"), "m.json"), InputError);
}

}  // namespace
}  // namespace omnicam
