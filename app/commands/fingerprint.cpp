#include "app/commands/fingerprint.h"

#include <sstream>
#include <vector>

#include "common/input_file.h"
#include "common/strings.h"
#include "formats/scene_file.h"
#include "tracer/film_file.h"

namespace arbor::app {

std::string render_fingerprint(const spec::SceneDesc& scene, std::optional<double> time,
                               std::optional<int> frame, const std::string& ocio,
                               std::string& settings) {
  std::ostringstream s;
  s.precision(17);
  s << formats::render_settings_text(scene.render) << "; transparent_sky "
    << (scene.output.transparent_sky ? "true" : "false") << "; ids "
    << (scene.output.wants_ids() ? "kept" : "none") << "; --time ";
  if (time)
    s << *time;
  else
    s << "none";
  if (frame) s << "; frame " << *frame << "; clock " << scene.clock;
  std::vector<std::string> files = spec::scene_inputs(scene);
  files.push_back(ocio);
  for (std::size_t i = 0; i < files.size(); ++i) {
    const std::string role = i == 0                  ? "the scene file"
                             : i + 1 == files.size() ? "the OCIO config"
                                                     : "input " + file_name(files[i]);
    s << "; " << role << " " << tracer::fingerprint_hex(input_digest(files[i], role));
  }
  settings = s.str();
  return tracer::fingerprint_hex(tracer::fnv1a("arbor render 2 " + settings));
}

}  // namespace arbor::app
