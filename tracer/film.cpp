// Pixel accumulation over passes and the reconstruction filter.
#include "tracer/film.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "imaging/treemaker_channels.h"

namespace arbor::tracer {

namespace {
// Below this magnitude a channel's error counts as absolute (docs/rendering.md): near-black
// pixels would otherwise never meet a relative threshold.
constexpr double kRelativeErrorFloor = 0.01;
}  // namespace

float sample_tent(float u) {
  return u < 0.5f ? std::sqrt(2.0f * u) - 1.0f : 1.0f - std::sqrt(2.0f - 2.0f * u);
}

imaging::Image make_image(int width, int height, std::size_t extras) {
  imaging::Image img;
  img.width = width;
  img.height = height;
  img.full_width = width;
  img.full_height = height;
  const std::size_t n = static_cast<std::size_t>(width) * height;
  img.beauty.assign(n, glm::vec3(0.0f));
  img.variance.assign(n, glm::vec3(0.0f));
  img.albedo.assign(n, glm::vec3(0.0f));
  img.normal.assign(n, glm::vec3(0.0f));
  img.depth.assign(n, 0.0f);
  img.samples.assign(n, 0.0f);
  img.alpha.assign(n, 0.0f);
  img.extra.assign(n * extras, 0.0f);
  return img;
}

int PassPlan::samples(int begin, int end) const {
  int n = 0;
  for (int p = begin; p < end; ++p) n += size(p);
  return n;
}

void add_to_slots(double* slots, std::uint32_t id, double samples) {
  if (id == 0) return;
  for (std::size_t i = 0; i < kIdSlots; ++i) {
    if (slots[i] == 0.0) {
      slots[i] = id_slot(id, samples);
      return;
    }
    if (slot_id(slots[i]) == id) {
      slots[i] += samples;
      return;
    }
  }
}

void PixelAccumulator::reset() {
  count_ = 0;
  mean_ = m2_ = glm::dvec3(0.0);
  std::fill(sums_.begin(), sums_.end(), 0.0);
}

void PixelAccumulator::add(const float rgb[3], const float alb[3], const glm::vec3& normal,
                           float depth, float alpha, const float* extra, std::uint32_t object_id,
                           std::uint32_t material_id) {
  // Welford's running mean and squared deviations.
  ++count_;
  const glm::dvec3 v(rgb[0], rgb[1], rgb[2]);
  const glm::dvec3 delta = v - mean_;
  mean_ += delta / static_cast<double>(count_);
  m2_ += delta * (v - mean_);
  double* s = sums_.data();
  for (int c = 0; c < 3; ++c) s[c] += alb[c];
  for (int c = 0; c < 3; ++c) s[3 + c] += normal[c];
  s[6] += depth;
  s[7] += alpha;
  for (std::size_t e = 0; e < extras_; ++e) s[kAovSums + e] += extra[e];
  if (sums_.size() > kAovSums + extras_) {
    add_to_slots(s + kAovSums + extras_, object_id, 1.0);
    add_to_slots(s + kAovSums + extras_ + kIdSlots, material_id, 1.0);
  }
}

scene::FilmCosts Film::costs() {
  scene::FilmCosts c;
  c.state = sizeof(PixelState);
  c.sum = sizeof(double);
  c.sums = kAovSums;
  c.id_sums = 2 * kIdSlots;
  c.record_extra = kRecordExtra;
  c.treemaker_extras = imaging::treemaker_channel_names().size();
  return c;
}

Film::Film(Window window, std::size_t extras, int pass_begin, bool keep_records, bool ids)
    : window_(window),
      extras_(extras),
      pass_begin_(pass_begin),
      next_pass_(pass_begin),
      keep_records_(keep_records),
      ids_(ids),
      states_(window.pixels()),
      sums_(window.pixels() * sum_stride(), 0.0) {}

void Film::fold(std::size_t p, double n, const glm::dvec3& m, const glm::dvec3& m2,
                const double* s) {
  if (n <= 0) return;  // every sample of the pass was NaN or infinite
  PixelState& st = states_[p];
  // West's weighted incremental mean and spread: a pass of n samples and mean m has weight n.
  const double w = static_cast<double>(st.count) + n;
  const glm::dvec3 delta = m - st.mean;
  st.mean += delta * (n / w);
  st.spread += n * delta * (m - st.mean);
  if (st.passes == 0) st.first_m2 = m2;
  ++st.passes;
  st.count += static_cast<std::uint32_t>(n);
  double* sum = &sums_[p * sum_stride()];
  for (std::size_t i = 0; i < kAovSums + extras_; ++i) sum[i] += s[i];
  if (ids_) {
    // The pass's slots in slot order (the order its samples first saw them).
    for (std::size_t k = 0; k < 2; ++k) {
      double* to = sum + kAovSums + extras_ + k * kIdSlots;
      const double* from = s + kAovSums + extras_ + k * kIdSlots;
      for (std::size_t i = 0; i < kIdSlots && from[i] != 0.0; ++i)
        add_to_slots(to, slot_id(from[i]), slot_samples(from[i]));
    }
  }
}

void Film::add_pass(std::size_t p, const PixelAccumulator& a) {
  if (keep_records_) {
    const std::size_t r = record_size();
    double* rec =
        &records_[static_cast<std::size_t>(next_pass_ - pass_begin_) * r * states_.size() + p * r];
    rec[0] = a.count();
    for (int c = 0; c < 3; ++c) rec[1 + c] = a.mean()[c];
    for (int c = 0; c < 3; ++c) rec[4 + c] = a.m2()[c];
    std::copy(a.sums().begin(), a.sums().end(), rec + 7);
  }
  fold(p, a.count(), a.mean(), a.m2(), a.sums().data());
}

void Film::fold_record(std::size_t p, const double* rec) {
  fold(p, rec[0], glm::dvec3(rec[1], rec[2], rec[3]), glm::dvec3(rec[4], rec[5], rec[6]), rec + 7);
}

double Film::relative_error(std::size_t p) const {
  const PixelState& st = states_[p];
  if (st.passes < 2) return HUGE_VAL;
  double worst = 0.0;
  for (int c = 0; c < 3; ++c) {
    const double var = st.spread[c] / (double(st.passes - 1) * double(st.count));
    worst = std::max(worst, std::sqrt(var) / std::max(std::fabs(st.mean[c]), kRelativeErrorFloor));
  }
  return worst;
}

void Film::begin_pass() {
  // Zero records for every pixel: a pixel that takes no samples folds nothing from its record.
  if (keep_records_) {
    records_.resize(
        static_cast<std::size_t>(next_pass_ - pass_begin_ + 1) * record_size() * states_.size(),
        0.0);
  }
}

void Film::finish_pass(const AdaptiveSettings& adaptive) {
  ++next_pass_;
  if (adaptive.noise_threshold <= 0) return;
  // A pixel's own estimate has only passes - 1 degrees of freedom and is often far too low by
  // chance, so a pixel stops only when it and its 8 neighbours are all at the threshold (as
  // Cycles dilates its convergence mask). Pixels already stopped count as converged.
  const int w = window_.width(), h = window_.height();
  std::vector<unsigned char> converged(states_.size(), 0);
  for (std::size_t p = 0; p < states_.size(); ++p) {
    const PixelState& st = states_[p];
    converged[p] =
        st.done || (st.passes >= 2 && st.count >= static_cast<std::uint32_t>(adaptive.min_spp) &&
                    relative_error(p) <= adaptive.noise_threshold);
  }
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const std::size_t p = static_cast<std::size_t>(y) * w + x;
      if (states_[p].done || !converged[p]) continue;
      bool all = true;
      for (int dy = -1; dy <= 1 && all; ++dy) {
        for (int dx = -1; dx <= 1 && all; ++dx) {
          const int nx = x + dx, ny = y + dy;
          if (nx >= 0 && ny >= 0 && nx < w && ny < h)
            all = converged[static_cast<std::size_t>(ny) * w + nx] != 0;
        }
      }
      if (all) states_[p].done = 1;
    }
  }
}

imaging::Image Film::image(std::size_t extras_wanted) const {
  imaging::Image img = make_image(window_.width(), window_.height(), extras_wanted);
  img.x0 = window_.x0;
  img.y0 = window_.y0;
  const std::size_t stride = sum_stride();
  if (ids_) {
    img.id_slots = kIdSlots;
    img.object_ids.assign(states_.size() * kIdSlots, 0u);
    img.material_ids.assign(states_.size() * kIdSlots, 0u);
    img.object_cover.assign(states_.size() * kIdSlots, 0.0f);
    img.material_cover.assign(states_.size() * kIdSlots, 0.0f);
  }
  for (std::size_t p = 0; p < states_.size(); ++p) {
    const PixelState& st = states_[p];
    img.samples[p] = static_cast<float>(st.count);
    if (st.count == 0) continue;
    const double n = st.count;
    img.beauty[p] = glm::vec3(st.mean);
    // Across passes: Σ n_p (m_p − m)² / ((P − 1) N), unbiased for the variance of the mean when
    // a pass mean's variance is σ²/n_p. One pass: the sample variance / n (overstated for QMC).
    if (st.passes >= 2) {
      img.variance[p] = glm::vec3(st.spread / (double(st.passes - 1) * n));
    } else if (st.count > 1) {
      img.variance[p] = glm::vec3(st.first_m2 / ((n - 1.0) * n));
    }
    const double* s = &sums_[p * stride];
    img.albedo[p] = glm::vec3(s[0] / n, s[1] / n, s[2] / n);
    img.normal[p] = glm::vec3(s[3] / n, s[4] / n, s[5] / n);
    img.depth[p] = static_cast<float>(s[6] / n);
    img.alpha[p] = static_cast<float>(s[7] / n);
    if (ids_) {
      for (std::size_t k = 0; k < 2; ++k) {
        std::array<double, kIdSlots> slots;
        std::copy_n(s + kAovSums + extras_ + k * kIdSlots, kIdSlots, slots.begin());
        // Most samples first, then the lower id; empty slots (0) last.
        std::sort(slots.begin(), slots.end(), [](double a, double b) {
          if ((a == 0.0) != (b == 0.0)) return b == 0.0;
          if (slot_samples(a) != slot_samples(b)) return slot_samples(a) > slot_samples(b);
          return slot_id(a) < slot_id(b);
        });
        std::uint32_t* ids = (k == 0 ? img.object_ids : img.material_ids).data() + p * kIdSlots;
        float* cover = (k == 0 ? img.object_cover : img.material_cover).data() + p * kIdSlots;
        for (std::size_t i = 0; i < kIdSlots && slots[i] != 0.0; ++i) {
          ids[i] = slot_id(slots[i]);
          cover[i] = static_cast<float>(slot_samples(slots[i]) / n);
        }
      }
    }
    for (std::size_t e = 0; e < extras_wanted; ++e) {
      img.extra[p * extras_wanted + e] = static_cast<float>(s[kAovSums + e] / n);
    }
  }
  return img;
}

}  // namespace arbor::tracer
