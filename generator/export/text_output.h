// Small helpers shared by the text exporters: shortest exact number formatting, buffered output.
#pragma once

#include <charconv>
#include <string>

#include "common/atomic_file.h"

namespace arbor::gen {

// Appends v in the shortest form that reads back as the same float.
inline void put_number(std::string& out, float v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}

// Hands the buffer to the file once it holds a megabyte, so huge trees stream out.
inline void flush_if_large(std::string& buffer, AtomicFile& file) {
  if (buffer.size() > (1u << 20)) {
    file.write(buffer);
    buffer.clear();
  }
}

}  // namespace arbor::gen
