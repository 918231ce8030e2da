// The film state file: a text header, then the film's arrays in native binary form.
#include "tracer/film_file.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <sys/stat.h>
#include <fstream>
#include <map>
#include <sstream>
#include <type_traits>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/input_file.h"

namespace arbor::tracer {

namespace {

const char* const kMagic = "arbor film state 4";
// The largest image a state may describe: the scene's and the command line's bound on width and
// height.
constexpr int kMaxSide = 16384;
static_assert(std::is_trivially_copyable<PixelState>::value, "PixelState is written as bytes");

// Names one to a line's value, separated by tabs (scene names hold no tabs or newlines).
std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : "\t") + n;
  return out;
}
std::vector<std::string> split_tabs(const std::string& text) {
  std::vector<std::string> out;
  if (text.empty()) return out;
  std::size_t start = 0;
  for (std::size_t tab; (tab = text.find('\t', start)) != std::string::npos; start = tab + 1) {
    out.push_back(text.substr(start, tab - start));
  }
  out.push_back(text.substr(start));
  return out;
}

// A 64-bit checksum of bytes, eight at a time (a multiply-xorshift chain; catches any flipped
// byte with probability 1 - 2^-64, and runs at several GB/s).
struct Checksum {
  std::uint64_t h = 0x9e3779b97f4a7c15ull;
  void add(const void* data, std::size_t size) {
    const auto* p = static_cast<const unsigned char*>(data);
    std::size_t i = 0;
    for (; i + 8 <= size; i += 8) {
      std::uint64_t w;
      std::memcpy(&w, p + i, 8);
      mix(w);
    }
    std::uint64_t tail = 0;
    std::memcpy(&tail, p + i, size - i);
    mix(tail ^ (static_cast<std::uint64_t>(size - i) << 56));
  }
  void mix(std::uint64_t w) {
    h = (h ^ w) * 0xff51afd7ed558ccdull;
    h ^= h >> 32;
  }
};

}  // namespace

std::string number_text(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string state_path(const std::string& exr) { return exr + ".state"; }

std::string settings_difference(const std::string& a, const std::string& b, const std::string& in_a,
                                const std::string& in_b) {
  // "name value" items; the value is the last word (names may have spaces: "input aspen.toml").
  auto items = [](const std::string& text) {
    std::vector<std::pair<std::string, std::string>> out;
    std::size_t start = 0;
    while (start < text.size()) {
      std::size_t end = text.find("; ", start);
      if (end == std::string::npos) end = text.size();
      const std::string item = text.substr(start, end - start);
      const std::size_t space = item.rfind(' ');
      out.emplace_back(space == std::string::npos ? item : item.substr(0, space),
                       space == std::string::npos ? "" : item.substr(space + 1));
      start = end + 2;
    }
    return out;
  };
  const auto ia = items(a), ib = items(b);
  std::string out;
  auto add = [&](const std::string& s) { out += (out.empty() ? "" : "; ") + s; };
  for (std::size_t i = 0; i < std::max(ia.size(), ib.size()); ++i) {
    if (i < ia.size() && i < ib.size() && ia[i] == ib[i]) continue;
    if (i < ia.size() && i < ib.size() && ia[i].first == ib[i].first) {
      const bool digest = ia[i].first.rfind("input", 0) == 0 || ia[i].first.rfind("the ", 0) == 0;
      add(digest
              ? ia[i].first + " has other contents"
              : ia[i].first + " " + ia[i].second + " " + in_a + ", " + ib[i].second + " " + in_b);
    } else if (i < ia.size() && i < ib.size()) {
      add(ia[i].first + " " + in_a + ", " + ib[i].first + " " + in_b);
    } else {
      add(i < ia.size() ? ia[i].first + " only " + in_a : ib[i].first + " only " + in_b);
    }
  }
  return out.empty() ? "the same settings" : out;
}

std::uint64_t fnv1a(const std::string& text, std::uint64_t hash) {
  return fnv1a_bytes(text.data(), text.size(), hash);
}

std::string fingerprint_hex(std::uint64_t hash) {
  char buf[24];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(hash));
  return buf;
}

void write_film_state(const std::string& path, const FilmHeader& h, const Film& film) {
  const Window& w = film.window();
  std::ostringstream head;
  head << kMagic << "\n"
       << "fingerprint " << h.fingerprint << "\n"
       << "settings " << h.settings << "\n"
       << "scene " << h.scene << "\n"
       << "size " << h.full_width << " " << h.full_height << "\n"
       << "window " << w.x0 << " " << w.y0 << " " << w.x1 << " " << w.y1 << "\n"
       << "plan " << h.plan.spp << " " << h.plan.pass_spp << " " << (h.plan.independent ? 1 : 0)
       << "\n"
       << "passes " << film.pass_begin() << " " << film.next_pass() << " " << h.pass_end << "\n"
       << "adaptive " << number_text(h.noise_threshold) << " " << h.min_spp << "\n"
       << "extras " << film.extras() << " " << (film.keeps_records() ? 1 : 0) << " "
       << (film.keeps_ids() ? 1 : 0) << "\n"
       << "seconds " << number_text(h.seconds) << "\n"
       << "counts " << h.nonfinite << " " << h.rays << "\n"
       << "integrator " << name_of(h.integrator) << "\n"
       << "seed " << h.seed << "\n"
       << "colorspace " << h.output.colorspace << "\n"
       << "display " << h.output.display << "\n"
       << "view " << h.output.view << "\n"
       << "pixel_type " << name_of(h.output.pixel_type) << "\n"
       << "transparent_sky " << (h.output.transparent_sky ? 1 : 0) << "\n"
       << "aovs " << h.output.aovs.text() << "\n"
       << "treemaker_weights " << h.treemaker_weights << "\n"
       << "exposure " << h.exposure << "\n"
       << "regularize " << (h.regularize ? 1 : 0) << "\n"
       << "lod " << h.lod_quality << "\n"
       << "object_names " << joined(h.object_names) << "\n"
       << "material_names " << joined(h.material_names) << "\n"
       << "end\n";
  AtomicFile file(path, true);
  Checksum sum;
  auto put = [&](const void* data, std::size_t bytes) {
    sum.add(data, bytes);
    file.write(data, bytes);
  };
  const std::string header = head.str();
  put(header.data(), header.size());
  put(film.states().data(), film.states().size() * sizeof(PixelState));
  put(film.sums().data(), film.sums().size() * sizeof(double));
  put(film.records().data(), film.records().size() * sizeof(double));
  file.write("checksum " + fingerprint_hex(sum.h) + "\n");
  file.commit();
}

FilmFile read_film_state(const std::string& path) {
  check_input_file(path, "film state");
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw InputError({path, 0, 0},
                     "cannot read the film state (it is written beside an EXR "
                     "whose render can be resumed or merged)");
  auto bad = [&](const std::string& why) {
    return InputError({path, 0, 0}, "is not a film state arbor can read: " + why);
  };
  std::string line;
  if (!std::getline(in, line) || line != kMagic)
    throw bad("it does not start with \"" + std::string(kMagic) + "\"");
  std::string header = line + "\n";
  std::map<std::string, std::string> keys;
  while (header.size() < (1u << 24) && std::getline(in, line) &&
         (header += line + "\n", line != "end")) {
    const auto space = line.find(' ');
    if (space == std::string::npos) throw bad("a header line without a value: " + line);
    keys[line.substr(0, space)] = line.substr(space + 1);
  }
  if (line != "end") throw bad("its header does not end");
  auto field = [&](const char* name) {
    auto it = keys.find(name);
    if (it == keys.end()) throw bad(std::string("its header has no ") + name);
    return std::istringstream(it->second);
  };
  FilmFile f;
  FilmHeader& h = f.header;
  h.fingerprint = keys["fingerprint"];
  h.settings = keys["settings"];
  h.scene = keys["scene"];
  const std::optional<spec::Integrator> integrator = spec::integrator_named(keys["integrator"]);
  if (!integrator)
    throw bad("its integrator \"" + keys["integrator"] + "\" is not path or treemaker");
  h.integrator = *integrator;
  h.output.colorspace = keys["colorspace"];
  h.output.display = keys["display"];
  h.output.view = keys["view"];
  const std::optional<imaging::PixelType> pixel_type =
      imaging::pixel_type_named(keys["pixel_type"]);
  if (!pixel_type) throw bad("its pixel type \"" + keys["pixel_type"] + "\" is not half or float");
  h.output.pixel_type = *pixel_type;
  h.output.transparent_sky = keys["transparent_sky"] == "1";
  h.treemaker_weights = keys["treemaker_weights"];
  h.exposure = keys["exposure"];
  h.regularize = keys["regularize"] == "1";
  h.lod_quality = keys["lod"].empty() ? 0.0 : std::strtod(keys["lod"].c_str(), nullptr);
  if (!std::isfinite(h.lod_quality) || h.lod_quality < 0.0) throw bad("its lod is not a quality");
  h.object_names = split_tabs(keys["object_names"]);
  h.material_names = split_tabs(keys["material_names"]);
  {
    std::istringstream aovs(keys["aovs"]);
    for (std::string a; aovs >> a;) {
      const std::optional<imaging::Aov> aov = imaging::aov_named(a);
      if (!aov) throw bad("its AOV \"" + a + "\" is not one arbor writes");
      h.output.aovs.add(*aov);
    }
  }
  Window w;
  int begin = 0, next = 0, records = 0, independent = 0, ids = 0;
  std::size_t extras = 0;
  bool ok = static_cast<bool>(field("size") >> h.full_width >> h.full_height);
  ok = ok && static_cast<bool>(field("window") >> w.x0 >> w.y0 >> w.x1 >> w.y1);
  ok = ok && static_cast<bool>(field("plan") >> h.plan.spp >> h.plan.pass_spp >> independent);
  h.plan.independent = independent != 0;
  ok = ok && static_cast<bool>(field("passes") >> begin >> next >> h.pass_end);
  ok = ok && static_cast<bool>(field("adaptive") >> h.noise_threshold >> h.min_spp);
  ok = ok && static_cast<bool>(field("extras") >> extras >> records >> ids);
  ok = ok && static_cast<bool>(field("seconds") >> h.seconds);
  ok = ok && static_cast<bool>(field("counts") >> h.nonfinite >> h.rays);
  ok = ok && static_cast<bool>(field("seed") >> h.seed);
  if (!ok || h.full_width <= 0 || h.full_height <= 0 || w.x0 < 0 || w.y0 < 0 ||
      w.x1 > h.full_width || w.y1 > h.full_height || w.width() <= 0 || w.height() <= 0 ||
      h.plan.spp <= 0 || h.plan.pass_spp <= 0 || begin < 0 || next < begin || h.pass_end < next ||
      h.pass_end > h.plan.passes() || extras > 64 || h.plan.spp > (1 << 20) || h.min_spp < 0 ||
      !std::isfinite(h.noise_threshold) || !std::isfinite(h.seconds)) {
    throw bad("its header is malformed");
  }
  if (h.full_width > kMaxSide || h.full_height > kMaxSide) {
    throw bad("its image size " + std::to_string(h.full_width) + "x" +
              std::to_string(h.full_height) + " is over the largest arbor renders (" +
              std::to_string(kMaxSide) + " a side)");
  }
  // Every size the header implies is checked against the file's own size before anything is
  // allocated: a forged header cannot ask for more memory than the file holds.
  const std::uint64_t pixels = static_cast<std::uint64_t>(w.pixels());
  const std::uint64_t stride = kAovSums + extras + (ids != 0 ? 2 * kIdSlots : 0);
  const std::uint64_t record_doubles =
      records != 0 ? static_cast<std::uint64_t>(next - begin) * (7 + stride) * pixels : 0;
  const std::uint64_t body = pixels * sizeof(PixelState) + pixels * stride * sizeof(double) +
                             record_doubles * sizeof(double);
  const std::uint64_t trailer = std::string("checksum 0123456789abcdef\n").size();
  struct stat st;
  if (::stat(path.c_str(), &st) != 0 ||
      static_cast<std::uint64_t>(st.st_size) != header.size() + body + trailer) {
    throw bad(
        "its size (" + std::to_string(st.st_size) + " bytes) is not what its header describes (" +
        std::to_string(header.size() + body + trailer) + " bytes): it is truncated or damaged");
  }
  f.film = std::make_unique<Film>(w, extras, begin, records != 0, ids != 0);
  Film& film = *f.film;
  film.set_next_pass(next);
  if (film.keeps_records()) film.records().resize(static_cast<std::size_t>(record_doubles));
  Checksum sum;
  sum.add(header.data(), header.size());
  auto read = [&](void* data, std::size_t bytes) {
    if (!in.read(static_cast<char*>(data), static_cast<std::streamsize>(bytes)))
      throw bad("it is truncated");
    sum.add(data, bytes);
  };
  read(film.states().data(), film.states().size() * sizeof(PixelState));
  read(film.sums().data(), film.sums().size() * sizeof(double));
  read(film.records().data(), film.records().size() * sizeof(double));
  if (!std::getline(in, line) || line != "checksum " + fingerprint_hex(sum.h) ||
      in.peek() != std::char_traits<char>::eof()) {
    throw bad("its checksum does not match its contents: the file is damaged");
  }
  // A state arbor wrote holds only finite numbers (non-finite samples are dropped and counted).
  auto finite = [](const double* v, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) {
      if (!std::isfinite(v[i])) return false;
    }
    return true;
  };
  bool ok_numbers = finite(film.sums().data(), film.sums().size()) &&
                    finite(film.records().data(), film.records().size());
  for (const PixelState& s : film.states()) {
    const double v[9] = {s.mean.x,   s.mean.y,     s.mean.z,     s.spread.x,  s.spread.y,
                         s.spread.z, s.first_m2.x, s.first_m2.y, s.first_m2.z};
    ok_numbers = ok_numbers && finite(v, 9) &&
                 s.passes <= static_cast<std::uint32_t>(next - begin) && s.done <= 1;
  }
  if (!ok_numbers)
    throw bad("it holds a sum that is not a finite number, or a pixel with impossible counts");
  return f;
}

}  // namespace arbor::tracer
