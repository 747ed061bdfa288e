#include "demo_dataset.h"

#include <cstdio>
#include <filesystem>
#include <sstream>

#include "aov_preview.h"
#include "atomic_file.h"
#include "dataset_runner.h"
#include "json_text.h"
#include "safe_files.h"

namespace omnicam::cli {

// A small dataset as a researcher would make one: two omnicams on the robot along the thesis'
// loop, every output; the report shows its depth, instances, classes and landmark annotations.
std::string demoDataset(const std::string& out, const std::string& scenePath) {
  namespace fs = std::filesystem;
  checkFoldersInside(out, "dataset");  // remade with --overwrite: never through a link planted there
  const std::string specPath = out + "/dataset_spec.json";
  const nlohmann::json spec = {
      {"format", "omnicam-dataset/1"},
      {"description", "omnicam demo: two cameras along the thesis loop"},
      {"scene", fs::absolute(scenePath).string()},
      {"spp", 4},
      {"shading", "lit"},
      {"size", 256},
      {"poses", {{"path", "thesis-loop"}, {"frames", 6}}},
      {"cameras", {{{"name", "front"}, {"mount", {{"x", 0.1}, {"y", 0.0}, {"yaw_deg", 0.0}}}},
                   {{"name", "rear"}, {"mount", {{"x", -0.1}, {"y", 0.0}, {"yaw_deg", 180.0}}},
                    {"rig", {{"height", 0.3}}}}}},
      {"outputs", {{"coco", true}}}};
  writeTextAtomically(specPath, spec.dump(2) + "\n");
  DatasetRunOptions options;
  options.dir = out + "/dataset";
  options.overwrite = true;  // the demo's own folder, remade each run
  std::printf("demo: dataset of 6 frames x 2 cameras (rgb, depth, instance, semantic, normal, landmarks, coco)\n");
  const DatasetRunResult result = runDataset(loadDatasetSpec(specPath), options);
  const DatasetVerifyResult verified = verifyDataset(options.dir);
  std::ostringstream html;
  html << "<h2>A reference dataset (<code>omnicam dataset</code>)</h2><p>" << result.frames
       << " frames × 2 cameras (front: F' 0.40 m high, 10 cm ahead of the robot's centre; rear: 0.30 m high, 10 cm behind, "
          "turned 180°) along the thesis loop, written to <code>dataset/</code> with <code>manifest.json</code> (every "
          "file's SHA-256: <code>omnicam dataset --verify</code> "
       << (verified.ok() ? "passes" : "FAILS") << " on " << verified.files
       << " files), OpenCV / Kalibr / camodocal intrinsics and <code>poses.tum</code> per camera. Spec: "
          "<code>dataset_spec.json</code>. Depth: metres along each pixel centre's ray from F' (yellow near, blue 6 m); "
          "instances and classes: one colour per id; landmarks: projected ground truth, green = visible, red = "
          "occluded (never labelled by hand); COCO: each camera's <code>coco.json</code> (the goals and beacons as "
          "masks in COCO's RLE and boxes, the landmarks as keypoints), drawn here from the file alone.</p>\n";
  const nlohmann::json frontCoco = readJsonFile(options.dir + "/front/coco.json");
  for (const std::string camera : {"front", "rear"}) {
    for (int frame : {0, 3}) {
      char stem[64];
      std::snprintf(stem, sizeof stem, "%s/%%s/%06d", camera.c_str(), frame);
      auto file = [&](const char* kind, const char* ext) {
        char path[160];
        std::snprintf(path, sizeof path, stem, kind);
        return options.dir + "/" + path + ext;
      };
      const std::string prefix = "dataset_" + camera + "_" + std::to_string(frame);
      int w = 0, h = 0;
      writeImageAtomic(out + "/" + prefix + "_depth.png", depthPreview(readDataExr(file("depth", ".exr")), 6.0));
      const std::vector<uint16_t> instance = readUint16Png(file("instance", ".png"), w, h);
      writeImageAtomic(out + "/" + prefix + "_instance.png", idPreview(instance, w, h));
      const std::vector<uint16_t> semantic = readUint16Png(file("semantic", ".png"), w, h);
      writeImageAtomic(out + "/" + prefix + "_semantic.png", idPreview(semantic, w, h));
      writeImageAtomic(out + "/" + prefix + "_landmarks.png",
                       drawLandmarkAnnotations(readImage(file("rgb", ".png")), readJsonFile(file("landmarks", ".json"))));
      const nlohmann::json coco = camera == "front" ? frontCoco : readJsonFile(options.dir + "/rear/coco.json");
      writeImageAtomic(out + "/" + prefix + "_coco.png", drawCocoAnnotations(readImage(file("rgb", ".png")), coco, frame + 1));
      html << "<div><b>" << camera << ", frame " << frame << "</b><br>";
      for (const char* kind : {"landmarks", "coco", "depth", "instance", "semantic"})
        html << "<figure style=\"max-width:260px\"><img src=\"" << prefix << "_" << kind << ".png\" width=\"256\"><figcaption>"
             << kind << "</figcaption></figure>";
      html << "</div>\n";
    }
  }
  return html.str();
}

}  // namespace omnicam::cli
