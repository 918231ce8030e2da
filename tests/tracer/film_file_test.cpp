// The film state file: what it writes reads back exactly; a state whose sums are not finite is
// refused even when its checksum matches (it was written that way, or forged with a checksum).
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "common/error.h"
#include "tracer/film_file.h"

namespace arbor::tracer {

namespace {

FilmHeader small_header() {
  FilmHeader h;
  h.fingerprint = "0123456789abcdef";
  h.scene = "scene.toml";
  h.full_width = 4;
  h.full_height = 3;
  h.plan = PassPlan{8, 4, false};
  h.pass_end = 2;
  return h;
}

Film small_film() {
  Film film(Window{0, 0, 4, 3}, 0, 0, false);
  film.begin_pass();
  for (std::size_t p = 0; p < 12; ++p) {
    PixelAccumulator acc(0, false);
    for (int s = 0; s < 4; ++s) {
      const float v = 0.1f * float(p + s), rgb[3] = {v, v, v}, albedo[3] = {0.5f, 0.5f, 0.5f};
      acc.add(rgb, albedo, glm::vec3(0.0f, 0.0f, 1.0f), 1.0f, 1.0f, nullptr, 0, 0);
    }
    film.add_pass(p, acc);
  }
  film.finish_pass({});
  return film;
}

}  // namespace

TEST(FilmFile, WritesAndReadsBackExactly) {
  const std::string path = ::testing::TempDir() + "film_file_exact.state";
  const Film film = small_film();
  write_film_state(path, small_header(), film);
  const FilmFile back = read_film_state(path);
  EXPECT_EQ(back.film->sums(), film.sums());
  ASSERT_EQ(back.film->states().size(), film.states().size());
  for (std::size_t p = 0; p < film.states().size(); ++p)
    EXPECT_EQ(back.film->state(p).mean, film.state(p).mean);
}

TEST(FilmFile, NonFiniteSumsAreRefusedEvenWithAGoodChecksum) {
  for (const double bad :
       {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    const std::string path = ::testing::TempDir() + "film_file_nan.state";
    Film film = small_film();
    film.sums()[5] = bad;
    write_film_state(path, small_header(), film);
    try {
      read_film_state(path);
      FAIL() << "a state with a non-finite sum was read";
    } catch (const InputError& e) {
      EXPECT_EQ(e.where().path, path);
      EXPECT_NE(e.message().find("not a finite number"), std::string::npos) << e.message();
    }
    Film mean = small_film();
    mean.states()[3].mean.y = bad;
    write_film_state(path, small_header(), mean);
    EXPECT_THROW(read_film_state(path), InputError);
  }
}

}  // namespace arbor::tracer
