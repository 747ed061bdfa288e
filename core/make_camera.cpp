#include "make_camera.h"

#include "central_camera.h"
#include "physical_camera.h"

namespace omnicam {

std::shared_ptr<const Camera> makeCamera(const RigSpec& rig, bool traced) {
  if (rig.ideal() && !traced) return std::make_shared<CentralCamera>(rig);
  return std::make_shared<PhysicalCamera>(rig);
}

}  // namespace omnicam
