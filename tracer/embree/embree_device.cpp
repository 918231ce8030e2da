// Embree device lifecycle and error callback.
#include "tracer/embree/embree_device.h"

#include <embree3/rtcore.h>

#include "common/error.h"

namespace arbor::tracer {

EmbreeDevice::EmbreeDevice(const std::string& config) {
  device_ = rtcNewDevice(config.empty() ? nullptr : config.c_str());
  if (!device_) {
    const RTCError code = rtcGetDeviceError(nullptr);
    throw RuntimeFailure("cannot create the Embree device (error " +
                         std::to_string(static_cast<int>(code)) + ")");
  }
  rtcSetDeviceErrorFunction(
      device_,
      [](void* self, RTCError code, const char* message) {
        EmbreeDevice::on_error(self, static_cast<int>(code), message);
      },
      this);
}

void EmbreeDevice::on_error(void* device, int code, const char* message) {
  if (code == RTC_ERROR_NONE) return;
  auto* self = static_cast<EmbreeDevice*>(device);
  const std::lock_guard<std::mutex> lock(self->error_mutex_);
  self->last_error_ = message ? message : "unknown Embree error";
}

void EmbreeDevice::check(const char* doing) const {
  const RTCError code = rtcGetDeviceError(device_);
  if (code == RTC_ERROR_NONE) return;
  std::string message;
  {
    const std::lock_guard<std::mutex> lock(error_mutex_);
    message = last_error_.empty() ? "error " + std::to_string(int(code)) : last_error_;
    last_error_.clear();
  }
  throw RuntimeFailure(std::string("Embree failed while ") + doing + ": " + message);
}

EmbreeDevice::~EmbreeDevice() {
  if (device_) rtcReleaseDevice(device_);
}

void SceneRelease::operator()(RTCSceneTy* scene) const {
  if (scene) rtcReleaseScene(scene);
}

SceneHandle new_scene(const EmbreeDevice& device) {
  SceneHandle scene(rtcNewScene(device.get()));
  device.check("creating a scene");
  return scene;
}

std::string EmbreeDevice::version() {
  RTCDevice device = rtcNewDevice(nullptr);
  if (!device) return "unknown";
  const auto v = rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_VERSION);
  rtcReleaseDevice(device);
  return std::to_string(v / 10000) + "." + std::to_string((v / 100) % 100) + "." +
         std::to_string(v % 100);
}

}  // namespace arbor::tracer
