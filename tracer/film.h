// The film: a pixel's samples accumulated pass by pass into its mean, an honest estimate of the
// variance of that mean (across independent passes), the AOVs, and the tent filter that places
// samples. docs/rendering.md, "Passes", states the estimator.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "imaging/image.h"
#include "scene/render_budget.h"

namespace arbor::tracer {

// Tent filter of radius 1 pixel: maps u in [0,1) to an offset in (-1, 1) distributed ∝ 1 - |x|.
float sample_tent(float u);

// An image of width × height with its AOV arrays allocated (zero) and `extras` integrator AOV
// floats a pixel.
imaging::Image make_image(int width, int height, std::size_t extras);

// The passes of a render: `spp` samples a pixel in passes of `pass_spp` (the last one shorter
// when pass_spp does not divide spp). By default the passes take consecutive points of one
// scrambled sequence per pixel (pass p starts at sample p × pass_spp), so `spp` samples are as
// well stratified as in one pass; `independent` gives each pass its own scramble, starting at
// sample 0, so pass means are independent replicates (docs/rendering.md, "Passes").
struct PassPlan {
  int spp = 1, pass_spp = 1;
  bool independent = false;
  int passes() const { return (spp + pass_spp - 1) / pass_spp; }
  int size(int pass) const {
    return pass < passes() - 1 ? pass_spp : spp - (passes() - 1) * pass_spp;
  }
  // The scramble pass `pass` draws from (0 is a single-pass render's) and its first sample index.
  std::uint32_t scramble(int pass) const {
    return independent ? static_cast<std::uint32_t>(pass) : 0u;
  }
  std::uint32_t first_sample(int pass) const {
    return independent ? 0u
                       : static_cast<std::uint32_t>(pass) * static_cast<std::uint32_t>(pass_spp);
  }
  // Samples a pixel of passes [begin, end).
  int samples(int begin, int end) const;
};

// A window of the image in pixels, end exclusive.
struct Window {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  int width() const { return x1 - x0; }
  int height() const { return y1 - y0; }
  std::size_t pixels() const {
    return static_cast<std::size_t>(width()) * static_cast<std::size_t>(height());
  }
  bool operator==(const Window& o) const {
    return x0 == o.x0 && y0 == o.y0 && x1 == o.x1 && y1 == o.y1;
  }
  bool operator!=(const Window& o) const { return !(*this == o); }
};

// The sums of the AOVs a pixel keeps besides its extras: albedo (3), normal (3), depth (1),
// alpha (1 a sample; with a transparent sky, 1 only when its camera ray hit something).
constexpr std::size_t kAovSums = 8;

// Compositing ids (object_id, material_id, Cryptomatte): a pixel that keeps them has kIdSlots
// slots for objects and kIdSlots for materials after its extras, each slot one id and the samples
// that saw it, packed exactly into a double as id × 2^21 + samples (ids < 2^32, samples ≤ 2^20).
// Slots fill in sample order; an id arriving when all are taken is not counted (a pixel
// rarely sees more than 8 objects; docs/outputs.md). 0 is an empty slot.
constexpr std::size_t kIdSlots = 8;
constexpr double kIdScale = 2097152.0;  // 2^21
inline double id_slot(std::uint32_t id, double samples) { return double(id) * kIdScale + samples; }
inline std::uint32_t slot_id(double slot) { return static_cast<std::uint32_t>(slot / kIdScale); }
inline double slot_samples(double slot) { return slot - double(slot_id(slot)) * kIdScale; }
// Counts `samples` of `id` into a pixel's slots (a no-op for id 0 or when all are taken).
void add_to_slots(double* slots, std::uint32_t id, double samples);

// One pixel's samples of one pass, in sample order (the order makes the sums bit-identical at
// any thread count): Welford's running mean and squared deviations of the beauty, sums of the
// AOVs.
class PixelAccumulator {
 public:
  // `ids`: keep the compositing id slots (kIdSlots for objects, kIdSlots for materials).
  PixelAccumulator(std::size_t extras, bool ids)
      : extras_(extras), sums_(kAovSums + extras + (ids ? 2 * kIdSlots : 0)) {}

  void reset();
  // A finite sample: beauty and albedo already in the output colour space; `alpha` 1 when the
  // camera ray hit something; the first hit's ids (0: none), kept only with `ids`.
  void add(const float rgb[3], const float albedo[3], const glm::vec3& normal, float depth,
           float alpha, const float* extra, std::uint32_t object_id, std::uint32_t material_id);

  int count() const { return count_; }
  const glm::dvec3& mean() const { return mean_; }
  const glm::dvec3& m2() const { return m2_; }
  const std::vector<double>& sums() const { return sums_; }

 private:
  std::size_t extras_;
  int count_ = 0;
  glm::dvec3 mean_{0.0}, m2_{0.0};
  std::vector<double> sums_;
};

// What one pixel has gathered over its passes.
struct PixelState {
  std::uint32_t passes = 0;  // passes that gave at least one finite sample
  std::uint32_t count = 0;   // finite samples over all passes
  std::uint32_t done = 0;    // 1: adaptive sampling stopped it
  glm::dvec3 mean{0.0};      // mean of all samples (passes weighted by their sample counts)
  glm::dvec3 spread{0.0};    // Σ n_p (m_p − mean)², by West's weighted update
  glm::dvec3 first_m2{0.0};  // Σ (x − m)² within its first pass (the estimate when passes = 1)
};

// The settings adaptive sampling judges pixels by (docs/rendering.md, "Adaptive sampling").
struct AdaptiveSettings {
  double noise_threshold = 0.0;  // 0: off
  int min_spp = 0;
};

// The film of a window of the image over a range of passes: every pixel's PixelState and AOV
// sums and, for a range that does not start at pass 0, each pass's own results (so that a merge
// can fold them in pass order after the passes before it).
class Film {
 public:
  // What a film keeps a pixel (its state, sums and pass records), for the memory estimate.
  static scene::FilmCosts costs();

  // `ids`: keep the compositing id slots.
  Film(Window window, std::size_t extras, int pass_begin, bool keep_records, bool ids = false);

  const Window& window() const { return window_; }
  std::size_t extras() const { return extras_; }
  int pass_begin() const { return pass_begin_; }
  int next_pass() const { return next_pass_; }  // the first pass not yet rendered
  bool keeps_records() const { return keep_records_; }
  bool keeps_ids() const { return ids_; }
  // Doubles per pixel in sums(): kAovSums, the extras, then 2 × kIdSlots when keeps_ids().
  std::size_t sum_stride() const { return kAovSums + extras_ + (ids_ ? 2 * kIdSlots : 0); }

  // Pixel p (row-major within the window).
  const PixelState& state(std::size_t p) const { return states_[p]; }
  bool done(std::size_t p) const { return states_[p].done != 0; }
  // Starts pass next_pass() (allocates its records); not thread-safe.
  void begin_pass();
  // Folds pass next_pass()'s result for pixel p in (between begin_pass and finish_pass, for
  // every pixel not done; pixels in parallel).
  void add_pass(std::size_t p, const PixelAccumulator& pass);
  // Ends the pass: applies adaptive sampling's test to every pixel.
  void finish_pass(const AdaptiveSettings& adaptive);

  // The pixel means and variance estimates as an image of the window.
  imaging::Image image(std::size_t extras_wanted) const;

  // The relative standard error adaptive sampling compares with its threshold.
  double relative_error(std::size_t p) const;

  // Raw access for the state file and merges.
  std::vector<PixelState>& states() { return states_; }
  std::vector<double>& sums() { return sums_; }
  std::vector<double>& records() { return records_; }
  const std::vector<PixelState>& states() const { return states_; }
  const std::vector<double>& sums() const { return sums_; }
  const std::vector<double>& records() const { return records_; }
  void set_next_pass(int pass) { next_pass_ = pass; }
  // Doubles per pixel and pass in records(): count, mean (3), m2 (3), the sums.
  static constexpr std::size_t kRecordExtra = 7;  // a pass record: its sums and these values
  std::size_t record_size() const { return kRecordExtra + sum_stride(); }
  // Folds a pass record (as stored in records()) into pixel p: exactly what add_pass did.
  void fold_record(std::size_t p, const double* record);

 private:
  void fold(std::size_t p, double count, const glm::dvec3& mean, const glm::dvec3& m2,
            const double* sums);

  Window window_;
  std::size_t extras_;
  int pass_begin_, next_pass_;
  bool keep_records_, ids_;
  std::vector<PixelState> states_;
  std::vector<double> sums_;     // sum_stride() a pixel
  std::vector<double> records_;  // record_size() a pixel a pass, passes in order
};

}  // namespace arbor::tracer
