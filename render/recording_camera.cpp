#include "recording_camera.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <random>

#include "float_environment.h"
#include "image.h"
#include "seed_mixing.h"

namespace omnicam {

RecordingCamera RecordingCamera::webcam() {
  RecordingCamera camera;
  camera.exposureEv = 0.3;
  camera.whiteBalance = {1.12, 1.0, 0.84};  // balanced for daylight, shooting under warm lamps
  camera.vignetting = 0.35;
  camera.fullWellElectrons = 2500.0;
  camera.readNoise = 0.008;
  camera.jpegQuality = 80;
  return camera;
}

namespace {

// Neighbouring frame indices give unrelated streams.
uint64_t noiseSeed(uint64_t seed, uint64_t frameIndex) { return mixBits(seed + kGoldenGamma * (frameIndex + 1)); }

// Each Bayer pattern as OpenCV's demosaicing names it (its RGGB… aliases), per method.
int demosaicCode(BayerPattern pattern, DemosaicMethod method) {
  static const int codes[4][3] = {
      {cv::COLOR_BayerRGGB2BGR, cv::COLOR_BayerRGGB2BGR_VNG, cv::COLOR_BayerRGGB2BGR_EA},
      {cv::COLOR_BayerBGGR2BGR, cv::COLOR_BayerBGGR2BGR_VNG, cv::COLOR_BayerBGGR2BGR_EA},
      {cv::COLOR_BayerGRBG2BGR, cv::COLOR_BayerGRBG2BGR_VNG, cv::COLOR_BayerGRBG2BGR_EA},
      {cv::COLOR_BayerGBRG2BGR, cv::COLOR_BayerGBRG2BGR_VNG, cv::COLOR_BayerGBRG2BGR_EA},
  };
  return codes[static_cast<int>(pattern) - 1][static_cast<int>(method)];
}

cv::Mat planeMat(LinearPlanes& planes, int c) { return cv::Mat(planes.height, planes.width, CV_32F, planes.rgb[static_cast<size_t>(c)].data()); }

LinearPlanes premultipliedPlanes(const ImageRGBA& image) {
  LinearPlanes planes;
  planes.width = image.width;
  planes.height = image.height;
  for (auto& plane : planes.rgb) plane.assign(static_cast<size_t>(image.width) * image.height, 0.0f);
  for (int j = 0; j < image.height; ++j)
    for (int i = 0; i < image.width; ++i)
      for (int c = 0; c < 3; ++c) planes.at(c, i, j) = image.at(i, j)[3] > 0 ? image.at(i, j)[c] : 0.0f;
  return planes;
}

// What the sensor does to one colour sample `value` (irradiance × exposure × gain): shot, read
// and row noise, then the ADC's clipping.
struct SensorNoise {
  const RecordingCamera& camera;
  std::mt19937_64& random;
  std::normal_distribution<double>& gaussian;
  double operator()(double value, double rowOffset) const {
    if (camera.fullWellElectrons > 0) {
      const double electrons = std::max(0.0, value) * camera.fullWellElectrons;
      // Poisson(0) is 0 (and outside the distribution's domain: no draw).
      value = electrons > 0 ? static_cast<double>(std::poisson_distribution<int64_t>(electrons)(random)) / camera.fullWellElectrons : 0.0;
    }
    if (camera.readNoise > 0) value += camera.readNoise * gaussian(random);
    return std::clamp(value + rowOffset, 0.0, 1.0);
  }
};

// In float, as the 8-bit codes have always been computed (the golden hashes hold them).
unsigned char eightBit(double encoded) {
  return static_cast<unsigned char>(std::lround(std::clamp(static_cast<float>(encoded), 0.0f, 1.0f) * 255.0f));
}

}  // namespace

int bayerColourAt(BayerPattern pattern, int i, int j) {
  static const int layouts[4][4] = {{0, 1, 1, 2}, {2, 1, 1, 0}, {1, 0, 2, 1}, {1, 2, 0, 1}};  // RGGB, BGGR, GRBG, GBRG
  return layouts[static_cast<int>(pattern) - 1][(j & 1) * 2 + (i & 1)];
}

void applyLensBlur(LinearPlanes& planes, double radiusPx, BlurKernel kernel) {
  if (radiusPx <= 0) return;
  cv::Mat psf;
  if (kernel == BlurKernel::Gaussian) {
    const int half = static_cast<int>(std::ceil(3.0 * radiusPx));
    const cv::Mat g = cv::getGaussianKernel(2 * half + 1, radiusPx, CV_32F);
    psf = g * g.t();
  } else {
    // A uniform disc: each cell weighted by the share of its area inside the radius (8×8 samples).
    const int half = static_cast<int>(std::ceil(radiusPx));
    psf = cv::Mat::zeros(2 * half + 1, 2 * half + 1, CV_32F);
    for (int y = -half; y <= half; ++y)
      for (int x = -half; x <= half; ++x) {
        int inside = 0;
        for (int sy = 0; sy < 8; ++sy)
          for (int sx = 0; sx < 8; ++sx) {
            const double px = x - 0.5 + (sx + 0.5) / 8.0, py = y - 0.5 + (sy + 0.5) / 8.0;
            inside += px * px + py * py <= radiusPx * radiusPx;
          }
        psf.at<float>(y + half, x + half) = static_cast<float>(inside);
      }
    const double total = cv::sum(psf)[0];
    if (total == 0) return;  // a radius below every sample's distance: the point stays a point
    psf /= total;
  }
  for (int c = 0; c < 3; ++c) {
    cv::Mat plane = planeMat(planes, c);
    cv::filter2D(plane.clone(), plane, CV_32F, psf, cv::Point(-1, -1), 0.0, cv::BORDER_CONSTANT);
  }
}

void applyChromaticAberration(LinearPlanes& planes, double aberration) {
  if (aberration == 0) return;
  const double cx = 0.5 * planes.width, cy = 0.5 * planes.height;
  for (const auto& [c, magnification] : {std::pair{0, 1.0 + aberration}, std::pair{2, 1.0 - aberration}}) {
    // The channel's image is magnified about the centre: the value at pixel centre p comes from
    // centre + (p − centre) / magnification (pixel centres at index + 0.5).
    cv::Mat mapX(planes.height, planes.width, CV_32F), mapY(planes.height, planes.width, CV_32F);
    for (int j = 0; j < planes.height; ++j)
      for (int i = 0; i < planes.width; ++i) {
        mapX.at<float>(j, i) = static_cast<float>(cx + (i + 0.5 - cx) / magnification - 0.5);
        mapY.at<float>(j, i) = static_cast<float>(cy + (j + 0.5 - cy) / magnification - 0.5);
      }
    cv::Mat plane = planeMat(planes, c);
    cv::remap(plane.clone(), plane, mapX, mapY, cv::INTER_LINEAR, cv::BORDER_CONSTANT, 0.0);
  }
}

double toneCurveValue(const RecordingCamera& camera, double v) {
  v = std::clamp(v, 0.0, 1.0);
  switch (camera.tone) {
    case ToneCurve::Srgb: return linearToSrgb(static_cast<float>(v));
    case ToneCurve::Gamma: return std::pow(v, 1.0 / camera.gamma);
    case ToneCurve::Filmic: {
      const double x = std::pow(v, 1.0 / 2.2), a = std::pow(x, camera.contrast), b = std::pow(1.0 - x, camera.contrast);
      return a + b > 0 ? a / (a + b) : 0.0;
    }
  }
  return v;
}

namespace {

// The light the sensor receives, after the optics (premultiplied: black beyond the mirror), and
// what divides it into a pixel's colour: 1 where the mirror covers the pixel, its coverage
// (through the same optics, per channel) where it covers part of it — a rim pixel's colour is the
// light of its covered part. Without optics: the rendered colour over its alpha, as always.
struct SensorLight {
  LinearPlanes light, coverage;
  bool optics = false;
  double colour(const ImageRGBA& linear, int c, int i, int j) const {
    const double alpha = linear.at(i, j)[3];
    const double divisor = !optics ? alpha : alpha >= 1.0 ? 1.0 : std::max<double>(coverage.at(c, i, j), alpha);
    return light.at(c, i, j) / divisor;
  }
};

SensorLight sensorLight(const RecordingCamera& camera, const ImageRGBA& linear) {
  SensorLight s;
  s.light = premultipliedPlanes(linear);
  s.optics = camera.blurRadiusPx > 0 || camera.chromaticAberration != 0;
  if (!s.optics) return s;
  s.coverage.width = linear.width;
  s.coverage.height = linear.height;
  for (auto& plane : s.coverage.rgb) plane.resize(static_cast<size_t>(linear.width) * linear.height);
  for (int j = 0; j < linear.height; ++j)
    for (int i = 0; i < linear.width; ++i)
      for (int c = 0; c < 3; ++c) s.coverage.at(c, i, j) = std::max(0.0f, linear.at(i, j)[3]);
  for (LinearPlanes* planes : {&s.light, &s.coverage}) {
    applyLensBlur(*planes, camera.blurRadiusPx, camera.blurKernel);
    applyChromaticAberration(*planes, camera.chromaticAberration);
  }
  return s;
}

// One offset per row, from a stream of its own (the pixels' stream stays as it was without it).
std::vector<double> rowOffsets(const RecordingCamera& camera, uint64_t seed, int rows) {
  std::vector<double> offsets(static_cast<size_t>(rows), 0.0);
  if (camera.rowNoise <= 0) return offsets;
  std::mt19937_64 random(seed ^ 0xA0761D6478BD642Full);
  std::normal_distribution<double> gaussian(0.0, camera.rowNoise);
  for (double& offset : offsets) offset = gaussian(random);
  return offsets;
}

// The sensor and the ADC: vignetting, exposure and white balance, the mosaic's colour at each
// site, noise, clipping; then demosaicing. Linear RGB in [0, 1] per pixel (CV_64FC3, RGB order).
cv::Mat sensedColour(const RecordingCamera& camera, const ImageRGBA& linear, const SensorLight& light, uint64_t seed) {
  const int w = linear.width, h = linear.height;
  std::mt19937_64 random(seed);
  std::normal_distribution<double> gaussian(0.0, 1.0);
  const std::vector<double> rowOffset = rowOffsets(camera, seed, h);
  const bool mosaic = camera.bayer != BayerPattern::None;
  const bool eightBitRaw = camera.demosaic == DemosaicMethod::Vng;  // OpenCV's VNG takes 8-bit only
  const double rawScale = eightBitRaw ? 255.0 : 65535.0;
  cv::Mat raw(h, w, eightBitRaw ? CV_8U : CV_16U, cv::Scalar(0));
  cv::Mat sensed(h, w, CV_64FC3, cv::Scalar(0, 0, 0));
  const double gain = std::exp2(camera.exposureEv);
  const double halfDiagonalSquared = 0.25 * (static_cast<double>(w) * w + static_cast<double>(h) * h);
  const SensorNoise noise{camera, random, gaussian};
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      if (linear.at(i, j)[3] <= 0) continue;
      const double dx = i + 0.5 - 0.5 * w, dy = j + 0.5 - 0.5 * h;
      const double vignette = 1.0 - camera.vignetting * (dx * dx + dy * dy) / halfDiagonalSquared;
      auto sample = [&](int c) {
        return noise(light.colour(linear, c, i, j) * gain * camera.whiteBalance[static_cast<size_t>(c)] * vignette,
                     rowOffset[static_cast<size_t>(j)]);
      };
      if (!mosaic) {
        for (int c = 0; c < 3; ++c) sensed.at<cv::Vec3d>(j, i)[c] = sample(c);
      } else if (eightBitRaw) {
        raw.at<unsigned char>(j, i) = static_cast<unsigned char>(std::lround(sample(bayerColourAt(camera.bayer, i, j)) * rawScale));
      } else {
        raw.at<uint16_t>(j, i) = static_cast<uint16_t>(std::lround(sample(bayerColourAt(camera.bayer, i, j)) * rawScale));
      }
    }
  if (!mosaic) return sensed;
  cv::Mat bgr;
  cv::demosaicing(raw, bgr, demosaicCode(camera.bayer, camera.demosaic));
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i)
      for (int c = 0; c < 3; ++c)
        sensed.at<cv::Vec3d>(j, i)[c] = (eightBitRaw ? bgr.at<cv::Vec3b>(j, i)[2 - c] : bgr.at<cv::Vec3w>(j, i)[2 - c]) / rawScale;
  return sensed;
}

// The ISP's output: the tone curve to 8-bit codes (BGR, as OpenCV holds them), then JPEG.
cv::Mat recordedCodes(const RecordingCamera& camera, const ImageRGBA& linear, const cv::Mat& sensed) {
  cv::Mat codes(linear.height, linear.width, CV_8UC3, cv::Scalar(0, 0, 0));
  for (int j = 0; j < linear.height; ++j)
    for (int i = 0; i < linear.width; ++i) {
      if (linear.at(i, j)[3] <= 0) continue;
      for (int c = 0; c < 3; ++c) codes.at<cv::Vec3b>(j, i)[2 - c] = eightBit(toneCurveValue(camera, sensed.at<cv::Vec3d>(j, i)[c]));
    }
  if (camera.jpegQuality > 0) {
    const size_t pixels = codes.total();
    std::vector<unsigned char> rgb(pixels * 3);
    for (size_t p = 0; p < pixels; ++p)
      for (int c = 0; c < 3; ++c) rgb[3 * p + c] = codes.data[3 * p + 2 - c];
    rgb = jpegCompressed(rgb, linear.width, linear.height, camera.jpegQuality);
    for (size_t p = 0; p < pixels; ++p)
      for (int c = 0; c < 3; ++c) codes.data[3 * p + 2 - c] = rgb[3 * p + c];
  }
  return codes;
}

}  // namespace

ImageRGBA recordFrame(const RecordingCamera& camera, const ImageRGBA& linear, uint64_t frameIndex) {
  // The same frame from any thread: one denormal more or less (a blur's tail weights below
  // 0.1 px) would reshuffle every later draw of the noise's stream. Flushed, as the frames of a
  // run without a thread count have always been recorded.
  const FlushDenormals mode;
  const uint64_t seed = noiseSeed(camera.seed, frameIndex);
  const cv::Mat codes = recordedCodes(camera, linear, sensedColour(camera, linear, sensorLight(camera, linear), seed));
  // Linear again: the 8-bit codes decoded as sRGB, alpha kept (beyond the rim: black).
  ImageRGBA recorded(linear.width, linear.height);
  for (int j = 0; j < linear.height; ++j)
    for (int i = 0; i < linear.width; ++i) {
      const float alpha = linear.at(i, j)[3];
      const cv::Vec3b& code = codes.at<cv::Vec3b>(j, i);
      float* out = recorded.at(i, j);
      for (int c = 0; c < 3; ++c) out[c] = alpha * srgbToLinear(code[2 - c] / 255.0f);
      out[3] = alpha;
    }
  return recorded;
}

}  // namespace omnicam
