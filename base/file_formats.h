#pragma once
// The "format" each of omnicam's JSON files states: what its reader checks first. A reader given
// another of them says which it is, rather than only that the format is wrong.
#include <string>
#include <string_view>

namespace omnicam {

inline constexpr const char* kSceneFormat = "omnicam-scene/1";               // docs/scene-format.md
inline constexpr const char* kDatasetSpecFormat = "omnicam-dataset/1";       // docs/dataset-format.md
inline constexpr const char* kManifestFormat = "omnicam-dataset-manifest/1";  // a dataset folder's manifest.json

// "; this is a scene file", "; this is a dataset spec", "; this is a dataset folder's manifest" for a
// file of one of these formats given where one of `expected` goes; "" for any other format.
inline std::string formatMismatchHint(std::string_view found, std::string_view expected) {
  if (found == expected) return "";
  if (found == kSceneFormat) return "; this is a scene file";
  if (found == kDatasetSpecFormat) return "; this is a dataset spec";
  if (found == kManifestFormat) return "; this is a dataset folder's manifest";
  return "";
}

}  // namespace omnicam
