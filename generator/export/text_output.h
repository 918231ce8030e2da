// Small helpers shared by the text exporters: shortest exact number formatting, buffered output.
#pragma once

#include <algorithm>
#include <charconv>
#include <string>

#include <glm/vec3.hpp>

#include "common/atomic_file.h"

namespace arbor::generator {

// Appends v in the shortest form that reads back as the same float.
inline void put_number(std::string& out, float v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}

// Appends v rounded to `decimals` places, without trailing zeros ("0.25", "3", never "-0"): the
// mesh writers' compact form. Falls back to the shortest exact form when v is too large for it.
inline void put_fixed(std::string& out, float v, int decimals) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, decimals);
  if (r.ec != std::errc()) {
    put_number(out, v);
    return;
  }
  char* end = r.ptr;
  if (std::find(buf, end, '.') != end) {
    while (end[-1] == '0') --end;
    if (end[-1] == '.') --end;
  }
  if (end - buf == 2 && buf[0] == '-' && buf[1] == '0') {
    out += '0';
    return;
  }
  out.append(buf, end);
}

// Which axis is up in an exported file. arbor's world is z-up (right-handed); many tools (Blender's
// OBJ importer, Maya, game engines) assume y-up, which is arbor's world turned -90° about x.
enum class UpAxis { Z, Y };
inline glm::vec3 oriented(const glm::vec3& p, UpAxis up) {
  return up == UpAxis::Y ? glm::vec3(p.x, p.z, -p.y) : p;
}

// Hands the buffer to the file once it holds a megabyte, so huge trees stream out.
inline void flush_if_large(std::string& buffer, AtomicFile& file) {
  if (buffer.size() > (1u << 20)) {
    file.write(buffer);
    buffer.clear();
  }
}

}  // namespace arbor::generator
