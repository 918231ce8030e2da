// Internal to tracer/: writes an OIIO image buffer atomically (a temporary beside the target,
// renamed over it when complete; the format follows the extension).
#pragma once

#include <string>

#include <OpenImageIO/imagebuf.h>

namespace arbor::trace {

void write_imagebuf_atomic(const OIIO::ImageBuf& buf, const std::string& path, OIIO::TypeDesc type);

}  // namespace arbor::trace
