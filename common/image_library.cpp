// Loads libarbor_oiio.so on first use (see image_library.h).
#include "common/image_library.h"

#include <dlfcn.h>

#include <cstdlib>
#include <mutex>

#include "common/error.h"
#include "common/executable.h"
#include "common/input_file.h"

namespace arbor {

std::string DecodedImage::attribute(const std::string& name, const std::string& fallback) const {
  const auto it = attributes.find(name);
  return it == attributes.end() ? fallback : it->second;
}

int DecodedImage::int_attribute(const std::string& name, int fallback) const {
  const auto it = attributes.find(name);
  if (it == attributes.end()) return fallback;
  char* end = nullptr;
  const long v = std::strtol(it->second.c_str(), &end, 10);
  return end != it->second.c_str() && *end == '\0' ? static_cast<int>(v) : fallback;
}

namespace {

constexpr const char* kModule = "libarbor_oiio.so";

// The module's entry point: a pointer to its one ImageLibrary.
using EntryPoint = const ImageLibrary* (*)();

const ImageLibrary* load(std::string& why) {
  std::vector<std::string> places;
  const std::string exe = executable_path();
  const auto slash = exe.find_last_of('/');
  if (slash != std::string::npos)
    places.push_back(exe.substr(0, slash) + "/../lib/arbor/" + kModule);
#ifdef ARBOR_MODULE_DIR
  places.push_back(std::string(ARBOR_MODULE_DIR) + "/" + kModule);
#endif
  for (const std::string& place : places) {
    // RTLD_LOCAL: OpenImageIO's libraries stay out of the symbols arbor itself binds against.
    void* handle = dlopen(place.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
      const char* e = dlerror();
      why += "\n  " + place + ": " + (e ? e : "cannot be loaded");
      continue;
    }
    const auto entry = reinterpret_cast<EntryPoint>(dlsym(handle, "arbor_image_library"));
    if (entry) return entry();
    why += "\n  " + place + ": has no arbor_image_library";
  }
  return nullptr;
}

}  // namespace

const ImageLibrary& image_library(const std::string& needed_for) {
  static std::once_flag once;
  static const ImageLibrary* library = nullptr;
  static std::string why;
  std::call_once(once, [] { library = load(why); });
  if (!library) {
    throw RuntimeFailure(std::string("cannot load ") + kModule + " (OpenImageIO), needed to " +
                         needed_for + ":" + why);
  }
  return *library;
}

DecodedImage read_image_file(const std::string& path, const std::string& what, bool pixels) {
  check_input_file(path, what);
  DecodedImage image;
  const std::string why = image_library("read " + path).read(path, pixels, image);
  if (!why.empty()) throw InputError({path, 0, 0}, "cannot read the " + what + ": " + why);
  return image;
}

}  // namespace arbor
