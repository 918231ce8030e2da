// The one Embree device of a render, as an RAII handle whose errors become arbor exceptions.
// This folder is the only place that includes <embree3/rtcore.h>.
#pragma once

#include <memory>
#include <mutex>
#include <string>

struct RTCDeviceTy;
struct RTCSceneTy;

namespace arbor::tracer {

class EmbreeDevice {
 public:
  // config: Embree's device configuration string (e.g. "threads=1"); empty for defaults.
  explicit EmbreeDevice(const std::string& config = "");
  ~EmbreeDevice();
  EmbreeDevice(const EmbreeDevice&) = delete;
  EmbreeDevice& operator=(const EmbreeDevice&) = delete;

  RTCDeviceTy* get() const { return device_; }
  // Throws RuntimeFailure naming `doing` and Embree's message if Embree reported an error.
  void check(const char* doing) const;
  // Embree's version string, e.g. "3.13.5".
  static std::string version();

 private:
  static void on_error(void* device, int code, const char* message);
  RTCDeviceTy* device_ = nullptr;
  // Embree reports errors through a callback, inside its own code where throwing is not allowed:
  // the message is kept here for check(), which throws it on the caller's side.
  mutable std::mutex error_mutex_;
  mutable std::string last_error_;
};

// Owns an Embree scene from its creation, so a constructor that throws half-way releases it.
struct SceneRelease {
  void operator()(RTCSceneTy* scene) const;
};
using SceneHandle = std::unique_ptr<RTCSceneTy, SceneRelease>;

// A new, empty scene on the device (checked).
SceneHandle new_scene(const EmbreeDevice& device);

}  // namespace arbor::tracer
